"""Builds the tissuemesh Python package: `pip install --no-build-isolation .` from the checkout (README, "Python").

The module is C++ (python/src, pybind11): setuptools hands it to CMake, which builds the whole library
position-independent in build/pip (TM_BUILD_DIR overrides; TM_JOBS sets the parallel jobs) and the module
tissuemesh._tissuemesh for the interpreter running pip. Everything comes from Debian packages (scripts/setup).
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
        build = pathlib.Path(os.environ.get("TM_BUILD_DIR", ROOT / "build" / "pip"))
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DTM_PYTHON=ON",
                     "-DTM_BUILD_TESTS=OFF", f"-DPython_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        if not (build / "CMakeCache.txt").exists():
            subprocess.check_call(configure)
        jobs = os.environ.get("TM_JOBS", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_tissuemesh", "-j", jobs])
        built = sorted((build / "python" / "tissuemesh").glob("_tissuemesh*.so"))
        if not built:
            raise RuntimeError(f"CMake built no _tissuemesh module in {build / 'python' / 'tissuemesh'}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(
    packages=["tissuemesh"],
    package_dir={"": "python"},
    ext_modules=[Extension("tissuemesh._tissuemesh", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
