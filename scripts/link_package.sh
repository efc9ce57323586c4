#!/usr/bin/env bash
# Makes WORKSPACE/src/bowg_ros, the package as catkin sees it, a directory
# holding one link per top-level entry of this repository.
#   scripts/link_package.sh WORKSPACE        (scripts/build.sh runs it)
# One link to the whole repository would put a workspace that lies inside the
# repository (the default .ws) inside its own package, and every `find -L`
# over the package (rosrun's) would report a file system loop. Left out: .git,
# the entry holding WORKSPACE and any other catkin workspace in the checkout.
# Synced on every call: missing links are made, links leading elsewhere are
# re-pointed, links to entries that are gone or left out are removed, and a
# former single link to a repository is replaced by the directory.
# (CMakeLists.txt installs from the checkout itself: install() would copy these
# links as links.)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -ne 1 ]; then
  echo "usage: $0 WORKSPACE" >&2
  exit 2
fi
ws="$1"
pkg="$ws/src/bowg_ros"

mkdir -p "$ws/src"
if [ -L "$pkg" ]; then
  echo "link_package: $pkg: replacing the link to the whole repository by a directory of links"
  rm "$pkg"
fi
mkdir -p "$pkg"
ws_real="$(cd "$ws" && pwd -P)"
declare -A wanted=()
shopt -s dotglob nullglob
for entry in "$repo"/*; do
  name="${entry##*/}"
  if [ "$name" = .git ]; then
    continue
  fi
  if [ -d "$entry" ]; then
    real="$(cd "$entry" && pwd -P)"
    case "$ws_real/" in "$real"/*) continue ;; esac
    if [ -e "$entry/.catkin_workspace" ]; then
      continue
    fi
  fi
  wanted[$name]=1
  link="$pkg/$name"
  if [ -e "$link" ] && [ ! -L "$link" ]; then
    echo "link_package: $link is not a link; move it away (the package's entries are links into $repo)" >&2
    exit 1
  fi
  if [ "$(readlink "$link" || true)" != "$entry" ]; then
    ln -sfn "$entry" "$link"
  fi
done
for link in "$pkg"/*; do
  if [ -L "$link" ] && [ -z "${wanted[${link##*/}]:-}" ]; then
    rm "$link"
  fi
done
