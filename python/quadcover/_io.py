"""quadcover.read / quadcover.write: meshes by file extension. OBJ, OFF, PLY and STL are read by the extension's
reader (with its located errors); other formats through meshio (Debian python3-meshio) when it is installed. Writes
are atomic (a temporary file in the same folder, then a rename): a failed write leaves no partial file."""
import os
import tempfile

import numpy as np

from . import _quadcover
from ._api import Mesh, as_arrays

NATIVE_FORMATS = (".obj", ".off", ".ply", ".stl")


def _meshio():
    try:
        import meshio
    except ImportError as e:
        raise ValueError("this format needs meshio (Debian: apt-get install python3-meshio); quadcover itself reads "
                         + " ".join(NATIVE_FORMATS)) from e
    return meshio


def meshio_faces(m):
    """The surface faces of a meshio.Mesh: triangle, quad and polygon cells, as a list of index lists."""
    faces = []
    for block in m.cells:
        if block.type in ("triangle", "quad") or block.type.startswith("polygon"):
            faces.extend(np.asarray(block.data).tolist())
    if not faces:
        raise ValueError("the file has no surface cells (triangle, quad or polygon); cell types: "
                         + ", ".join(sorted({b.type for b in m.cells})))
    return faces


def read(path):
    """Reads a mesh: a :class:`quadcover.Mesh` with ``vertices``, ``faces`` (#F×3 array for triangle meshes, else a
    list of polygons) and, from OBJ, ``uv``/``face_uv``. Raises ValueError naming the file (and line) on bad input."""
    path = os.fspath(path)
    if os.path.splitext(path)[1].lower() in NATIVE_FORMATS:
        d = _quadcover.load(path)
        return Mesh(d["V"], d["F"], d["uv"], d["face_uv"])
    meshio = _meshio()
    if not os.path.exists(path):
        raise ValueError(f"{path}: no such file")
    try:
        m = meshio.read(path)
    except Exception as e:  # meshio raises its own ReadError, KeyError, ...
        raise ValueError(f"{path}: meshio cannot read it: {e}") from e
    faces = meshio_faces(m)
    if all(len(f) == 3 for f in faces):
        faces = np.asarray(faces, dtype=np.int32).reshape(-1, 3)
    return Mesh(np.asarray(m.points, dtype=np.float64)[:, :3], faces)


def _face_lists(faces):
    return faces.tolist() if isinstance(faces, np.ndarray) else [list(map(int, f)) for f in faces]


def _write_obj(f, V, faces, uv):
    for p in V:
        f.write("v %r %r %r\n" % tuple(float(x) for x in p))
    if uv is None:
        for face in faces:
            f.write("f " + " ".join(str(i + 1) for i in face) + "\n")
        return
    uv = np.asarray(uv, dtype=np.float64)
    if uv.ndim == 3:  # per corner (#F×k×2, as parameterize returns): one vt per corner
        corner = 0
        for c in uv.reshape(-1, 2):
            f.write("vt %r %r\n" % (float(c[0]), float(c[1])))
        for face in faces:
            f.write("f " + " ".join(f"{i + 1}/{corner + k + 1}" for k, i in enumerate(face)) + "\n")
            corner += len(face)
    else:  # per vertex (#V×2)
        for c in uv:
            f.write("vt %r %r\n" % (float(c[0]), float(c[1])))
        for face in faces:
            f.write("f " + " ".join(f"{i + 1}/{i + 1}" for i in face) + "\n")


def _write_off(f, V, faces):
    f.write(f"OFF\n{len(V)} {len(faces)} 0\n")
    for p in V:
        f.write("%r %r %r\n" % tuple(float(x) for x in p))
    for face in faces:
        f.write(f"{len(face)} " + " ".join(map(str, face)) + "\n")


def _write_ply(f, V, faces):
    header = ("ply\nformat binary_little_endian 1.0\ncomment quadcover\n"
              f"element vertex {len(V)}\nproperty double x\nproperty double y\nproperty double z\n"
              f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    f.write(header.encode("ascii"))
    f.write(np.ascontiguousarray(V, dtype="<f8").tobytes())
    for face in faces:
        f.write(np.uint8(len(face)).tobytes() + np.asarray(face, dtype="<i4").tobytes())


def write(path, V, faces=None, uv=None):
    """Writes a mesh by extension: .obj (with ``uv``: per-corner #F×k×2 as parameterize returns, or per-vertex
    #V×2), .off, .ply (binary), anything else through meshio. ``V`` may be a mesh-like object instead of V, faces.
    Atomic: on failure no file (and no partial file) is left at ``path``."""
    path = os.fspath(path)
    if faces is None:
        if hasattr(V, "vertices") and hasattr(V, "faces"):
            V, faces = V.vertices, V.faces
        else:
            V, faces = as_arrays(V)
    V = np.asarray(V, dtype=np.float64)
    face_lists = _face_lists(faces)
    n = len(V)
    for k, face in enumerate(face_lists):
        if len(face) < 3 or min(face) < 0 or max(face) >= n:
            raise ValueError(f"{path}: face {k} has a vertex index out of range [0, {n}) or fewer than 3 vertices")
    ext = os.path.splitext(path)[1].lower()
    if uv is not None and ext != ".obj":
        raise ValueError(f"{path}: texture coordinates are written to .obj only")
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp" + ext, dir=folder)
    try:
        if ext in (".obj", ".off"):
            with os.fdopen(fd, "w") as f:
                (_write_obj(f, V, face_lists, uv) if ext == ".obj" else _write_off(f, V, face_lists))
        elif ext == ".ply":
            with os.fdopen(fd, "wb") as f:
                _write_ply(f, V, face_lists)
        else:
            os.close(fd)
            meshio = _meshio()
            sizes = {len(face) for face in face_lists}
            cells = ([({3: "triangle", 4: "quad"}.get(s, f"polygon{s}"),
                       [face for face in face_lists if len(face) == s]) for s in sorted(sizes)])
            meshio.write(tmp, meshio.Mesh(V, cells), file_format=meshio.extension_to_filetypes[ext][0]
                         if ext in meshio.extension_to_filetypes else None)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
