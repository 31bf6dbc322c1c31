"""Builds the extension slc._slc with the project's own CMake build (python/CMakeLists.txt).

The build tree is build-python/ (or $SLC_PYTHON_BUILD_DIR), Release, with only the library and the
extension; $SLC_BUILD_JOBS sets the parallel jobs (default: all cores). $SLC_PYTHON_MODULE names a
module already built (by a tree configured with -DSLC_BUILD_PYTHON=ON) to install instead.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        # A module already built by a configured tree (scripts/test builds it with the tool).
        prebuilt = os.environ.get("SLC_PYTHON_MODULE")
        if prebuilt:
            shutil.copyfile(prebuilt, target)
            return
        build = Path(os.environ.get("SLC_PYTHON_BUILD_DIR", ROOT / "build-python"))
        # The interpreter itself, not a venv's link to it, so that the cache stays valid.
        python = os.path.realpath(sys.executable)
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja",
            "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_FLAGS=-DSLC_ENABLE_ASSERTS",
            "-DSLC_WERROR=ON", "-DSLC_BUILD_PYTHON=ON", "-DSLC_BUILD_TESTS=OFF",
            "-DSLC_BUILD_BENCH=OFF", "-DSLC_BUILD_TOOL=OFF", "-DSLC_BUILD_EXAMPLES=OFF",
            f"-DPython_EXECUTABLE={python}",
        ]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("SLC_BUILD_JOBS", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build), "--target", "_slc", "-j", jobs], check=True)
        built = next((build / "python" / "slc").glob("_slc*.so"))
        shutil.copyfile(built, target)


setup(
    ext_modules=[Extension("slc._slc", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own files beside CMake's, not in build/, the CMake tree of scripts/build.
    options={"build": {"build_base": "build-python/setuptools"}},
)
