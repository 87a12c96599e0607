"""Where the quadcover command-line tool is: the one installed inside this package (pip install), the build tree's
(when the package was built by CMake), or QUADCOVER_CLI / PATH."""
import os
import shutil

HERE = os.path.dirname(os.path.abspath(__file__))


def cli_path():
    """Path of the quadcover executable. Order: $QUADCOVER_CLI, the package's bin/quadcover (pip install), the
    CMake build tree the package was built in, `quadcover` on PATH. Raises FileNotFoundError if none exists."""
    candidates = [os.environ.get("QUADCOVER_CLI"), os.path.join(HERE, "bin", "quadcover")]
    try:
        from ._build_paths import CLI

        candidates.append(CLI)
    except ImportError:
        pass
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    found = shutil.which("quadcover")
    # A pip-installed console script `quadcover` is this package's own launcher: only a real binary will do.
    if found and not _is_python_launcher(found):
        return found
    raise FileNotFoundError("the quadcover command-line tool was not found: set QUADCOVER_CLI, build the `quadcover` "
                            "CMake target, or pip install the package")


def _is_python_launcher(path):
    try:
        with open(path, "rb") as f:
            return f.read(2) == b"#!"
    except OSError:
        return True


def main(argv=None):
    """Runs the CLI with argv (default: this process's arguments), replacing the Python process."""
    import sys

    exe = cli_path()
    args = sys.argv[1:] if argv is None else list(argv)
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(exe, [exe] + args)
