# SPDX-License-Identifier: MIT
# Builds the wheel's extension with the project's own CMake build (pyproject.toml says how to call
# it): configure the source tree above this directory with SEWERPLAN_PYTHON=ON for the Python
# that runs the build, build the target sewerplan_python, and put _sewerplan*.so into the package.
#
# Environment:
#   SEWERPLAN_WHEEL_BUILD_DIR  the CMake build tree (default: <source>/build/wheel; kept, so a
#                              second wheel build is incremental)
#   SEWERPLAN_CMAKE_ARGS       more CMake arguments, split as the shell splits them (for example
#                              "-DCMAKE_BUILD_TYPE=RelWithDebInfo -DSEWERPLAN_WITH_GIS=OFF")
#   CMAKE_BUILD_PARALLEL_LEVEL how many compile jobs (CMake's own variable)
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = pathlib.Path(__file__).resolve().parent
SOURCE = HERE.parent


def project_version():
    """The version of project(sewerplan VERSION ...) in CMakeLists.txt, its one source."""
    text = (SOURCE / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*sewerplan\s+VERSION\s+([0-9][0-9.]*)", text)
    if match is None:
        raise RuntimeError(f"{SOURCE / 'CMakeLists.txt'}: no project(sewerplan VERSION ...)")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds the extension with CMake instead of setuptools' compiler calls."""

    def build_extension(self, ext):
        build_dir = pathlib.Path(os.environ.get("SEWERPLAN_WHEEL_BUILD_DIR",
                                                SOURCE / "build" / "wheel"))
        configure = ["cmake", "-S", str(SOURCE), "-B", str(build_dir),
                     "-DCMAKE_BUILD_TYPE=Release", "-DSEWERPLAN_PYTHON=ON",
                     "-DSEWERPLAN_BUILD_TESTS=OFF", "-DSEWERPLAN_BUILD_BENCH=OFF",
                     "-DSEWERPLAN_WEB=OFF", f"-DPython_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        configure += shlex.split(os.environ.get("SEWERPLAN_CMAKE_ARGS", ""))
        if (build_dir / "CMakeCache.txt").exists():
            configure = [a for a in configure if a not in ("-G", "Ninja")]  # kept by the cache
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "sewerplan_python"],
                       check=True)
        built = sorted((build_dir / "python" / "sewerplan").glob("_sewerplan*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _sewerplan*.so in {build_dir}/python/sewerplan, "
                               f"found {[p.name for p in built]}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(
    version=project_version(),
    ext_modules=[Extension("sewerplan._sewerplan", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
