"""Builds dfrecon's Python extension with the project's CMake build.

pyproject.toml names setuptools as the backend; this file gives it one
extension, `dfrecon._dfrecon`, whose build is CMake's: configure the source
tree (tests, benchmarks and the program's extras off), build the target
`dfrecon_python`, and copy the module where setuptools packs it. The version
is the one CMakeLists.txt declares.

Environment:
  DFRECON_CMAKE_BUILD_DIR  a build folder to configure and build in (an
                           existing one, e.g. `build` after `make build`, is
                           reused: only what is missing is built); default: a
                           folder under setuptools' build_temp.
  CMAKE_BUILD_PARALLEL_LEVEL  jobs for `cmake --build` (default: the cores).
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"project\(dfrecon VERSION ([0-9.]+)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt: no `project(dfrecon VERSION ...)`")
    return match.group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(os.environ.get("DFRECON_CMAKE_BUILD_DIR") or
                         Path(self.build_temp) / "cmake").resolve()
        build_dir.mkdir(parents=True, exist_ok=True)
        # A configured folder is reused as it is (its interpreter and
        # options stay: changing them would rebuild it); a new one is made
        # for this interpreter, with only what the module needs.
        if not (build_dir / "CMakeCache.txt").exists():
            configure = [
                "cmake", "-S", str(ROOT), "-B", str(build_dir),
                "-DCMAKE_BUILD_TYPE=Release", "-DDFRECON_PYTHON=ON",
                "-DDFRECON_TESTS=OFF", "-DDFRECON_BENCH=OFF",
                "-DPython_EXECUTABLE=" + sys.executable,
            ]
            try:  # pybind11 from pip, where CMake finds no system one
                import pybind11
                configure.append("-Dpybind11_DIR=" + pybind11.get_cmake_dir())
            except ImportError:
                pass
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            if shutil.which("clang++"):
                configure += ["-DCMAKE_CXX_COMPILER=clang++"]
            subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "dfrecon_python",
                        "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "dfrecon").glob("_dfrecon*.so"))
        if not built:
            raise RuntimeError("the CMake build made no _dfrecon module in %s" %
                               (build_dir / "python" / "dfrecon"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        # The module as built for this interpreter, under the name setuptools
        # expects for it.
        shutil.copyfile(built[-1], target)


setup(
    version=project_version(),
    # setuptools' own folders beside CMake's, not in the source tree.
    options={"build": {"build_base": os.environ.get("DFRECON_PIP_BUILD_BASE", "build/pip")},
             "egg_info": {"egg_base": os.environ.get("DFRECON_PIP_BUILD_BASE", "build/pip")}},
    ext_modules=[CMakeExtension("dfrecon._dfrecon")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
