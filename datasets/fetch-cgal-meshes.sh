#!/usr/bin/env bash
# Fetches seven real scanned/CAD meshes (OFF) from Debian's libcgal-demo package into
# datasets/cache/meshes/. Idempotent: does nothing when all seven are already there.
# Works from any cwd. Needs apt lists (scripts/install-deps.sh runs apt-get update); if the
# download fails it runs apt-get update once (with sudo when not root) and retries.
#
#   datasets/fetch-cgal-meshes.sh
#
# Where the meshes are in the package (libcgal-demo 5.5.1-2, bookworm):
#   usr/share/doc/libcgal-dev/data.tar.gz  ->  data/meshes/<name>.off
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
CACHE="$HERE/cache"
MESHES="$CACHE/meshes"
PKG=libcgal-demo
NAMES=(bunny00 armadillo refined_elephant fandisk blade lion-head anchor_dense)
# Candidate archive paths inside the package, in the order tried.
DATA_TARS=(usr/share/doc/libcgal-dev/data.tar.gz usr/share/doc/libcgal-dev/data.tar.xz)

log() { echo "fetch-cgal-meshes: $*"; }
die() { echo "fetch-cgal-meshes: ERROR: $*" >&2; exit 1; }

missing=()
for n in "${NAMES[@]}"; do
  [ -s "$MESHES/$n.off" ] || missing+=("$n")
done
if [ ${#missing[@]} -eq 0 ]; then
  log "all ${#NAMES[@]} meshes present in $MESHES, nothing to do"
  exit 0
fi
log "missing: ${missing[*]}"

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO=sudo
# As root, apt-get download drops privileges to _apt, which cannot write into our cache
# dir and then warns; download as root directly (same as what apt falls back to).
APT_OPTS=(-q)
[ "$(id -u)" -eq 0 ] && APT_OPTS+=(-o APT::Sandbox::User=root)

DEB_DIR="$CACHE/deb"
mkdir -p "$DEB_DIR" "$MESHES"
# Newest cached .deb (glob order sorts versions well enough for one package), or "".
cached_deb() {
  local debs=("$DEB_DIR/${PKG}"_*.deb)
  [ -e "${debs[0]}" ] && echo "${debs[-1]}"
  return 0
}
deb="$(cached_deb)"
if [ -z "$deb" ]; then
  log "apt-get download $PKG -> $DEB_DIR"
  if ! (cd "$DEB_DIR" && apt-get "${APT_OPTS[@]}" download "$PKG" >/dev/null); then
    log "download failed; running apt-get update and retrying once"
    $SUDO apt-get update -qq
    (cd "$DEB_DIR" && apt-get "${APT_OPTS[@]}" download "$PKG" >/dev/null) ||
      die "apt-get download $PKG failed (is a Debian mirror reachable?)"
  fi
  deb="$(cached_deb)"
  [ -n "$deb" ] || die "apt-get download reported success but no ${PKG}_*.deb in $DEB_DIR"
else
  log "using cached $(basename "$deb")"
fi
version="$(dpkg-deb -f "$deb" Version)"

work="$(mktemp -d "$CACHE/extract.XXXXXX")"
trap 'rm -rf "$work"' EXIT
log "dpkg -x $(basename "$deb")"
dpkg -x "$deb" "$work/pkg"

data_tar=""
for t in "${DATA_TARS[@]}"; do
  if [ -f "$work/pkg/$t" ]; then data_tar="$t"; break; fi
done
[ -n "$data_tar" ] || die "none of ${DATA_TARS[*]} found in $(basename "$deb")"

members=()
for n in "${NAMES[@]}"; do members+=("data/meshes/$n.off"); done
listing="$(tar -tf "$work/pkg/$data_tar")"
for m in "${members[@]}"; do
  grep -qxF "$m" <<<"$listing" || die "$m is not in $data_tar of $PKG $version"
done

log "extracting ${#members[@]} meshes from $data_tar"
tar -xf "$work/pkg/$data_tar" -C "$work" "${members[@]}"
for n in "${NAMES[@]}"; do
  mv -f "$work/data/meshes/$n.off" "$MESHES/$n.off"
done

{
  echo "package: $PKG $version ($(basename "$deb"))"
  echo "archive: $data_tar"
  echo "members: data/meshes/{$(IFS=,; echo "${NAMES[*]}")}.off"
  echo "fetched: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  (cd "$MESHES" && for n in "${NAMES[@]}"; do sha256sum "$n.off"; done)
} >"$MESHES/SOURCE.txt"

for n in "${NAMES[@]}"; do
  # OFF header: "OFF" then "nV nF nE" on the first non-comment line after it.
  counts="$(awk '/^[ \t]*(#|$)/{next} NR==1 && /^OFF[ \t]*$/{next} {print $1" vertices, "$2" facets"; exit}' "$MESHES/$n.off")"
  log "  $n.off: $counts, $(stat -c %s "$MESHES/$n.off") bytes"
done
log "done: $PKG $version -> $MESHES (provenance in SOURCE.txt)"
