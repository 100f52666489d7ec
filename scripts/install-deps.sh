#!/usr/bin/env bash
# Installs Huygens' Debian 12 build and test dependencies with apt-get.
# Idempotent: packages already installed are skipped; nothing runs when all are present.
set -euo pipefail

packages=(
  build-essential cmake pkg-config clang-format
  clang libclang-rt-14-dev libomp-dev  # the libFuzzer targets (scripts/test-fuzz.sh)
  libopenmpi-dev openmpi-bin libfftw3-mpi-dev  # MPI ranks (HUYGENS_MPI, docs/scale.md)
  libfftw3-dev libglm-dev nlohmann-json3-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libglfw3-dev libepoxy-dev libimgui-dev
  libgl-dev libegl-dev libgl1-mesa-dri libegl-mesa0 mesa-utils
  xvfb xauth
  python3 python3-numpy python3-matplotlib
  python3-vtk9  # VTK's own readers for the ParaView output test (tests/programs/vtk_output_test.py)
  python3-dev pybind11-dev python3-pytest  # the Python package (HUYGENS_PYTHON, python/) and its tests
  python3-setuptools python3-wheel          # `pip install --no-build-isolation .` (python/README.md)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} Debian packages are installed"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    SUDO=sudo
  else
    echo "install-deps: not root and no sudo; run as root:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
else
  SUDO=
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
