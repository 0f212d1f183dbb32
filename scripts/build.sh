#!/usr/bin/env bash
# Installs the dependencies (apt), fetches the real meshes, exports OpenSCAD's examples (the
# robustness corpus), configures and builds ncpath in ./build (Release). Used by both of
# README's set-up commands and by CI.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/install-deps.sh
datasets/fetch-cgal-meshes.sh
datasets/make-openscad-corpus.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"
