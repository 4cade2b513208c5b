"""The PEP 517 backend of `pip install .` (pyproject.toml): the keyturn package built by the
project's own CMake build, standard library only, so it works offline with Debian's pip and
pybind11 (no setuptools, scikit-build or downloads).

build_wheel configures a CMake build folder unless it is there already, builds the one target
`keyturn_python` in it (ccache and an existing build make that quick), and zips the package it
produced (build/ui/python/keyturn/: the extension, __init__.py, the stubs, py.typed) with pip's
metadata. The build folder, in this order: `pip install --config-settings build-dir=DIR .`, $KEYTURN_BUILD_DIR,
or build/ in the repository (the one the README's scripts build)."""
import base64
import hashlib
import io
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import time
import zipfile
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[3]
NAME = "keyturn"
SUMMARY = "ISS keypoint-distribution shape descriptors of depth views, datasets and models"


def _log(text):
    print(f"keyturn build backend: {text}", file=sys.stderr, flush=True)


def _version():
    m = re.search(r"project\(\s*keyturn\s+VERSION\s+([0-9][0-9.]*)", (SOURCE / "CMakeLists.txt").read_text())
    if not m:
        raise RuntimeError(f"{SOURCE / 'CMakeLists.txt'}: no `project(keyturn VERSION …)`")
    return m.group(1)


def _tag():
    impl = f"cp{sys.version_info.major}{sys.version_info.minor}"
    abi = impl + getattr(sys, "abiflags", "")
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{impl}-{abi}-{platform}"


def _build_dir(config_settings):
    given = (config_settings or {}).get("build-dir") or os.environ.get("KEYTURN_BUILD_DIR")
    folder = Path(given) if given else SOURCE / "build"
    return folder if folder.is_absolute() else (SOURCE / folder).resolve()


def _run(cmd):
    _log(" ".join(map(str, cmd)))
    # The build's output to stderr: pip shows it with -v, and stdout is pip's to parse.
    subprocess.run([str(c) for c in cmd], check=True, stdout=sys.stderr)


def _cache_value(cache, key):
    m = re.search(rf"^{re.escape(key)}:[A-Z]+=(.*)$", cache, re.M)
    return m.group(1) if m else None


def _build(config_settings):
    """Builds the extension; returns the package folder in the build tree."""
    build = _build_dir(config_settings)
    python = getattr(sys, "_base_executable", None) or sys.executable  # the interpreter, not a venv's link
    cache = build / "CMakeCache.txt"
    if not cache.exists():
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        _run(["cmake", "-S", SOURCE, "-B", build, *generator, "-DCMAKE_BUILD_TYPE=Release",
              f"-DPython3_EXECUTABLE={python}"])
    else:
        source = _cache_value(cache.read_text(errors="replace"), "CMAKE_HOME_DIRECTORY")
        if source and Path(source).resolve() != SOURCE:
            raise RuntimeError(f"{build} is the build folder of {source}, not of {SOURCE}: "
                               f"pass --config-settings build-dir=ANOTHER_FOLDER")
    jobs = (config_settings or {}).get("jobs") or str(os.cpu_count() or 1)
    t0 = time.monotonic()
    _run(["cmake", "--build", build, "--target", "keyturn_python", "--parallel", jobs])
    _log(f"built keyturn_python in {build} in {time.monotonic() - t0:.1f} s")
    package = build / "ui" / "python" / NAME
    extension = package / ("_keyturn" + sysconfig.get_config_var("EXT_SUFFIX"))
    if not extension.exists():
        found = sorted(p.name for p in package.glob("_keyturn*.so")) if package.is_dir() else []
        built_for = _cache_value(cache.read_text(errors="replace"), "Python3_EXECUTABLE") if cache.exists() else None
        raise RuntimeError(f"{build} did not build the module for this Python ({extension.name}): it has "
                           f"{found or 'none'}, built for {built_for}. Install with the Python the build uses, "
                           f"or pass --config-settings build-dir=ANOTHER_FOLDER for a build of its own")
    return package


def _metadata():
    return (f"Metadata-Version: 2.1\nName: {NAME}\nVersion: {_version()}\nSummary: {SUMMARY}\n"
            "Requires-Python: >=3.9\nRequires-Dist: numpy\nProvides-Extra: open3d\n"
            "Requires-Dist: open3d; extra == \"open3d\"\n"
            "Description-Content-Type: text/markdown\n\n"
            "The keyturn Python package (docs/python.md): describe depth views from numpy arrays, Open3D point "
            "clouds or files; a dataset's features; train and apply models.\n")


def _wheel_file():
    return f"Wheel-Version: 1.0\nGenerator: keyturn_build_backend\nRoot-Is-Purelib: false\nTag: {_tag()}\n"


def _dist_info():
    return f"{NAME}-{_version()}.dist-info"


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    info = Path(metadata_directory) / _dist_info()
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(_metadata())
    (info / "WHEEL").write_text(_wheel_file())
    return info.name


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    package = _build(config_settings)
    wheel = Path(wheel_directory) / f"{NAME}-{_version()}-{_tag()}.whl"
    records = []

    def add(zf, arcname, data):
        zf.writestr(zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0)), data, zipfile.ZIP_DEFLATED)
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        records.append(f"{arcname},sha256={digest},{len(data)}")

    with zipfile.ZipFile(wheel, "w") as zf:
        for f in sorted(package.iterdir()):
            program = f.name == "keyturn-worker"  # the worker program of core/worker_process.h
            if f.is_file() and (f.suffix in (".py", ".pyi", ".so") or f.name == "py.typed" or program):
                info = zipfile.ZipInfo(f"{NAME}/{f.name}", date_time=(2020, 1, 1, 0, 0, 0))
                info.external_attr = (0o755 if f.suffix == ".so" or program else 0o644) << 16
                data = f.read_bytes()
                zf.writestr(info, data, zipfile.ZIP_DEFLATED)
                digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
                records.append(f"{NAME}/{f.name},sha256={digest},{len(data)}")
        info = _dist_info()
        add(zf, f"{info}/METADATA", _metadata().encode())
        add(zf, f"{info}/WHEEL", _wheel_file().encode())
        add(zf, f"{info}/top_level.txt", f"{NAME}\n".encode())
        records.append(f"{info}/RECORD,,")
        zf.writestr(zipfile.ZipInfo(f"{info}/RECORD", date_time=(2020, 1, 1, 0, 0, 0)),
                    "\n".join(records) + "\n", zipfile.ZIP_DEFLATED)
    _log(f"wrote {wheel.name}")
    return wheel.name


def build_sdist(sdist_directory, config_settings=None):
    """The repository's tracked files (git ls-files) as NAME-VERSION.tar.gz."""
    try:
        listed = subprocess.run(["git", "-C", str(SOURCE), "ls-files", "-z"], check=True, capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        raise RuntimeError(f"{SOURCE}: an sdist is made from a git checkout (git ls-files): {e}")
    base = f"{NAME}-{_version()}"
    target = Path(sdist_directory) / f"{base}.tar.gz"
    with tarfile.open(target, "w:gz") as tar:
        for name in filter(None, listed.decode().split("\0")):
            path = SOURCE / name
            if path.is_file():
                tar.add(path, arcname=f"{base}/{name}", recursive=False)
        pkg_info = _metadata().encode()
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        info.size = len(pkg_info)
        tar.addfile(info, io.BytesIO(pkg_info))
    return target.name
