#!/usr/bin/env bash
# Sets up rfrecon on a Debian 12 machine: installs the Debian packages it needs (only those missing; idempotent,
# non-interactive) and the PyPI packages of its Python module and tests into the python3 on PATH, builds it into build/
# (Release, tests, benchmarks and the Python module included) and installs the Python package rfrecon from that
# build (docs/python.md).
# Usage: bash scripts/setup.sh [--no-build]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git python3 python3-dev python3-pip clang clang-format clang-tidy
  ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers pocl-opencl-icd clinfo oclgrind
  libeigen3-dev libopencv-dev libopencv-contrib-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libhdf5-dev libassimp-dev libtiff-dev libssl-dev libdeflate-dev
  libsdl2-dev libaravis-dev libusb-1.0-0-dev xvfb gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-x
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

# Python: pybind11 and scikit-build-core build the module; numpy and scipy are the package's dependencies; pytest,
# tqdm, dask[distributed] and open3d-cpu are what tests/python and docs/python.md's walkthrough use (docs/building.md).
# PIP_BREAK_SYSTEM_PACKAGES: where python3 is Debian's own, pip refuses to install beside apt's packages without it.
export PIP_BREAK_SYSTEM_PACKAGES=1 PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1
python3 -m pip install -q "pybind11>=2.10" "scikit-build-core>=0.10" numpy scipy pytest tqdm "dask[distributed]" \
  open3d-cpu

if [[ "${1:-}" != "--no-build" ]]; then
  # A unity build (8 sources of a target compiled as one): 8.4 min from scratch on 2 cores against 11.9 min
  # (docs/building.md). For day-to-day work on a few files, configure a build directory with -DCMAKE_UNITY_BUILD=OFF.
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON
  cmake --build build -j"$(nproc)"
  # The package from the same build/ (scikit-build-core, pyproject.toml): reconfigures it and builds only the module,
  # which is up to date. The generator must be the one build/ has. scikit-build-core leaves its temporary install
  # prefix in build/'s cache: the second configure puts back the default, for `cmake --install build`.
  CMAKE_GENERATOR=$(sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' build/CMakeCache.txt) \
    python3 -m pip install -q --no-build-isolation .
  cmake -S . -B build -DCMAKE_INSTALL_PREFIX=/usr/local >/dev/null
fi
