"""quadcover: seamless quad-aligned parameterization (QuadCover) and quad remeshing.

The compiled extension ``quadcover._quadcover`` does the work on plain numpy arrays; this package adds the habits of
Python mesh code on top: :func:`read` / :func:`write` by file extension (meshio for formats beyond OBJ, OFF, PLY,
STL), any object with ``vertices`` and ``faces`` attributes (trimesh, a :class:`Mesh`, ...) where ``V, F`` are
expected, ``faces=`` as the target quad count and a ``progress`` callback on the long calls.
"""
from . import _quadcover
from ._quadcover import *  # noqa: F401,F403  (every function of the extension, as before)
from ._quadcover import __version__, load  # noqa: F401
from ._api import Cancelled, Mesh, accepts, as_arrays, field, info, parameterize, remesh  # noqa: F401
from ._io import read, write  # noqa: F401
from ._cli import cli_path  # noqa: F401

__all__ = ["Cancelled", "Mesh", "accepts", "as_arrays", "cli_path", "field", "info", "load", "parameterize",
           "read", "remesh", "write", "__version__"]
