"""setuptools build of the huygens package: the extension module huygens._huygens is built by the
project's own CMake (target huygens_python, HUYGENS_PYTHON=ON) for the interpreter that runs this
build, without the tests, benchmarks and viewer; the pure-Python files come from python/huygens.

    python3 -m venv --system-site-packages VENV && VENV/bin/pip install --no-build-isolation .

HUYGENS_ISA (environment) chooses the instruction set as for scripts/build.sh (default: this CPU's,
native); CMAKE_BUILD_PARALLEL_LEVEL the build's jobs (default: the CPU count). setuptools' folders
go to build-pip/ (the CMake build of the README's set-up is build/), its metadata to python/huygens.egg-info.
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
    """Builds huygens._huygens with CMake and copies it where setuptools packs it."""

    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release", "-DHUYGENS_PYTHON=ON", "-DHUYGENS_BUILD_TESTS=OFF",
            "-DHUYGENS_BUILD_BENCHMARKS=OFF", "-DHUYGENS_BUILD_VIZ=OFF", f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        if os.environ.get("HUYGENS_ISA"):
            configure.append(f"-DHUYGENS_ISA={os.environ['HUYGENS_ISA']}")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(configure)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "huygens_python", "-j", jobs])
        built = sorted((build / "python" / "huygens").glob("_huygens*.so"))
        if not built:
            raise RuntimeError(f"the CMake build left no huygens/_huygens*.so in {build / 'python'}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    packages=["huygens"],
    package_dir={"": "python"},
    package_data={"huygens": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("huygens._huygens", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}},
    zip_safe=False,
)
