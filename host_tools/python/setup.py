"""Builds the _curio extension with the repository's CMake (pip install --no-build-isolation).

The module is CMake's target _curio (host_tools/python/CMakeLists.txt), configured for the
Python that runs this script in <repository>/build/python-<version>; the float model files
(firmware/nn/models/*.cfm, for Encoder.decode) are copied into the package.
"""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.join(REPO, "build", "python-%d.%d" % sys.version_info[:2])
        configure = ["cmake", "-S", REPO, "-B", build, "-G", "Ninja",
                     "-DCMAKE_BUILD_TYPE=Release", "-DCURIO_BUILD_TRAINER=OFF",
                     "-DCURIO_PYTHON=" + sys.executable]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "--build", build, "--target", "_curio", "-j", jobs], check=True)
        built = glob.glob(os.path.join(build, "host_tools", "python", "curio", "_curio*.so"))
        if len(built) != 1:
            sys.exit("setup.py: CMake built no _curio module (is pybind11-dev installed?)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


class BuildPy(build_py):
    def run(self):
        super().run()
        models = os.path.join(self.build_lib, "curio", "models")
        os.makedirs(models, exist_ok=True)
        for path in glob.glob(os.path.join(REPO, "firmware", "nn", "models", "*.cfm")):
            shutil.copyfile(path, os.path.join(models, os.path.basename(path)))


setup(ext_modules=[Extension("curio._curio", sources=[])],
      cmdclass={"build_ext": CMakeBuild, "build_py": BuildPy})
