"""The pure-Python layer over the extension: mesh-like inputs, the density vocabulary (faces= / edge_length=), a
progress callback and cancellation, passed to the extension only where it has them (feature-detected)."""
import inspect
import re
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from . import _quadcover


@dataclass
class Mesh:
    """A mesh as :func:`quadcover.read` returns it: ``vertices`` #V×3 float, ``faces`` #F×3 int array (triangles)
    or a list of polygons; ``uv`` / ``face_uv`` the texture coordinates of the file, when it has them."""

    vertices: np.ndarray
    faces: Any
    uv: Optional[np.ndarray] = None
    face_uv: Optional[list] = None

    def __iter__(self):  # V, F = mesh
        return iter((self.vertices, self.faces))


_native_cancelled = getattr(_quadcover, "Cancelled", None)
if isinstance(_native_cancelled, type) and issubclass(_native_cancelled, BaseException):
    Cancelled = _native_cancelled
else:

    class Cancelled(RuntimeError):
        """Raised when a ``progress`` callback returned True (the call stopped without a result)."""


def accepts(function, name):
    """True if ``function`` (a Python or pybind11 function) takes the keyword argument ``name``."""
    try:
        return name in inspect.signature(function).parameters
    except (TypeError, ValueError):  # pybind11: the signatures are the first lines of the docstring
        doc = getattr(function, "__doc__", None) or ""
        return re.search(r"[(,]\s*" + re.escape(name) + r"\s*:", doc) is not None


def _faces_array(faces):
    """Triangles for the extension. A #F×3 (or other non-polygon) array is passed on as it is, so the extension's
    own checks (integer type, index range, shape) see it unchanged; polygons (lists of any length, or #F×k arrays
    with k > 3) are split into fans (fine for convex ones: triangulate concave n-gons first)."""
    if isinstance(faces, np.ndarray) and (faces.ndim != 2 or faces.shape[1] <= 3):
        return faces
    tris = []
    for f in faces:
        f = [int(i) for i in f]
        if len(f) < 3:
            raise ValueError(f"face {len(tris)}: a face needs at least 3 vertices, got {len(f)}")
        tris.extend([f[0], f[k], f[k + 1]] for k in range(1, len(f) - 1))
    return np.asarray(tris, dtype=np.int64).reshape(-1, 3)


def as_arrays(mesh, F=None):
    """(V #V×3, F #F×3) for the extension from V, F arrays or from one mesh-like object: anything with
    ``vertices`` and ``faces`` (trimesh, :class:`Mesh`) or ``triangles`` (open3d) attributes, a meshio.Mesh, or
    :func:`load`'s dict."""
    if F is None:
        if isinstance(mesh, dict) and "V" in mesh:
            mesh, F = mesh["V"], mesh["F"]
        elif hasattr(mesh, "vertices") and (hasattr(mesh, "faces") or hasattr(mesh, "triangles")):
            F = mesh.faces if hasattr(mesh, "faces") else mesh.triangles
            mesh = mesh.vertices
        elif hasattr(mesh, "points") and hasattr(mesh, "cells"):  # meshio
            from ._io import meshio_faces

            mesh, F = mesh.points, meshio_faces(mesh)
        else:
            raise TypeError("expected V, F arrays or a mesh with 'vertices' and 'faces' attributes, got "
                            + type(mesh).__name__)
    V = mesh if isinstance(mesh, np.ndarray) else np.asarray(mesh, dtype=np.float64)  # arrays: checked natively
    if not isinstance(F, (list, tuple, np.ndarray)):
        F = np.asarray(F)  # e.g. open3d's Vector3iVector
    return V, _faces_array(F)


def _density_and_progress(function, kwargs, progress, faces):
    """Adds faces= (or its older name quads=) and progress= to kwargs as the extension takes them."""
    if faces is not None:
        if accepts(function, "faces"):  # the extension checks faces= against quads= itself
            kwargs["faces"] = faces
        else:
            if "quads" in kwargs and kwargs["quads"] not in (0, faces):
                raise ValueError("give the target quad count once (faces= or its alias quads=), not both")
            kwargs["quads"] = int(faces)
    native_progress = progress is not None and accepts(function, "progress")
    if native_progress:
        kwargs["progress"] = progress
    return native_progress


def _call(function, stage, mesh, F, progress, faces, kwargs):
    V, F = as_arrays(mesh, F)
    native_progress = _density_and_progress(function, kwargs, progress, faces)
    if progress is not None and not native_progress and progress(stage, 0.0, "started"):
        raise Cancelled("cancelled")
    try:
        result = function(V, F, **kwargs)
    except Cancelled:
        raise
    except RuntimeError as e:
        if "cancel" in str(e).lower():
            raise Cancelled(str(e)) from e
        raise
    if progress is not None and not native_progress:
        progress(stage, 1.0, "done")
    return result


def info(mesh, F=None):
    """Counts and topology (dict): see ``quadcover._quadcover.info``; ``mesh`` as in :func:`as_arrays`."""
    return _quadcover.info(*as_arrays(mesh, F))


def field(mesh, F=None, **kwargs):
    """Cross field (dict): see ``quadcover._quadcover.field``; ``mesh`` as in :func:`as_arrays`."""
    return _quadcover.field(*as_arrays(mesh, F), **kwargs)


class ParamResult(tuple):
    """``(uv, report)`` of :func:`parameterize`, with ``.V`` and ``.F``: the triangulation ``uv`` lives on. That is
    the input's, or, when the curve constraints or the fold refinement needed it, a refinement of it: the input's
    vertices first (same numbers), then the midpoints of ``report["refinement"]["split"]``;
    ``report["refinement"]`` says how many, ``report["fold_refinement"]`` what the fold refinement did."""

    def __new__(cls, uv, report, V, F):
        result = super().__new__(cls, (uv, report))
        result.V, result.F = V, F
        return result

    @property
    def uv(self):
        return self[0]

    @property
    def report(self):
        return self[1]


def parameterize(mesh, F=None, *, faces=None, progress=None, **kwargs):
    """Seamless QuadCover parameterization: returns (uv #F'×3×2, report) as a :class:`ParamResult` whose ``.V``,
    ``.F`` are the triangulation of uv (the input's unless the report's ``refinement`` split edges). ``mesh``: V
    (with F) or a mesh-like object (see :func:`as_arrays`). ``faces``: target quad count (alias ``quads``), or
    ``edge_length``. ``progress(stage, fraction, message)`` is called as the stages run; returning True cancels
    (:class:`Cancelled`). Other keywords as in the extension (``help(quadcover._quadcover.parameterize)``)."""
    return ParamResult(*_call(_quadcover.parameterize, "parameterize", mesh, F, progress, faces, kwargs))


def remesh(mesh, F=None, *, faces=None, progress=None, **kwargs):
    """Quad remeshing: returns (QV #Q×3, quad faces, report); faces is #faces×4 when every face is a quad. Inputs,
    ``faces``, ``progress`` as in :func:`parameterize`; other keywords as in the extension
    (``help(quadcover._quadcover.remesh)``: optimize, field, smooth_quads, ...)."""
    return _call(_quadcover.remesh, "remesh", mesh, F, progress, faces, kwargs)
