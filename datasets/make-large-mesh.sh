#!/usr/bin/env bash
# Generates the large benchmark meshes in datasets/cache/meshes/ by subdivision, written as
# binary STL. Fetches the CGAL meshes first if needed. Idempotent: does nothing for a mesh
# when a complete STL of at least its facet count is already there. Works from any cwd.
#   elephant_large.stl: refined_elephant.off (88,928 facets) midpoint-subdivided twice to
#                       1,422,848 facets (~68 MiB; at least NCPATH_LARGE_MIN_FACETS, default
#                       1,400,000)
#   anchor_large.stl:   anchor_dense.off (7,598 facets) midpoint-subdivided three times to
#                       486,272 facets (~23 MiB; at least 454,273, the seed's Table 1 model)
# With --scans, also the dense scan-like meshes (Loop's subdivision: every vertex moves, no
# two facets coplanar, nothing hidden under an overhang), issue 17's inputs:
#   bunny00_loop.stl:    bunny00.off (75,408 facets) twice to 1,206,528 facets (~58 MiB)
#   bunny00_loop3.stl:   bunny00.off three times to 4,826,112 facets (~230 MiB)
#   armadillo_loop.stl:  armadillo.off (52,000 facets) four times to 13,312,000 facets
#                        (~635 MiB; the first Loop mesh of armadillo with >= 4.8 M facets)
#
#   datasets/make-large-mesh.sh [--scans] [path/to/ncpath_subdivide]
#
# Without an argument the binary is looked for in build/datasets/, then build*/datasets/
# under the repository root, then on PATH. Build it with
#   cmake -S . -B build -G Ninja && cmake --build build --target ncpath_subdivide
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
MESHES="$HERE/cache/meshes"

log() { echo "make-large-mesh: $*"; }
die() { echo "make-large-mesh: ERROR: $*" >&2; exit 1; }

# Facet count of a binary STL whose size matches its header count, else nothing.
stl_facets() {
  local f="$1" size n
  size="$(stat -c %s "$f")"
  [ "$size" -ge 84 ] || return 0
  n="$(od -An -t u4 -j 80 -N 4 --endian=little "$f" | tr -d ' ')"
  [ "$size" -eq $((84 + 50 * n)) ] && echo "$n"
  return 0
}

SCANS=0
if [ "${1:-}" = "--scans" ]; then
  SCANS=1
  shift
fi
# Sets bin (the ncpath_subdivide to run) when a mesh has to be made.
BIN_ARG="${1:-}"
bin=""
find_bin() {
  [ -z "$bin" ] || return 0
  bin="$BIN_ARG"
  if [ -z "$bin" ]; then
    for c in "$ROOT/build/datasets/ncpath_subdivide" "$ROOT"/build*/datasets/ncpath_subdivide; do
      if [ -x "$c" ]; then bin="$c"; break; fi
    done
    [ -n "$bin" ] || bin="$(command -v ncpath_subdivide || true)"
    [ -n "$bin" ] || die "ncpath_subdivide not found; build it (cmake --build build --target \
ncpath_subdivide) or pass its path as the first argument"
  fi
  [ -x "$bin" ] || die "$bin is not an executable"
}

# make_one SRC OUT MIN_FACETS [SCHEME]
make_one() {
  local SRC="$1" OUT="$2" MIN_FACETS="$3" SCHEME="${4:-midpoint}" n start end
  if [ -f "$OUT" ]; then
    n="$(stl_facets "$OUT")"
    if [ -n "$n" ] && [ "$n" -ge "$MIN_FACETS" ]; then
      log "$OUT already there ($n facets, $(stat -c %s "$OUT") bytes), nothing to do"
      return 0
    fi
    log "$OUT is incomplete or too small; regenerating"
  fi

  [ -s "$SRC" ] || die "$SRC missing after fetch-cgal-meshes.sh"
  find_bin
  log "$bin $SRC -> $OUT (--min-facets $MIN_FACETS --scheme $SCHEME)"
  tmp="$OUT.partial"
  trap 'rm -f "$tmp"' EXIT
  start=$(date +%s.%N)
  "$bin" "$SRC" "$tmp" --min-facets "$MIN_FACETS" --scheme "$SCHEME" | sed 's/^/  /'
  end=$(date +%s.%N)
  n="$(stl_facets "$tmp")"
  if [ -z "$n" ] || [ "$n" -lt "$MIN_FACETS" ]; then
    die "$tmp is not a complete binary STL of >= $MIN_FACETS facets"
  fi
  mv -f "$tmp" "$OUT"
  log "done: $OUT, $n facets, $(stat -c %s "$OUT") bytes, $(awk -v a="$start" -v b="$end" \
  'BEGIN{printf "%.1f", b - a}') s"
}

"$HERE/fetch-cgal-meshes.sh"

make_one "$MESHES/refined_elephant.off" "$MESHES/elephant_large.stl" \
  "${NCPATH_LARGE_MIN_FACETS:-1400000}"
make_one "$MESHES/anchor_dense.off" "$MESHES/anchor_large.stl" 454273
if [ "$SCANS" = 1 ]; then
  make_one "$MESHES/bunny00.off" "$MESHES/bunny00_loop.stl" 1200000 loop
  make_one "$MESHES/bunny00.off" "$MESHES/bunny00_loop3.stl" 4800000 loop
  make_one "$MESHES/armadillo.off" "$MESHES/armadillo_loop.stl" 4800000 loop
fi
