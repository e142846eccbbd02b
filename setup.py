"""setuptools entry of `pip install .` and `python3 -m build`: the pure-Python files of
src/python/tsrir as they are, and the extension tsrir._tsrir built by the project's own CMake for
the interpreter that runs this (its headers; numpy is only needed at run time). pyproject.toml
says how to run it offline.

Environment:
  TSRIR_BUILD_DIR   a CMake build tree of this source (e.g. build/, made by utils/bootstrap.sh) to
                    reuse: its module target is brought up to date and its extension is used, after
                    checking that the tree is this source's and was built for this interpreter's ABI.
                    Without it, a tree is configured in setuptools' build directory (LibTorch and
                    the tests off) and only the module target is built.
  TSRIR_CMAKE_ARGS  more CMake arguments for a new tree (as for utils/bootstrap.sh)
  TSRIR_BUILD_JOBS  parallel build jobs (default: all cores)
"""
import glob
import os
import shlex
import shutil
import subprocess
import sysconfig
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def cmake_cache(build_dir):
    """The CMakeCache.txt entries of a build tree: {name: value}."""
    entries = {}
    with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
        for line in f:
            name, sep, value = line.rstrip("\n").partition("=")
            if sep and not line.startswith(("#", "//")):
                entries[name.split(":")[0]] = value
    return entries


def run(command):
    print("setup.py: " + " ".join(shlex.quote(c) for c in command), file=sys.stderr, flush=True)
    subprocess.check_call(command)


class CMakeBuild(build_ext):
    """Builds the one extension, tsrir._tsrir, with CMake."""

    def build_extension(self, ext):
        build_dir = os.environ.get("TSRIR_BUILD_DIR")
        if build_dir:
            build_dir = os.path.abspath(build_dir)
            self.check_reusable(build_dir)
        else:
            build_dir = os.path.join(os.path.abspath(self.build_temp), "cmake")
            self.configure(build_dir)
        jobs = os.environ.get("TSRIR_BUILD_JOBS") or str(os.cpu_count() or 1)
        run(["cmake", "--build", build_dir, "--target", "tsrir_python", "--parallel", jobs])
        python_dir = cmake_cache(build_dir)["TSRIR_PYTHON_DIR"]
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = os.path.join(python_dir, "tsrir", "_tsrir" + suffix)
        if not os.path.exists(built):
            found = glob.glob(os.path.join(python_dir, "tsrir", "_tsrir*"))
            raise RuntimeError("setup.py: %s has no extension for this interpreter (%s, needs *%s; found %s)"
                               % (build_dir, sys.executable, suffix, ", ".join(found) or "none"))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)

    def configure(self, build_dir):
        if os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            return  # configured by an earlier build: cmake --build re-runs it when needed
        command = ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                   "-DTSRIR_WITH_TORCH=OFF", "-DTSRIR_BUILD_TESTS=OFF",
                   "-DPython3_EXECUTABLE=" + sys.executable]
        if shutil.which("ninja"):
            command += ["-G", "Ninja"]
        command += shlex.split(os.environ.get("TSRIR_CMAKE_ARGS", ""))
        run(command)
        if cmake_cache(build_dir).get("TSRIR_PYTHON_MODULE") != "ON":
            raise RuntimeError("setup.py: CMake did not configure the Python module (see its messages above: "
                               "python3-dev and pybind11-dev are needed)")

    @staticmethod
    def check_reusable(build_dir):
        if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            raise RuntimeError("setup.py: TSRIR_BUILD_DIR=%s is not a configured CMake build tree" % build_dir)
        cache = cmake_cache(build_dir)
        source = cache.get("CMAKE_HOME_DIRECTORY", "")
        if os.path.realpath(source) != os.path.realpath(ROOT):
            raise RuntimeError("setup.py: TSRIR_BUILD_DIR=%s was configured for the source %s, not %s"
                               % (build_dir, source, ROOT))
        if cache.get("TSRIR_PYTHON_MODULE") != "ON":
            raise RuntimeError("setup.py: TSRIR_BUILD_DIR=%s does not build the Python module" % build_dir)


setup(ext_modules=[Extension("tsrir._tsrir", sources=[])],
      cmdclass={"build_ext": CMakeBuild},
      # setuptools' own build files apart from a CMake tree in build/ (utils/bootstrap.sh's default)
      options={"build": {"build_base": os.path.join("build", "python-package")}})
