#!/usr/bin/env bash
# Fetches OpenArena's Quake 3 maps and textures from Debian's packages into a cache folder outside
# the repository (nothing of it is committed) and prints the folder of the .pk3 archives.
#   scripts/fetch-openarena.sh [CACHE]   (default: $VT_DATA_CACHE, else ~/.cache/vt)
# Idempotent: a complete earlier fetch is reused. Needs apt-get (Debian 12); about 290 MB.
set -euo pipefail

cache="${1:-${VT_DATA_CACHE:-${HOME:-/tmp}/.cache/vt}}/openarena"
packages=(openarena-081-maps openarena-081-textures openarena-data openarena-085-data
          openarena-088-data)
baseoa="$cache/baseoa"
if [[ -f "$cache/complete" ]]; then
  echo "$baseoa"
  exit 0
fi

staging=$(mktemp -d "${TMPDIR:-/tmp}/vt-openarena.XXXXXX")
trap 'rm -rf "$staging"' EXIT
chmod 755 "$staging"  # apt-get downloads as its own user
download() { (cd "$staging" && apt-get download -q "${packages[@]}" >&2); }
if ! download; then
  # A fresh machine has no package lists yet.
  echo "fetch-openarena: updating the package lists" >&2
  sudo=()
  ((EUID == 0)) || sudo=(sudo)
  "${sudo[@]}" apt-get update -qq >&2
  download
fi
for deb in "$staging"/*.deb; do dpkg-deb -x "$deb" "$staging/root"; done
mkdir -p "$cache"
rm -rf "$baseoa"
mkdir -p "$baseoa"
mv "$staging"/root/usr/share/games/openarena/baseoa/*.pk3 "$baseoa/"
touch "$cache/complete"
echo "$baseoa"
