#!/usr/bin/env bash
# Installs, from Debian 12 (bookworm) packages only, everything a fresh machine needs to
# build, test, benchmark and run the demo of ncpath, and to fetch/generate the datasets.
# Idempotent: apt-get skips what is already installed. Uses sudo only when not root.
#
#   scripts/install-deps.sh            # install everything
#   NCPATH_EXTRA_PACKAGES="foo bar" scripts/install-deps.sh   # plus ad-hoc extras
set -euo pipefail

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO=sudo
export DEBIAN_FRONTEND=noninteractive

# Toolchain and build system: compiler, CMake >= 3.25 (bookworm ships 3.25.1), Ninja,
# pkg-config for libraries without CMake configs, git for the work tree.
TOOLCHAIN=(build-essential cmake ninja-build pkg-config git ca-certificates)

# Libraries the top-level CMakeLists.txt find_package()s: Eigen (kernels' value types),
# oneTBB (engine/parallel.hpp), Embree 3 (engine spatial queries), HDF5 C (CL output),
# CLI11 (command line), toml++ (job specs), zlib (the CL writer deflates HDF5 chunks itself).
LIBRARIES=(libeigen3-dev libtbb-dev libembree-dev libhdf5-dev libcli11-dev
  libtomlplusplus-dev zlib1g-dev)

# Tests and benchmarks: GoogleTest/GoogleMock, Google Benchmark.
TEST_BENCH=(libgtest-dev libgmock-dev libbenchmark-dev)

# Inspecting and checking results: h5dump/h5ls, and Python with h5py/numpy for the demo
# and the result-checking scripts.
RESULTS=(hdf5-tools python3 python3-h5py python3-numpy)

# datasets/fetch-cgal-meshes.sh: apt-get download + dpkg -x (apt and dpkg are always
# present) and tar/gzip to unpack the CGAL data tarball; xz-utils for .tar.xz archives;
# coreutils for sha256sum/stat.
DATASETS=(tar gzip xz-utils coreutils)

# ---- Extra packages: other engineers add what their part needs HERE, one per line, with
# ---- a comment saying why (e.g. libssl-dev). Callers can also pass NCPATH_EXTRA_PACKAGES.
EXTRA=(
  libssl-dev           # batch/output/CMakeLists.txt: find_package(OpenSSL COMPONENTS Crypto)
  nlohmann-json3-dev   # batch/CMakeLists.txt: find_package(nlohmann_json 3)
  libdxflib-dev        # batch/io/CMakeLists.txt: DXF pocket profiles (pkg-config dxflib)
  libpolyclipping-dev  # tests/kernels: Clipper as an independent offset oracle (tests only)
  openmpi-bin          # mpirun for ncpath-mpi (batch/CMakeLists.txt) and its tests
  libopenmpi-dev       # batch/CMakeLists.txt: find_package(MPI COMPONENTS CXX), ncpath-mpi
  libcairo2-dev        # batch/CMakeLists.txt: previews and the report (pkg-config cairo)
  chromium             # tests/batch/preview_test.cpp: the report opened in headless Chromium
  openscad             # datasets/make-openscad-corpus.sh: its examples, the robustness corpus
)
# shellcheck disable=SC2206  # word splitting of the env var is intended
EXTRA+=(${NCPATH_EXTRA_PACKAGES:-})

ALL=("${TOOLCHAIN[@]}" "${LIBRARIES[@]}" "${TEST_BENCH[@]}" "${RESULTS[@]}"
  "${DATASETS[@]}" "${EXTRA[@]}")

echo "install-deps: apt-get update"
$SUDO apt-get update -qq

echo "install-deps: installing ${#ALL[@]} packages: ${ALL[*]}"
# -qq keeps apt quiet; errors still go to stderr and abort the script (set -e).
$SUDO apt-get install -y -qq --no-install-recommends "${ALL[@]}" >/dev/null

echo "install-deps: done ($(cmake --version | head -n1), $(c++ --version | head -n1))"
