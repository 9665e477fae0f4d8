"""The extension polarview._core, built by CMake for the wheel (pyproject.toml; docs/python.md).

build_ext configures the repository with only the Python module on (no viewer, no tests) in the
wheel's own build directory, builds the target polarview_python and copies the extension where
setuptools packs it. POLARVIEW_CMAKE_BUILD_DIR names an already configured CMake build directory
to build the target in instead (the tests use the one ctest runs from). The build directory is
build-wheel/, apart from the CMake build/ the README makes.
"""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_BASE = "build-wheel"


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = os.environ.get("POLARVIEW_CMAKE_BUILD_DIR", "")
        if not build_dir:
            build_dir = os.path.join(ROOT, BUILD_BASE, "cmake")
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.check_call(["cmake", "-S", ROOT, "-B", build_dir, *generator, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DPOLARVIEW_BUILD_VIEWER=OFF", "-DPOLARVIEW_BUILD_TESTS=OFF",
                                   "-DPOLARVIEW_BUILD_PYTHON=ON", "-DPython3_EXECUTABLE=" + sys.executable])
        elif not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            raise RuntimeError(f"POLARVIEW_CMAKE_BUILD_DIR={build_dir} is not a configured CMake build directory")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "polarview_python", "--parallel", jobs])
        built = glob.glob(os.path.join(build_dir, "python", "polarview", "_core*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one extension polarview/_core*.so in {build_dir}/python, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


os.makedirs(os.path.join(ROOT, BUILD_BASE), exist_ok=True)
setup(ext_modules=[CMakeExtension("polarview._core")], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}})
