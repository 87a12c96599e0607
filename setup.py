"""setuptools driving CMake (pyproject.toml names setuptools as the build backend): `pip install .` configures and
builds the `quadcover` (CLI) and `quadcover_python` (extension) targets, then installs the pure-Python package
python/quadcover with the extension and the CLI (quadcover/bin/quadcover) inside it.

QUADCOVER_BUILD_DIR=PATH reuses an existing CMake build tree (only out-of-date targets are rebuilt); otherwise a
Release build without tests and benchmarks is made in build/pip, configured with the extra options in CMAKE_ARGS
(e.g. "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"). CMAKE_BUILD_PARALLEL_LEVEL sets the jobs."""
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(quadcover VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("QUADCOVER_BUILD_DIR") or os.path.join(ROOT, "build", "pip")
        build = os.path.abspath(build)
        cache = os.path.join(build, "CMakeCache.txt")
        if not os.path.isfile(cache):
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.check_call(["cmake", "-S", ROOT, "-B", build, *generator, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DQUADCOVER_BUILD_PYTHON=ON", "-DQUADCOVER_BUILD_TESTS=OFF",
                                   "-DQUADCOVER_BUILD_BENCH=OFF", f"-DPython_EXECUTABLE={sys.executable}",
                                   *shlex.split(os.environ.get("CMAKE_ARGS", ""))])
        else:
            with open(cache) as f:
                has_module = "QUADCOVER_BUILD_PYTHON:BOOL=ON" in f.read()
            if not has_module:  # e.g. the build of scripts/setup.sh --main: add the module to it
                subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-DQUADCOVER_BUILD_PYTHON=ON",
                                       f"-DPython_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", build, "--target", "quadcover", "quadcover_python", "-j", jobs])
        package = os.path.join(build, "python", "quadcover")
        built = [f for f in os.listdir(package) if f.startswith("_quadcover") and f.endswith(".so")]
        if len(built) != 1:
            raise RuntimeError(f"expected one _quadcover*.so in {package}, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(package, built[0]), target)
        # The CLI inside the package: quadcover.cli_path() and `python3 -m quadcover` find it there.
        bin_dir = os.path.join(os.path.dirname(target), "bin")
        os.makedirs(bin_dir, exist_ok=True)
        shutil.copyfile(os.path.join(build, "quadcover"), os.path.join(bin_dir, "quadcover"))
        os.chmod(os.path.join(bin_dir, "quadcover"), 0o755)


os.makedirs(os.path.join(ROOT, "build", "setuptools"), exist_ok=True)
setup(
    version=version(),
    packages=["quadcover"],
    package_dir={"": "python"},
    ext_modules=[Extension("quadcover._quadcover", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build/setuptools"}},
    zip_safe=False,
)
