"""pip's way in: `pip install --no-build-isolation ./python` builds dla3d's Python module with
CMake for the Python that runs pip (a venv, pyenv or conda) and installs it there, beside the
pure-Python package. It uses what is installed (setuptools, CMake, pybind11 and the C++
libraries from the README's setup) and downloads nothing. See docs/python.md."""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent.parent


class CMakeBuild(build_ext):
    """Builds dla3d._core with the project's CMake, for this interpreter."""

    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        subprocess.check_call([
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}", "-DDLA_BUILD_CLI=OFF", "-DDLA_BUILD_TESTS=OFF",
            "-DDLA_BUILD_BENCH=OFF", "-DDLA_BUILD_EXAMPLES=OFF", "-DDLA_WEB_VIEWER=OFF"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", str(build), "--target", "dla3d_core", "-j", jobs])
        built = build / "python" / "dla3d" / ("_core" + sysconfig.get_config_var("EXT_SUFFIX"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


def version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(dla VERSION ([0-9.]+)", text).group(1)


setup(
    name="dla3d",
    version=version(),
    description="Grow branching structures: DLA, space colonization, Eden, random drops, ballistic aggregation",
    packages=["dla3d"],
    package_dir={"dla3d": "dla3d"},
    ext_modules=[Extension("dla3d._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    zip_safe=False,
)
