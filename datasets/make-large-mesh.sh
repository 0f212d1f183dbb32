#!/usr/bin/env bash
# Generates the large benchmark mesh datasets/cache/meshes/elephant_large.stl: CGAL's
# refined_elephant.off (88,928 facets) midpoint-subdivided twice to 1,422,848 facets,
# written as binary STL (~68 MiB). Fetches the CGAL meshes first if needed. Idempotent:
# does nothing when a complete STL of at least MIN_FACETS facets is already there.
# Works from any cwd.
#
#   datasets/make-large-mesh.sh [path/to/ncpath_subdivide]
#
# Without an argument the binary is looked for in build/datasets/, then build*/datasets/
# under the repository root, then on PATH. Build it with
#   cmake -S . -B build -G Ninja && cmake --build build --target ncpath_subdivide
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
MESHES="$HERE/cache/meshes"
SRC="$MESHES/refined_elephant.off"
OUT="$MESHES/elephant_large.stl"
MIN_FACETS="${NCPATH_LARGE_MIN_FACETS:-1400000}"

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

if [ -f "$OUT" ]; then
  n="$(stl_facets "$OUT")"
  if [ -n "$n" ] && [ "$n" -ge "$MIN_FACETS" ]; then
    log "$OUT already there ($n facets, $(stat -c %s "$OUT") bytes), nothing to do"
    exit 0
  fi
  log "$OUT is incomplete or too small; regenerating"
fi

"$HERE/fetch-cgal-meshes.sh"
[ -s "$SRC" ] || die "$SRC missing after fetch-cgal-meshes.sh"

bin="${1:-}"
if [ -z "$bin" ]; then
  for c in "$ROOT/build/datasets/ncpath_subdivide" "$ROOT"/build*/datasets/ncpath_subdivide; do
    if [ -x "$c" ]; then bin="$c"; break; fi
  done
  [ -n "$bin" ] || bin="$(command -v ncpath_subdivide || true)"
  [ -n "$bin" ] || die "ncpath_subdivide not found; build it (cmake --build build --target \
ncpath_subdivide) or pass its path as the first argument"
fi
[ -x "$bin" ] || die "$bin is not an executable"

log "$bin $SRC -> $OUT (--min-facets $MIN_FACETS)"
tmp="$OUT.partial"
trap 'rm -f "$tmp"' EXIT
start=$(date +%s.%N)
"$bin" "$SRC" "$tmp" --min-facets "$MIN_FACETS" | sed 's/^/  /'
end=$(date +%s.%N)
n="$(stl_facets "$tmp")"
if [ -z "$n" ] || [ "$n" -lt "$MIN_FACETS" ]; then
  die "$tmp is not a complete binary STL of >= $MIN_FACETS facets"
fi
mv -f "$tmp" "$OUT"
log "done: $OUT, $n facets, $(stat -c %s "$OUT") bytes, $(awk -v a="$start" -v b="$end" \
'BEGIN{printf "%.1f", b - a}') s"
