#!/usr/bin/env bash
# Installs every Debian 12 package keyturn needs to build, test and run.
# Idempotent and quick when everything is already there: it only calls apt-get
# for packages that dpkg does not report as installed. Then it checks that every
# command the build, test and demo scripts call is on PATH.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/toolchain.sh"

packages=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config
  # the hardening build: clang with AddressSanitizer, UBSan and libFuzzer
  clang-$KEYTURN_CLANG_VERSION libclang-rt-$KEYTURN_CLANG_VERSION-dev
  # llvm-symbolizer: LeakSanitizer's suppressions (tests/sanitizers/lsan.supp) match function
  # names, which only a symbolizer gives; without it the suppressed system leaks fail the run
  llvm-$KEYTURN_CLANG_VERSION
  # Clang's OpenMP (libomp): the reconstruction plugin's find_package(OpenMP) fails without it
  # under Clang (GCC brings its own libgomp), so a bare machine's hardening build did not configure
  libomp-$KEYTURN_CLANG_VERSION-dev
  # point clouds (PCL pulls in Eigen, FLANN, Boost and VTK)
  libpcl-dev libeigen3-dev
  # ray casting for the simulated SR4000 views
  libembree-dev
  # devices: USB discovery (libusb) and its emulation in tests (umockdev)
  libusb-1.0-0-dev umockdev libumockdev-dev
  # turntable over Modbus RTU/TCP
  libmodbus-dev
  # SHA-256 checksums of captured files (OpenSSL libcrypto)
  libssl-dev
  # plots (Qt Charts, rendered to PNG headless) and the GUI: Qt Widgets, VTK's Qt
  # widget, OpenCV's colour maps; Xvfb + Mesa (llvmpipe) for the GUI tests and headless runs
  qtbase5-dev libqt5charts5-dev fonts-dejavu-core libvtk9-qt-dev libopencv-imgproc-dev
  xvfb xauth libgl1-mesa-dri
  # a standard Modbus master, polls the simulated turntable in the tests
  mbpoll
  # images: 16-bit PNGs of raw distance, amplitude and confidence
  libopencv-imgcodecs-dev
  # learning: XGBoost (C API; its CMake config wants the xgboost package too) and
  # libtorch; OpenBLAS (single-threaded: evaluate runs folds in parallel) instead of
  # the reference BLAS, 3x faster network training (docs/results.md)
  libxgboost-dev xgboost libtorch-dev libopenblas0-serial
  # reconstruction from a turntable capture (keyturn reconstruct): Open3D's C++ library
  # (multi-view ICP, pose graph optimisation, TSDF integration, Poisson surfaces)
  libopen3d-dev
  # BigBIRD's HDF5 files (keyturn import bigbird): the HDF5 C library
  libhdf5-dev
  # command line, configuration, JSON; camera files users have (ROS camera_info and OpenCV
  # calibration YAML: yaml-cpp; Open3D's PinholeCameraIntrinsic JSON: nlohmann-json)
  libcli11-dev nlohmann-json3-dev libyaml-cpp-dev
  # commodity depth cameras (Kinect, Xtion, Astra) through OpenNI2: its library, the driver API
  # (Driver/OniDriverAPI.h) the simulated OpenNI2 driver is built against, the samples' sources
  # (SimpleRead, EventBasedRead, MultipleStreamRead) the tests compile, and its tools (NiViewer2)
  libopenni2-dev openni2-utils
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # JSON assertions in the command-line tests
  jq
  # the docs test (tests/docs: runs the examples in README.md and docs/, standard library only)
  python3
  # the Python package (ui/python, pybind11) and its tests (numpy); scikit-learn is optional (docs/python.md)
  python3-dev pybind11-dev python3-numpy
  # `pip install .` into a venv (pyproject.toml, offline), Open3D clouds in and out, the walkthrough's
  # plots, and mypy on its typed example (tests/python: python.package, python.walkthrough)
  python3-venv python3-pip python3-open3d python3-matplotlib mypy
  # the Slurm test (tests/slurm: a private single-node cluster on loopback runs describe and
  # evaluate as array jobs): Slurm's daemons and commands, and munge for its credentials
  slurm-wlm munge
)

# Commands the scripts and tests call (a package can be installed and still not
# provide the name a script uses: clang-14 has no 'clang').
commands=(
  cc c++ cmake ctest ninja ccache pkg-config "$KEYTURN_CC" "$KEYTURN_CXX" "$KEYTURN_SYMBOLIZER"
  xvfb-run Xvfb xauth mbpoll umockdev-run umockdev-wrapper
  munged mungekey slurmctld slurmd sbatch squeue scontrol sinfo
)

check_commands() {
  local absent=()
  for c in "${commands[@]}"; do
    command -v "$c" > /dev/null || absent+=("$c")
  done
  if [ ${#absent[@]} -ne 0 ]; then
    echo "install-deps: commands the scripts call are not on PATH: ${absent[*]}" >&2
    exit 1
  fi
  # A compiler can be there and still lack a runtime the build asks for (libomp for Clang).
  if ! printf 'int main(void) { return 0; }\n' | "$KEYTURN_CC" -fopenmp -x c - -o /dev/null 2> /dev/null; then
    echo "install-deps: $KEYTURN_CC cannot build an OpenMP program (libomp-$KEYTURN_CLANG_VERSION-dev missing?)" >&2
    exit 1
  fi
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  check_commands
  echo "install-deps: all ${#packages[@]} packages and ${#commands[@]} commands present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
check_commands
echo "install-deps: installed ${#missing[@]} packages; all ${#commands[@]} commands present"
