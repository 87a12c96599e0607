"""feature_angle= and align_curves= of parameterize() / remesh(): the angle reaches the field stage (the report's
field.features), 'off' / 0 drops the sharp features but keeps the boundaries, bad values are ValueError before any
work, and the result equals the CLI's for the same options."""
import json
import os
import subprocess

import numpy as np
import pytest

import quadcover
from quadcover._cli import cli_path

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data")


def mesh(name):
    return quadcover.read(os.path.join(DATA, name + ".obj"))


def features(report):
    return report["field"]["features"]


def test_feature_angle_reaches_the_field_stage():
    fandisk = mesh("fandisk")
    _, at35 = quadcover.parameterize(fandisk, optimize="none")
    _, at80 = quadcover.parameterize(fandisk, optimize="none", feature_angle=80)
    _, off = quadcover.parameterize(fandisk, optimize="none", feature_angle="off")
    _, zero = quadcover.parameterize(fandisk, optimize="none", feature_angle=0.0)
    assert at35["options"]["feature_angle"] == 35 and at80["options"]["feature_angle"] == 80
    assert off["options"]["feature_angle"] == 0 and features(off) == features(zero)
    # fandisk is closed: without sharp features nothing is constrained or aligned.
    assert features(off)["sharp_edges"] == 0 and features(off)["constrained_faces"] == 0
    assert off["aligned_curves"]["curves"] == []
    # a larger angle keeps fewer (but some) sharp edges
    assert 0 < features(at80)["sharp_edges"] < features(at35)["sharp_edges"]
    assert features(at35)["constrained_faces"] > features(at35)["sharp_edges"]


# The curves are decided before the stages that repair the map's validity, which cost most of a camelhead run.
WITHOUT_REPAIRS = dict(optimize="none", merge_cones=False, move_cones=False, fold_refinement_rounds=0,
                       validity_retries=0)


def test_off_keeps_boundaries_and_align_curves_frees_them():
    camel = mesh("camelhead_boundary")
    _, _, aligned = quadcover.remesh(camel, feature_angle="off", **WITHOUT_REPAIRS)
    _, _, free = quadcover.remesh(camel, feature_angle="off", align_curves=False, **WITHOUT_REPAIRS)
    assert features(aligned)["constrained_faces"] > 0 and features(aligned)["boundaries"]
    assert aligned["aligned_curves"]["curves"] != []
    assert free["options"]["align_curves"] is False and free["aligned_curves"]["curves"] == []
    for curve in aligned["aligned_curves"]["curves"]:  # a free line says why, an enforced one has no reason
        assert (curve["left_free_because"] is None) == curve["enforced"]


@pytest.mark.parametrize("bad", [-1, 180.5, float("nan"), float("inf"), "abc", "35", True, None])
@pytest.mark.parametrize("job", [quadcover.parameterize, quadcover.remesh])
def test_bad_feature_angle_is_a_value_error(job, bad):
    with pytest.raises(ValueError, match="feature_angle"):
        job(mesh("fandisk"), feature_angle=bad)


def test_align_curves_takes_a_bool():
    with pytest.raises(TypeError):
        quadcover.parameterize(mesh("fandisk"), align_curves="yes")


def test_same_result_as_the_cli(tmp_path):
    path = os.path.join(DATA, "fandisk.obj")
    QV, _, report = quadcover.remesh(mesh("fandisk"), optimize="none", feature_angle=60, align_curves=False)
    out, rep = tmp_path / "q.obj", tmp_path / "q.json"
    subprocess.run([cli_path(), "remesh", path, "-o", str(out), "--optimize", "none", "--feature-angle", "60",
                    "--align", "false", "--report", str(rep), "-q"], check=True)
    cli = json.loads(rep.read_text())
    assert cli["options"] == report["options"] and cli["field"]["features"] == report["field"]["features"]
    assert np.allclose(quadcover.read(str(out)).vertices, QV, atol=1e-6)


def test_fill_propagate_reaches_the_field_stage():
    """fill= picks the thesis's trusted propagation (5.1.2) or the smooth fill (the default)."""
    bunny = mesh("bunny_3k")
    _, smooth = quadcover.parameterize(bunny, optimize="none")
    _, propagate = quadcover.parameterize(bunny, optimize="none", fill="propagate")
    assert smooth["options"]["fill"] == "smooth" and propagate["options"]["fill"] == "propagate"
    assert propagate["field"]["branch_points_initial"] > smooth["field"]["branch_points_initial"]
    with pytest.raises(ValueError):
        quadcover.parameterize(bunny, optimize="none", fill="flood")


def test_given_features_are_the_clis_features_file(tmp_path):
    """features= (vertex pairs, indices into V) gives the sharp edges as the CLI's --features FILE (counted from 1)."""
    fandisk = mesh("fandisk")
    F = np.asarray(fandisk.faces)
    pairs = np.unique(np.sort(np.concatenate([F[:40, [0, 1]], F[:40, [1, 2]]]), axis=1), axis=0)
    _, given = quadcover.parameterize(fandisk, optimize="none", features=pairs)
    assert features(given)["given_edges"] == len(pairs) == features(given)["sharp_edges"]
    assert given["options"]["feature_angle"] is None
    path, rep = tmp_path / "f.txt", tmp_path / "r.json"
    path.write_text("".join(f"{a + 1} {b + 1}\n" for a, b in pairs))
    subprocess.run([cli_path(), "param", os.path.join(DATA, "fandisk.obj"), "-o", str(tmp_path / "p.obj"),
                    "--optimize", "none", "--features", str(path), "--report", str(rep), "-q"], check=True)
    assert json.loads(rep.read_text())["field"]["features"] == features(given)
    _, none = quadcover.parameterize(fandisk, optimize="none", features=np.zeros((0, 2), dtype=int))
    assert features(none)["sharp_edges"] == 0 and features(none)["given_edges"] == 0


@pytest.mark.parametrize("bad, message", [([[0, 3000]], "not joined by an edge"), ([[0, 10 ** 7]], "not a vertex"),
                                          ([[0, 1, 2]], "#E×2"), ("edges", "#E×2"), ([[-1, 2]], "out of range")])
def test_bad_features_are_a_value_error(bad, message):
    with pytest.raises(ValueError, match=message):
        quadcover.parameterize(mesh("fandisk"), optimize="none", features=bad)
