#!/usr/bin/env bash
# Installs the Debian packages boomdyn needs, only those missing (idempotent).
set -euo pipefail
packages=(
  petsc-dev slepc-dev libhdf5-openmpi-dev libeigen3-dev libyaml-cpp-dev libmetis-dev
  libsuitesparse-dev  # KLU, called directly by the one-rank solver (PETSc depends on it too)
  openmpi-bin cmake make g++ pkg-config git libgtest-dev libbenchmark-dev
  python3 python3-numpy python3-h5py python3-matplotlib python3-meshio
  clang libclang-rt-14-dev  # the scene-reader fuzzer (tests/fuzz): clang++ and libFuzzer + sanitizer runtimes
)
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
