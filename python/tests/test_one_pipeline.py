"""The Python module runs the library's jobs (src/pipeline/): the same checks as the CLI, the same report document
as the CLI's --report JSON and the HTML page's data, and a progress callback that can cancel."""
import html
import json
import os
import re
import subprocess
import tempfile

import numpy as np
import pytest

import quadcover

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
DATA = os.path.join(ROOT, "tests", "data")
CLI = os.environ.get("QUADCOVER_CLI", os.path.join(ROOT, os.environ.get("QUADCOVER_PY_BUILD", "build"), "quadcover"))


def mesh(name):
    d = quadcover.load(os.path.join(DATA, name + ".obj"))
    return d["V"], d["F"]


def without_costs(j):
    """j without its "seconds" and "memory" keys at every depth (as tests/e2e/e2e.py strip_timing)."""
    if isinstance(j, dict):
        return {k: without_costs(v) for k, v in j.items() if k not in ("seconds", "memory")}
    if isinstance(j, list):
        return [without_costs(v) for v in j]
    return j


def strip(report):
    """The report without what differs between two runs or two callers: timings, memory peaks and file names."""
    r = without_costs(json.loads(json.dumps(report)))
    for key in ("input", "output"):
        r.pop(key, None)
    return r


def test_cli_json_python_dict_and_html_page_are_one_report():
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(DATA, "eight_genus2.obj")
        rep, page = os.path.join(d, "r.json"), os.path.join(d, "r.html")
        subprocess.run([CLI, "param", src, "-o", os.path.join(d, "p.obj"), "--report", rep, "--report-html", page,
                        "-q"], check=True)
        cli = json.load(open(rep))
        text = open(page, encoding="utf-8").read()
        m = re.search(r'<script type="application/json" id="qc-data">(.*?)</script>', text, re.S)
        assert m, "the page carries its data"
        data = json.loads(m.group(1).replace("<\\/", "</"))
        V, F = mesh("eight_genus2")
        _, py = quadcover.parameterize(V, F)
    assert cli["schema_version"] == py["schema_version"] == 1 and cli["job"] == py["job"] == "param"
    assert strip(cli) == strip(py)
    assert strip(data["report"]) == strip(cli)


def test_remesh_report_has_the_cli_shape():
    V, F = mesh("torus_5k")
    _, Q, report = quadcover.remesh(V, F, faces=800)
    assert report["job"] == "remesh" and report["mesh"]["faces"] == F.shape[0]
    assert report["quad_mesh"]["faces"] == len(Q)
    # faces= is the target quad count (the old name quads= still works): within a few percent on a torus.
    assert abs(len(Q) - 800) <= 0.03 * 800
    with pytest.raises(ValueError, match="once"):
        quadcover.remesh(V, F, faces=800, quads=900)


def test_boundary_quads_is_the_cli_option():
    V, F = mesh("lilium_disk")
    _, Q, made = quadcover.remesh(V, F)
    _, P, clipped = quadcover.remesh(V, F, boundary_quads=False)
    assert made["options"]["boundary_quads"] and not clipped["options"]["boundary_quads"]
    assert isinstance(Q, np.ndarray) and Q.shape[1] == 4  # all quads
    assert made["quad_mesh"]["non_quads"] == 0 < clipped["quad_mesh"]["non_quads"]
    assert sum(len(f) != 4 for f in P) == clipped["quad_mesh"]["non_quads"]
    assert made["surface_check"]["same_topology"] and clipped["surface_check"]["same_topology"]


def test_remesh_dict_has_a_memory_peak_per_timed_stage():
    V, F = mesh("bunny_3k")
    _, _, report = quadcover.remesh(V, F, faces=800)
    memory = report["memory"]
    assert memory["input_faces"] == F.shape[0]
    names = [s["stage"] for s in memory["stages"]]
    assert sorted(names) == sorted(report["seconds"]) and len(set(names)) == len(names)
    assert names.index("field") < names.index("extract") < names.index("metrics")  # pipeline order
    for s in memory["stages"]:
        if os.path.exists("/proc/self/status"):
            assert s["peak_bytes"] > 0, s
        assert s["peak_bytes"] <= memory["peak_bytes"], s
        assert s["bytes_per_face"] == int(s["peak_bytes"] / F.shape[0] + 0.5), s  # rounded half up


@pytest.mark.parametrize("bad_F,match", [
    (lambda F: F.astype(np.float64), "integer"),
    (lambda F: np.where(F == 0, 2**33, F).astype(np.int64), "out of range"),
    (lambda F: np.where(F == 0, -1, F), "out of range"),
    (lambda F: F[:, :2], "#F x 3"),
])
def test_face_arrays_are_checked_not_wrapped_or_truncated(bad_F, match):
    V, F = mesh("bunny_3k")
    for call in (quadcover.info, quadcover.parameterize):
        with pytest.raises(ValueError, match=match):
            call(V, bad_F(F))


def test_vertex_arrays_are_checked():
    V, F = mesh("bunny_3k")
    bad = V.copy()
    bad[5, 1] = np.nan
    with pytest.raises(ValueError, match="vertex 5 has a non-finite"):
        quadcover.info(bad, F)
    with pytest.raises(ValueError, match="#V x 3"):
        quadcover.info(V[:, :2], F)


def test_python_applies_the_cli_checks():
    V, F = mesh("bunny_3k")
    # A density whose map holds a handful of quads is refused (the CLI exits 2), not returned as triangles.
    with pytest.raises(ValueError, match="too few to extract"):
        quadcover.remesh(V, F, quads=3)
    with pytest.raises(ValueError, match="too few to extract"):
        quadcover.remesh(V, F, edge_length=1e6)
    with pytest.raises(ValueError, match="largest that fits"):
        quadcover.parameterize(V, F, quads=10**9)  # before any allocation, not a MemoryError minutes later
    with pytest.raises(ValueError, match="smooth_rigidity"):
        quadcover.remesh(V, F, smooth_rigidity=2.0)
    with pytest.raises(ValueError, match="either"):
        quadcover.parameterize(V, F, quads=100, edge_length=0.1)


def test_progress_callback_sees_the_stages_and_can_cancel():
    V, F = mesh("bunny_3k")
    seen = []
    quadcover.parameterize(V, F, progress=lambda stage, fraction, message: seen.append(stage))
    assert "optimize" in seen and "param" in seen
    with pytest.raises(RuntimeError, match="cancelled"):
        quadcover.remesh(V, F, progress=lambda stage, fraction, message: stage == "optimize")

    def boom(stage, fraction, message):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        quadcover.parameterize(V, F, progress=boom)
