"""The PEP 517 / PEP 660 build backend of `pip install .` (pyproject.toml): builds the `dynslam`
Python module and command with CMake and packs them, with the embedded KITTI data, into a wheel.

In-tree and with no build requirements, so that pip needs no package index: Debian's CMake,
compiler, Ceres, pybind11 and NumPy are what the build uses (scripts/lib/common.sh installs
them). The build tree is $DYNSLAM_BUILD_DIR when set (an existing one is reused as configured,
e.g. build/release), else build/pip-cpXY in the source tree, configured for the Python that runs
pip. `pip install -e .` installs a path to that build tree's module instead of a copy.
"""
import base64
import hashlib
import importlib.machinery
import os
import stat
import pathlib
import subprocess
import sys
import sysconfig
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
NAME = "dynslam"
TAG = f"cp{sys.version_info.major}{sys.version_info.minor}"


def _build_tree():
    """Configures (when new) and builds the module and the command; returns the build tree."""
    given = os.environ.get("DYNSLAM_BUILD_DIR")
    build = pathlib.Path(given).resolve() if given else ROOT / "build" / f"pip-{TAG}"
    if not (build / "CMakeCache.txt").is_file():
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        f"-DPython_EXECUTABLE={sys.executable}", "-DDYNSLAM_BUILD_TESTS=OFF",
                        "-DDYNSLAM_BUILD_BENCHMARKS=OFF"], check=True, stdout=sys.stderr)
    jobs = str(len(os.sched_getaffinity(0)))
    subprocess.run(["cmake", "--build", str(build), "-j", jobs, "--target", "dynslam_python",
                    "dynslam_cli"], check=True, stdout=sys.stderr)
    package = build / "python" / NAME
    if not any(package.glob(f"_dynslam{suffix}") for suffix in importlib.machinery.EXTENSION_SUFFIXES):
        raise RuntimeError(f"{package} holds no module for {sys.executable} (a build tree "
                           f"configured for another Python? unset DYNSLAM_BUILD_DIR)")
    return build


def _version(build):
    scope = {}
    exec((build / "python" / NAME / "_version.py").read_text(), scope)
    return scope["__version__"]


def _metadata(version):
    return (f"Metadata-Version: 2.1\nName: {NAME}\nVersion: {version}\n"
            "Summary: Dynamic SLAM back ends on Ceres Solver (world-centric, object-centric and "
            "hybrid factor graphs)\nRequires-Python: >=3.9\nRequires-Dist: numpy\n"
            "License: see the repository\n")


class _Wheel:
    """A wheel being written: files with their RECORD lines."""

    def __init__(self, directory, version):
        self.name = f"{NAME}-{version}-{TAG}-{TAG}-{sysconfig.get_platform().replace('-', '_').replace('.', '_')}.whl"
        self.zip = zipfile.ZipFile(pathlib.Path(directory) / self.name, "w", zipfile.ZIP_DEFLATED)
        self.dist_info = f"{NAME}-{version}.dist-info"
        self.records = []

    def add(self, arcname, data, executable=False):
        info = zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0))
        info.external_attr = (stat.S_IFREG | (0o755 if executable else 0o644)) << 16
        info.compress_type = zipfile.ZIP_DEFLATED
        self.zip.writestr(info, data)
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        self.records.append(f"{arcname},sha256={digest},{len(data)}")

    def add_tree(self, source, prefix):
        for path in sorted(pathlib.Path(source).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                self.add(f"{prefix}/{path.relative_to(source).as_posix()}", path.read_bytes(),
                         os.access(path, os.X_OK))

    def close(self, version):
        self.add(f"{self.dist_info}/METADATA", _metadata(version).encode())
        self.add(f"{self.dist_info}/WHEEL", (f"Wheel-Version: 1.0\nGenerator: dynslam_build\n"
                                            f"Root-Is-Purelib: false\nTag: {TAG}-{TAG}-"
                                            f"{self.name.rsplit('-', 1)[1][:-4]}\n").encode())
        self.add(f"{self.dist_info}/entry_points.txt",
                 b"[console_scripts]\ndynslam = dynslam._cli:main\n")
        self.records.append(f"{self.dist_info}/RECORD,,")
        self.zip.writestr(f"{self.dist_info}/RECORD", "\n".join(self.records) + "\n")
        self.zip.close()
        return self.name


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_editable(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    build = _build_tree()
    version = _version(build)
    wheel = _Wheel(wheel_directory, version)
    wheel.add_tree(build / "python" / NAME, NAME)
    wheel.add(f"{NAME}/bin/dynslam", (build / "apps" / "dynslam").read_bytes(), executable=True)
    wheel.add_tree(ROOT / "data" / "kitti_tracking", f"{NAME}/data/kitti_tracking")
    return wheel.close(version)


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    build = _build_tree()
    version = _version(build)
    wheel = _Wheel(wheel_directory, version)
    wheel.add(f"_{NAME}_editable.pth", f"{build / 'python'}\n".encode())
    return wheel.close(version)
