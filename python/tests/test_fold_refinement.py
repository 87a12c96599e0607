"""fold_refinement_rounds= of parameterize() / remesh(): the CLI's --refine-folds. It reaches the job (the report's
options and fold_refinement), 0 keeps the input's triangulation, a negative count is a ValueError before any work."""
import math

import numpy as np
import pytest

import quadcover


def torus(n_major=12, n_minor=6, R=2.0, r=0.7):
    """The coarse torus of the C++ tests (tests/support make_torus): at the default density, kept as it is
    (validity_retries=0: no finer default for a tube of under three quads around), its map needs the fold refinement."""
    V, F = [], []
    for i in range(n_major):
        for j in range(n_minor):
            u, v = 2 * math.pi * i / n_major, 2 * math.pi * j / n_minor
            V.append(((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u), r * math.sin(v)))
    idx = lambda i, j: (i % n_major) * n_minor + j % n_minor
    for i in range(n_major):
        for j in range(n_minor):
            F.append((idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)))
            F.append((idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)))
    return np.array(V), np.array(F, dtype=np.int64)


def test_fold_refinement_rounds_reaches_the_job():
    V, F = torus()
    default = quadcover.parameterize(V, F, validity_retries=0)
    assert default.report["options"]["fold_refinement_rounds"] == 6
    assert default.report["fold_refinement"]["rounds"] >= 1
    assert len(default.F) > len(F)  # the refined triangulation
    off = quadcover.parameterize(V, F, fold_refinement_rounds=0, validity_retries=0)
    assert off.report["options"]["fold_refinement_rounds"] == 0
    assert off.report["fold_refinement"]["rounds"] == 0
    assert len(off.F) == len(F) and off.uv.shape[0] == len(F)
    one = quadcover.parameterize(V, F, fold_refinement_rounds=1, validity_retries=0)
    assert one.report["fold_refinement"]["rounds"] == 1


def test_negative_rounds_are_a_value_error():
    V, F = torus()
    with pytest.raises(ValueError):
        quadcover.parameterize(V, F, fold_refinement_rounds=-1)
    with pytest.raises(ValueError):
        quadcover.remesh(V, F, fold_refinement_rounds=-1)
