#!/usr/bin/env bash
# Fills DIR/sysroot with Debian 12's arm64 OpenCV, zlib and googletest for
# the engine's cross-build (scripts/check_arm64.sh): the packages and the
# libraries they need are downloaded with a private apt state in DIR/apt and
# unpacked with dpkg -x. The machine's own packages and apt configuration are
# not touched (no dpkg --add-architecture). Idempotent: a sysroot unpacked
# from the same package list is kept.
# Usage: scripts/arm64_sysroot.sh DIR
set -euo pipefail
dir="${1:?usage: arm64_sysroot.sh DIR}"
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"

# The runtime libraries come with everything they depend on; the -dev
# packages (headers, .so links, libgtest.a) alone.
RUNTIME=(libopencv-core406 libopencv-imgproc406 libopencv-imgcodecs406 libopencv-features2d406
  libopencv-calib3d406 libopencv-flann406 zlib1g)
DEV=(libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-features2d-dev
  libopencv-calib3d-dev libopencv-flann-dev zlib1g-dev libgtest-dev)

stamp="$dir/sysroot/.bowg_packages"
wanted="${RUNTIME[*]} | ${DEV[*]}"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$wanted" ]; then
  echo "arm64_sysroot: $dir/sysroot already holds: $wanted"
  exit 0
fi

apt_dir="$dir/apt"
mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial" "$apt_dir/state" "$apt_dir/dev"
: > "$apt_dir/state/status"  # nothing installed: apt downloads the whole closure
apt_opts=(-o APT::Architecture=arm64 -o APT::Architectures=arm64
  -o Dir::State="$apt_dir/state" -o Dir::State::Lists="$apt_dir/lists"
  -o Dir::State::status="$apt_dir/state/status" -o Dir::Cache="$apt_dir/cache"
  -o APT::Sandbox::User=root -o Debug::NoLocking=1)
echo "arm64_sysroot: downloading arm64 packages into $apt_dir"
apt-get "${apt_opts[@]}" update -qq
# Only this download's versions are unpacked.
apt-get "${apt_opts[@]}" clean
rm -f "$apt_dir"/dev/*.deb
apt-get "${apt_opts[@]}" install -y -qq --download-only --no-install-recommends "${RUNTIME[@]}"
(cd "$apt_dir/dev" && apt-get "${apt_opts[@]}" download "${DEV[@]}")

rm -rf "$dir/sysroot.partial"
mkdir -p "$dir/sysroot.partial"
count=0
for deb in "$apt_dir"/cache/archives/*.deb "$apt_dir"/dev/*.deb; do
  dpkg -x "$deb" "$dir/sysroot.partial"
  count=$((count + 1))
done

# What the packages' maintainer scripts and ld.so.conf would do on an arm64
# machine: libraries found through alternatives (BLAS, LAPACK) or folders of
# their own (HDF4, OGDI) are linked into the main library folder, where the
# cross linker (-rpath-link) and qemu's loader look.
root="$dir/sysroot.partial"
libdir="$root/usr/lib/aarch64-linux-gnu"
# (readelf fails on the .so files that are linker scripts: not libraries.)
needed="$({ find "$root" -name 'lib*.so*' -type f -exec readelf -d {} + 2>/dev/null || true; } \
  | sed -nE 's/.*Shared library: \[(.*)\]/\1/p' | sort -u)"
for name in $needed; do
  if [ -e "$libdir/$name" ] || [ -e "$root/lib/aarch64-linux-gnu/$name" ] \
    || [ -e "/usr/aarch64-linux-gnu/lib/$name" ]; then
    continue
  fi
  found="$(find "$root" -name "$name" \( -type f -o -type l \) | head -n 1)"
  if [ -z "$found" ]; then
    echo "arm64_sysroot: $name, needed by an unpacked library, is in no downloaded package" >&2
    exit 1
  fi
  ln -s "$(realpath --relative-to="$libdir" "$found")" "$libdir/$name"
done
echo "$wanted" > "$root/.bowg_packages"
rm -rf "$dir/sysroot"
mv "$dir/sysroot.partial" "$dir/sysroot"
echo "arm64_sysroot: $count packages unpacked into $dir/sysroot"
