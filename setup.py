"""Builds frictal's Python extension (frictal._core) with the project's own CMake build.

pip calls this through pyproject.toml (setuptools backend). The extension and the C++ library it
links are compiled by CMake in build/python-<tag>/ under the source tree; nothing is downloaded.
Environment: FRICTAL_CMAKE_ARGS adds CMake options (e.g. "-DFRICTAL_MPI=OFF"), FRICTAL_JOBS sets
the parallel build jobs (default: all cores).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version() -> str:
    """The version defined once, in CMakeLists.txt's project(VERSION ...)."""
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    m = re.search(r"project\(\s*frictal\s+VERSION\s+([0-9][0-9.]*)", text)
    if not m:
        raise RuntimeError("CMakeLists.txt: project(frictal VERSION x.y.z) not found")
    return m.group(1)


class CMakeExtension(Extension):
    def __init__(self, name: str):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        cmake = shutil.which("cmake")
        if cmake is None:
            raise RuntimeError("frictal: cmake not found (Debian: apt-get install cmake)")
        tag = sysconfig.get_config_var("SOABI") or f"py{sys.version_info[0]}{sys.version_info[1]}"
        build_dir = ROOT / "build" / f"python-{tag}"
        build_dir.mkdir(parents=True, exist_ok=True)
        args = [
            cmake, "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DFRICTAL_BUILD_TESTS=OFF", "-DFRICTAL_BUILD_CLI=OFF", "-DFRICTAL_BUILD_PYTHON=ON",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        args += shlex.split(os.environ.get("FRICTAL_CMAKE_ARGS", ""))
        env = dict(os.environ)
        env.setdefault("CCACHE_BASEDIR", str(ROOT))
        subprocess.run(args, check=True, env=env)
        jobs = os.environ.get("FRICTAL_JOBS", str(os.cpu_count() or 1))
        subprocess.run([cmake, "--build", str(build_dir), "--target", "frictal_python_core", "-j", jobs],
                       check=True, env=env)
        built = sorted((build_dir / "python" / "frictal").glob("_core*.so"))
        if not built:
            raise RuntimeError(f"frictal: the CMake build made no _core module in {build_dir}/python/frictal")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(version=project_version(), ext_modules=[CMakeExtension("frictal._core")], cmdclass={"build_ext": CMakeBuild})
