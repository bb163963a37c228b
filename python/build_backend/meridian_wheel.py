"""PEP 517 build backend of the Python package `meridian` (pyproject.toml at the root).

It builds the extension with the project's CMake (the same build as
`-DMERIDIAN_PYTHON=ON`) and packs python/meridian and `_core` into a wheel with
the standard library's zipfile: no setuptools, nothing fetched from an index,
so `pip wheel .` and `pip install .` work offline. The wheel is for the machine
it was built on (Debian 12's interpreter and its shared libraries: yaml-cpp,
GeographicLib, NetCDF, FFTW, fmt, utf8proc), tagged cpXY-cpXY-<platform>; it is
not a manylinux wheel.

Environment: MERIDIAN_WHEEL_BUILD_DIR, the CMake build directory to use (default
<root>/build-wheel; an existing build tree configured with MERIDIAN_PYTHON=ON is
reused), MERIDIAN_WHEEL_JOBS (parallel jobs, default the CPU count).
"""

import base64
import hashlib
import os
import re
import subprocess
import sys
import sysconfig
import zipfile

_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
_NAME = "meridian"


def _version():
    text = open(os.path.join(_ROOT, "CMakeLists.txt"), encoding="utf-8").read()
    m = re.search(r"project\(Meridian VERSION ([0-9.]+)", text)
    if not m:
        raise RuntimeError("no project(Meridian VERSION ...) in CMakeLists.txt")
    return m.group(1)


def _tag():
    py = f"cp{sys.version_info.major}{sys.version_info.minor}"
    plat = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{py}-{py}-{plat}"


def _metadata():
    return (
        "Metadata-Version: 2.1\n"
        f"Name: {_NAME}\n"
        f"Version: {_version()}\n"
        "Summary: True north and the plumb line from instrument data (gyro-theodolite, maglev gyro, "
        "marine navigation, deflection of the vertical, spherical-harmonic gravity)\n"
        "Requires-Python: >=3.9\n"
        "Requires-Dist: numpy\n"
        "Provides-Extra: dask\n"
        "Requires-Dist: dask; extra == \"dask\"\n"
    )


def _build_package():
    """Configure (if needed) and build the extension; return <build>/python/meridian."""
    build = os.environ.get("MERIDIAN_WHEEL_BUILD_DIR") or os.path.join(_ROOT, "build-wheel")
    jobs = os.environ.get("MERIDIAN_WHEEL_JOBS") or str(os.cpu_count() or 1)
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        subprocess.run(["cmake", "-S", _ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DMERIDIAN_PYTHON=ON",
                        f"-DPython3_EXECUTABLE={sys.executable}"], check=True, stdout=sys.stderr)
    subprocess.run(["cmake", "--build", build, "--target", "meridian_python", "-j", jobs], check=True,
                   stdout=sys.stderr)
    pkg = os.path.join(build, "python", _NAME)
    if not any(f.startswith("_core") and f.endswith(".so") for f in os.listdir(pkg)):
        raise RuntimeError(f"no extension _core*.so in {pkg}: configure {build} with -DMERIDIAN_PYTHON=ON")
    return pkg


def _record_line(arcname, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{arcname},sha256={digest},{len(data)}"


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    pkg = _build_package()
    version = _version()
    dist_info = f"{_NAME}-{version}.dist-info"
    wheel_name = f"{_NAME}-{version}-{_tag()}.whl"
    files = []
    for f in sorted(os.listdir(pkg)):
        if f.endswith(".py") or (f.startswith("_core") and f.endswith(".so")):
            with open(os.path.join(pkg, f), "rb") as fh:
                files.append((f"{_NAME}/{f}", fh.read()))
    files.append((f"{dist_info}/METADATA", _metadata().encode()))
    files.append((f"{dist_info}/WHEEL", (
        "Wheel-Version: 1.0\nGenerator: meridian_wheel\nRoot-Is-Purelib: false\n" f"Tag: {_tag()}\n").encode()))
    record = [_record_line(a, d) for a, d in files] + [f"{dist_info}/RECORD,,"]
    files.append((f"{dist_info}/RECORD", ("\n".join(record) + "\n").encode()))
    path = os.path.join(wheel_directory, wheel_name)
    tmp = path + ".part"
    with zipfile.ZipFile(tmp, "w", compression=zipfile.ZIP_DEFLATED) as z:
        for arcname, data in files:
            info = zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = (0o755 if arcname.endswith(".so") else 0o644) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
    os.replace(tmp, path)
    return wheel_name


def get_requires_for_build_wheel(config_settings=None):
    return []


def build_sdist(sdist_directory, config_settings=None):
    # Only wheels: the source distribution is the repository (CMake, C++ and all).
    raise NotImplementedError("meridian builds wheels only; build from a clone of the repository")
