#!/usr/bin/env bash
# Installs the Debian packages boomdyn needs, only those missing (idempotent):
#   scripts/install-deps.sh           # to build and run boomdyn and plot (scripts/main.sh)
#   scripts/install-deps.sh --tests   # and to run the test suite (scripts/test.sh)
set -euo pipefail
# What scripts/main.sh needs: build boomdyn (CMake also configures the tests,
# hence GoogleTest), run it, plot.
packages=(
  petsc-dev slepc-dev libhdf5-openmpi-dev libeigen3-dev libyaml-cpp-dev libmetis-dev
  libsuitesparse-dev  # KLU, called directly by the one-rank solver (PETSc depends on it too)
  openmpi-bin cmake make g++ pkg-config git libgtest-dev
  python3 python3-numpy python3-h5py python3-matplotlib python3-yaml  # yaml: scene text in postprocess/
)
# With --tests, what the test suite needs beside (scripts/test.sh).
if [ "${1:-}" = "--tests" ]; then
  packages+=(
    python3-meshio  # the XDMF tests read the output as ParaView's readers do
    libbenchmark-dev  # benchmarks/kernels (-DBOOMDYN_BENCHMARKS=ON)
    clang libclang-rt-14-dev  # the scene-reader fuzzer (tests/fuzz): clang++ and libFuzzer + sanitizer runtimes
  )
elif [ $# -gt 0 ]; then
  echo "usage: scripts/install-deps.sh [--tests]" >&2
  exit 2
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y --no-install-recommends "${missing[@]}"
