#!/usr/bin/env bash
# Exports the example models that ship with Debian's `openscad` package
# (/usr/share/openscad/examples/**/*.scad, 48 files) as ASCII STL to
# datasets/cache/openscad/<name>.stl: CAD parts nobody here wrote (CSG of cubes, cylinders and
# spheres, extrusions, text, surfaces from height data), the corpus of the robustness tests
# (tests/engine/robustness_test.cpp) and of the soak command (bench/corpus_soak.cpp). 41 of the 48
# are 3-D; the 2-D ones and the ones that only print make OpenSCAD exit with an error and are
# listed as skipped. Idempotent: models already exported are kept. Works from any cwd.
#
#   datasets/make-openscad-corpus.sh            # all of them
#   datasets/make-openscad-corpus.sh CSG logo   # these only (names without .scad)
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OUT="$HERE/cache/openscad"
EXAMPLES=/usr/share/openscad/examples
log() { echo "make-openscad-corpus: $*"; }

command -v openscad >/dev/null || { echo "make-openscad-corpus: openscad is not installed (scripts/install-deps.sh installs it)" >&2; exit 1; }
[ -d "$EXAMPLES" ] || { echo "make-openscad-corpus: $EXAMPLES is missing" >&2; exit 1; }
mkdir -p "$OUT"

mapfile -t files < <(find "$EXAMPLES" -name '*.scad' | sort)
if [ $# -gt 0 ]; then
  wanted=()
  for n in "$@"; do
    for f in "${files[@]}"; do [ "$(basename "$f" .scad)" = "$n" ] && wanted+=("$f"); done
  done
  files=("${wanted[@]}")
fi

export OUT
export_one() {
  local f="$1" n
  n="$(basename "$f" .scad)"
  [ -s "$OUT/$n.stl" ] && return 0
  # Relative imports (surface data, fonts) are resolved from the example's own folder.
  if (cd "$(dirname "$f")" && timeout 600 openscad -q -o "$OUT/$n.tmp.stl" "$f") >/dev/null 2>&1 &&
     [ -s "$OUT/$n.tmp.stl" ]; then
    mv "$OUT/$n.tmp.stl" "$OUT/$n.stl"
    echo "exported $n"
  else
    rm -f "$OUT/$n.tmp.stl"
    echo "skipped $n (not a 3-D model)"
  fi
}
export -f export_one
printf '%s\n' "${files[@]}" | xargs -P "$(nproc)" -I{} bash -c 'export_one "$@"' _ {} |
  sort | sed 's/^/make-openscad-corpus: /'
log "$(find "$OUT" -name '*.stl' | wc -l) models in $OUT"
