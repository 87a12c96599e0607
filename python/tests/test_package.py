"""The pure-Python layer of the quadcover package: read/write round trips by extension (meshio for other formats),
mesh-like objects, faces= and progress= on the long calls, and `python3 -m quadcover` running the CLI."""
import os
import subprocess
import sys

import numpy as np
import pytest

import quadcover

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data")
BUNNY = os.path.join(DATA, "bunny_3k.obj")


def quad_grid(n=3):
    """An n×n grid of unit quads in the plane z = 0 (a polygon mesh with known counts)."""
    V = np.array([[i, j, 0.0] for j in range(n + 1) for i in range(n + 1)])
    Q = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i]
         for j in range(n) for i in range(n)]
    return V, Q


def test_read_returns_a_mesh_with_vertices_and_faces():
    m = quadcover.read(BUNNY)
    d = quadcover.load(BUNNY)
    np.testing.assert_array_equal(m.vertices, d["V"])
    np.testing.assert_array_equal(m.faces, d["F"])
    V, F = m  # unpacks like the (V, F) pair
    assert V.shape == (1839, 3) and F.shape == (3674, 3)


@pytest.mark.parametrize("ext", [".obj", ".off", ".ply"])
def test_write_then_read_round_trips_positions_and_polygons(tmp_path, ext):
    V, Q = quad_grid()
    V = V + np.array([0.1, 1e-17, 1 / 3])  # numbers that need every digit
    path = tmp_path / ("grid" + ext)
    quadcover.write(path, V, Q)
    m = quadcover.read(path)
    np.testing.assert_array_equal(m.vertices, V)  # exact: shortest round-trip text / binary doubles
    assert [list(f) for f in m.faces] == Q
    assert [p.name for p in tmp_path.iterdir()] == [path.name]  # no temporary file left


def test_write_obj_with_per_corner_uv_reads_back(tmp_path):
    V, F = quadcover.read(BUNNY)
    result = quadcover.parameterize(V, F, faces=300, optimize="none", stiffening=0, relaxation=0)
    uv, report = result
    # uv lives on result.V, result.F: the input's vertices first, unchanged, then one midpoint per split edge, each
    # split adding two triangles (the report's refinement says how many).
    added = report["refinement"]["added_vertices"]
    assert result.V.shape == (len(V) + added, 3) and result.F.shape == (len(F) + 2 * added, 3)
    np.testing.assert_array_equal(result.V[: len(V)], V)
    assert uv.shape == (len(result.F), 3, 2) and result.uv is uv and result.report is report
    path = tmp_path / "param.obj"
    quadcover.write(path, result.V, result.F, uv=uv)
    m = quadcover.read(path)
    assert m.uv.shape == (3 * len(result.F), 2)
    # Each face's corners point at its own three vt lines, in order.
    np.testing.assert_allclose(m.uv[np.asarray(m.face_uv)], uv, rtol=0, atol=0)


def test_write_rejects_bad_indices_and_leaves_no_file(tmp_path):
    V, Q = quad_grid()
    with pytest.raises(ValueError, match="face 1"):
        quadcover.write(tmp_path / "bad.obj", V, [Q[0], [0, 1, 99]])
    assert list(tmp_path.iterdir()) == []


def test_read_names_the_file_on_bad_input(tmp_path):
    bad = tmp_path / "broken.obj"
    bad.write_text("v 0 0 0\nv 1 zero 0\n")
    with pytest.raises(ValueError, match="broken.obj"):
        quadcover.read(bad)


class TrimeshLike:
    """What trimesh (and similar libraries) hand over: attributes, not a tuple."""

    def __init__(self, V, F):
        self.vertices, self.faces = V, F


def test_mesh_like_objects_give_the_same_result_as_arrays():
    V, F = quadcover.read(BUNNY)
    kw = dict(faces=300, optimize="none", stiffening=0, relaxation=0)
    uv_arrays, _ = quadcover.parameterize(V, F, **kw)
    for obj in (TrimeshLike(V, F), quadcover.read(BUNNY), quadcover.load(BUNNY), TrimeshLike(V.tolist(), F.tolist())):
        uv, _ = quadcover.parameterize(obj, **kw)
        np.testing.assert_array_equal(uv, uv_arrays)  # deterministic and the same input
    assert quadcover.info(*quadcover.as_arrays(TrimeshLike(V, F)))["faces"] == len(F)
    with pytest.raises(TypeError, match="vertices"):
        quadcover.remesh(object())


def test_polygon_faces_are_split_into_triangles():
    V, Q = quad_grid(2)
    V2, T = quadcover.as_arrays(V, Q)
    assert T.shape == (2 * len(Q), 3)
    np.testing.assert_array_equal(quadcover.as_arrays(V, np.array(Q))[1], T)  # a #F×4 array: the same fans
    # Same covered area as the quads: 4 unit squares.
    area = 0.5 * np.linalg.norm(np.cross(V2[T[:, 1]] - V2[T[:, 0]], V2[T[:, 2]] - V2[T[:, 0]]), axis=1).sum()
    assert area == pytest.approx(4.0)


def test_faces_is_the_target_quad_count_and_quads_still_works():
    m = quadcover.read(BUNNY)
    kw = dict(optimize="none", stiffening=0, relaxation=0)
    uv_faces, r1 = quadcover.parameterize(m, faces=500, **kw)
    uv_quads, r2 = quadcover.parameterize(m, quads=500, **kw)
    np.testing.assert_array_equal(uv_faces, uv_quads)
    assert r1["edge_length"] == r2["edge_length"]
    with pytest.raises(ValueError, match="once"):
        quadcover.parameterize(m, faces=500, quads=800, **kw)


def test_progress_is_called_and_cancel_raises_cancelled():
    m = quadcover.read(BUNNY)
    calls = []

    def progress(stage, fraction, message):
        assert isinstance(stage, str) and (0.0 <= fraction <= 1.0 or fraction == -1.0) and isinstance(message, str)
        calls.append((stage, fraction))
        return False

    QV, Q, report = quadcover.remesh(m, faces=300, progress=progress, optimize="none")
    assert calls and len(Q) > 100
    with pytest.raises(quadcover.Cancelled):
        quadcover.remesh(m, faces=300, progress=lambda *a: True, optimize="none")
    assert issubclass(quadcover.Cancelled, RuntimeError)


def test_accepts_reads_pybind11_signatures():
    native = quadcover._quadcover
    assert quadcover.accepts(native.remesh, "smooth_quads")
    assert quadcover.accepts(native.remesh, "edge_length")
    assert not quadcover.accepts(native.remesh, "no_such_option")
    assert quadcover.accepts(lambda a, b=1: None, "b")


def test_meshio_formats_read_and_write(tmp_path):
    meshio = pytest.importorskip("meshio", reason="python3-meshio (scripts/setup.sh --tests installs it)")
    V, F = quadcover.read(BUNNY)
    path = tmp_path / "bunny.vtk"
    quadcover.write(path, V, F)
    m = quadcover.read(path)
    np.testing.assert_allclose(m.vertices, V)
    np.testing.assert_array_equal(m.faces, F)
    assert isinstance(meshio.read(str(path)), meshio.Mesh)
    assert quadcover.info(m.vertices, m.faces)["genus"] == 0


def test_python_m_quadcover_runs_the_cli(tmp_path):
    out = tmp_path / "b.quad.obj"
    r = subprocess.run([sys.executable, "-m", "quadcover", "remesh", BUNNY, "-o", str(out), "-q", "--optimize",
                        "none"], capture_output=True, text=True, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    m = quadcover.read(out)
    assert len(m.faces) > 100 and all(len(f) == 4 for f in m.faces)
    bad = subprocess.run([sys.executable, "-m", "quadcover", "info", str(tmp_path / "none.obj")],
                         capture_output=True, text=True)
    assert bad.returncode != 0  # the CLI's own exit code comes through


def test_info_and_field_take_mesh_objects_and_new_extension_functions_are_exported():
    m = quadcover.read(os.path.join(DATA, "torus_5k.obj"))
    assert quadcover.info(m)["genus"] == 1
    assert quadcover.field(m)["X"].shape == (len(m.faces),)
    native = [n for n in dir(quadcover._quadcover) if not n.startswith("_")]
    assert native and all(hasattr(quadcover, n) for n in native)
