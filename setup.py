"""Builds the extension with the project's own CMake (pybind11 and Eigen from the system).

    pip install --no-build-isolation .

needs cmake, a C++17 compiler, Eigen 3, pybind11 and NumPy (Debian: cmake g++
libeigen3-dev pybind11-dev python3-dev python3-numpy); nothing is downloaded.
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DACTIONSTRING_BUILD_PYTHON=ON",
            "-DACTIONSTRING_BUILD_TOOLS=OFF",
            "-DACTIONSTRING_BUILD_TESTS=OFF",
            "-DACTIONSTRING_BUILD_BENCH=OFF",
            "-DACTIONSTRING_BUILD_C_API=OFF",
            "-DACTIONSTRING_INSTALL=OFF",
            f"-DPython_EXECUTABLE={sys.executable}",
        ]
        subprocess.check_call(configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_actionstring", "-j", jobs])
        built = next((build / "python" / "actionstring").glob("_actionstring*"))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    package_dir={"": "python"},
    packages=["actionstring"],
    package_data={"actionstring": ["py.typed"]},
    ext_modules=[Extension("actionstring._actionstring", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
