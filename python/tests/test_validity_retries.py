"""validity_retries= of parameterize() / remesh(): the CLI's --retries (pipeline/validity_retries.h). It reaches the
job (the report's options and validity_retries), every attempt is reported with its density and validity, the kept
one is the job's result, and a count outside [0, 8] is a ValueError before any work."""
import numpy as np
import pytest

import quadcover
from test_fold_refinement import torus


def test_validity_retries_reach_the_job_and_every_attempt_is_reported():
    V, F = torus(24, 6, R=1.0, r=0.08)  # a tube under three quad edges at 100 quads: no density keeps it
    QV, Q, report = quadcover.remesh(V, F, faces=100, validity_retries=2)
    assert report["options"]["validity_retries"] == 2
    attempts = report["validity_retries"]["attempts"]
    # The default field on a closed surface: the smoothest first, then the curvature-guided one (not valid either),
    # the full optimization, then the two density retries with the field and optimization of the best of those.
    assert [round(a["quads_factor"], 2) for a in attempts] == [1.0, 1.0, 1.0, 1.02, 0.98]
    assert [a["field"] for a in attempts[:2]] == ["smooth", "curvature"]
    assert [a["optimize"] for a in attempts[:3]] == ["relocate", "relocate", "full"]
    assert attempts[3]["field"] == attempts[4]["field"]
    assert attempts[3]["optimize"] == attempts[4]["optimize"]
    assert report["options"]["field"] == attempts[report["validity_retries"]["used"]]["field"]
    assert report["options"]["field_auto"]
    assert all(a["topology_changes"] == 1 and not a["valid"] for a in attempts)
    assert all(a["seconds"] > 0 for a in attempts)
    kept = attempts[report["validity_retries"]["used"]]
    assert kept["non_quads"] == report["surface_check"]["output"]["non_quads"]
    assert kept["edge_length"] == pytest.approx(report["edge_length"])
    assert any("topology changed" in w for w in report["warnings"])


def test_no_retries_means_one_attempt():
    V, F = torus(24, 6, R=1.0, r=0.08)
    _, _, report = quadcover.remesh(V, F, faces=100, validity_retries=0)
    assert len(report["validity_retries"]["attempts"]) == 1
    assert any("retries off" in w for w in report["warnings"])


def test_a_clean_map_has_one_valid_attempt():
    V, F = torus(40, 16)
    result = quadcover.parameterize(V, F, quads=400)
    assert result.report["options"]["validity_retries"] == 1
    assert result.report["validity_retries"]["attempts"][0]["valid"]
    assert result.report["parameterization"]["wrong_windings"] == 0


@pytest.mark.parametrize("bad", [-1, 9])
def test_a_count_outside_the_range_is_refused(bad):
    V, F = torus()
    with pytest.raises(ValueError, match="validity_retries"):
        quadcover.parameterize(V, F, validity_retries=bad)
    with pytest.raises(ValueError, match="validity_retries"):
        quadcover.remesh(V, F, validity_retries=bad)
