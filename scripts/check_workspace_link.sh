#!/usr/bin/env bash
# The workspace's package is a directory of links into the repository
# (scripts/link_package.sh), so that rosrun's `find -L` over the package meets
# no file system loop even with the workspace inside the repository (the
# default .ws). Checks the link sync on a scratch workspace (migration of the
# former single link, a dangling link, a link leading elsewhere), then the
# built workspace: the package directory, `rospack find` and `rosrun` from the
# devel space, with no "File system loop" on stderr. Run after scripts/build.sh
# (scripts/test.sh does).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
fail() {
  echo "check_workspace_link: FAIL: $*" >&2
  exit 1
}

scratch="$(mktemp -d "${TMPDIR:-/tmp}/bowg_link_check.XXXXXX")"
# rm -r removes the links, never what they lead to.
trap 'rm -rf "$scratch"' EXIT

# 1. The link sync on a scratch workspace.
pkg="$scratch/src/bowg_ros"
mkdir -p "$scratch/src"
ln -s "$repo" "$pkg"
bash "$repo/scripts/link_package.sh" "$scratch" > /dev/null
[ -d "$pkg" ] && [ ! -L "$pkg" ] || fail "$pkg is still a link after the migration"
ln -s "$repo/no_such_entry" "$pkg/no_such_entry"
ln -sfn "$scratch" "$pkg/docs"
bash "$repo/scripts/link_package.sh" "$scratch"
[ ! -L "$pkg/no_such_entry" ] || fail "the dangling link $pkg/no_such_entry was kept"
[ "$(readlink "$pkg/docs")" = "$repo/docs" ] || fail "$pkg/docs leads to $(readlink "$pkg/docs"), not $repo/docs"
[ ! -e "$pkg/.git" ] || fail "$pkg/.git is linked"
shopt -s dotglob nullglob
for entry in "$repo"/*; do
  name="${entry##*/}"
  case "$name" in .git) continue ;; esac
  if [ -d "$entry" ] && [ -e "$entry/.catkin_workspace" ]; then
    [ ! -e "$pkg/$name" ] || fail "the workspace $entry is linked into the package"
    continue
  fi
  [ "$(readlink "$pkg/$name")" = "$entry" ] || fail "$pkg/$name does not lead to $entry"
done
shopt -u dotglob nullglob
echo "link sync: migration, dangling and misdirected links ok"

# 2. The built workspace.
[ -f "$ws/devel/setup.bash" ] || fail "no $ws/devel/setup.bash: build first (scripts/build.sh)"
[ -d "$ws/src/bowg_ros" ] && [ ! -L "$ws/src/bowg_ros" ] \
  || fail "$ws/src/bowg_ros is not a directory of links"
ws_real="$(cd "$ws" && pwd -P)"
for link in "$ws/src/bowg_ros"/* "$ws/src/bowg_ros"/.[!.]*; do
  [ -d "$link" ] || continue
  case "$ws_real/" in "$(cd "$link" && pwd -P)"/*) fail "$link holds the workspace itself" ;; esac
done
case "$ws_real/" in
  "$(cd "$repo" && pwd -P)"/*) echo "workspace $ws lies inside the repository" ;;
  *) echo "note: workspace $ws lies outside the repository (no loop possible either way)" ;;
esac
# A clean environment: only the devel space, the system's ROS and the tools.
out="$scratch/rosrun.out"
err="$scratch/rosrun.err"
set +e
env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c '
  source "$1/devel/setup.bash" || exit 3
  found="$(rospack find bowg_ros)"
  if [ "$found" != "$1/src/bowg_ros" ]; then
    echo "rospack find bowg_ros: $found, not $1/src/bowg_ros" >&2
    exit 4
  fi
  find -L "$found" -name no_such_file
  timeout 60 rosrun bowg_ros bowg_convert_vocabulary --help' _ "$ws" > "$out" 2> "$err"
status=$?
set -e
if grep -q 'File system loop' "$err"; then
  head -n 5 "$err" >&2
  fail "find -L / rosrun over the package report a file system loop"
fi
[ "$status" -eq 0 ] || { cat "$err" >&2; fail "rosrun bowg_ros bowg_convert_vocabulary --help exited $status"; }
grep -q '^usage: bowg_convert_vocabulary' "$out" || fail "rosrun bowg_ros bowg_convert_vocabulary --help printed no usage"
echo "devel space: rospack find, find -L and rosrun over the package without a file system loop"
echo "check_workspace_link: ok"
