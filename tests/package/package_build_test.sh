#!/usr/bin/env bash
# Usage: package_build_test.sh CPACK BUILD_DIR OUT_DIR VERSION
# Builds the Debian package from the build tree (as scripts/package.sh does) into OUT_DIR/dist and
# checks what a cell PC gets: the file list, the conffile, Depends (from dpkg-shlibdeps: the
# runtime libraries, none of the lab's), and the maintainer scripts.
set -uo pipefail
cpack=$1 build=$2 out=$3 version=$4
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

rm -rf "$out" && mkdir -p "$out"
if ! (cd "$out" && "$cpack" -G DEB --config "$build/CPackConfig.cmake" -B "$out" >"$out/cpack.log" 2>&1); then
  echo "cpack failed:"; cat "$out/cpack.log"; exit 1
fi
arch=$(dpkg --print-architecture)
deb="$out/dist/binpick_${version}_${arch}.deb"
[ -f "$deb" ] || { echo "FAIL: no $deb; cpack wrote: $(ls "$out/dist")"; exit 1; }

files=$(dpkg-deb -c "$deb" | awk '{ print $6 }' | sed 's#^\./#/#')
for expected in /usr/bin/binpick /usr/bin/binpickd /usr/lib/binpick/libbinpick_image_codecs.so \
    /usr/lib/binpick/libbinpick_http_transport.so /usr/lib/binpick/libbinpick_aravis.so \
    /usr/lib/systemd/system/binpickd.service \
    /etc/binpick/binpickd.yaml /usr/share/binpick/models/l_bracket.ply /usr/share/doc/binpick/copyright \
    /usr/share/doc/binpick/install.md /usr/share/doc/binpick/binpickd.md /usr/share/doc/binpick/README.md \
    /usr/share/doc/binpick/examples/binpickd.yaml /usr/share/doc/binpick/examples/detection.yaml; do
  printf '%s\n' "$files" | grep -qxF "$expected" || fail "the package has no $expected"
done
# Nothing outside the Debian layout: no /usr/local, no state, no build paths.
stray=$(printf '%s\n' "$files" | grep -v -E '^/(etc/binpick|usr/bin|usr/lib/binpick|usr/lib/systemd/system|usr/share/(binpick|doc/binpick))(/|$)' |
  grep -v -E '^/(etc|usr|usr/lib|usr/lib/systemd|usr/share|usr/share/doc)?/$')
[ -z "$stray" ] || fail "files outside the package's places: $stray"

control=$out/control
dpkg-deb -e "$deb" "$control"
[ "$(cat "$control/conffiles")" = /etc/binpick/binpickd.yaml ] ||
  fail "conffiles is '$(cat "$control/conffiles")', not /etc/binpick/binpickd.yaml"
for script in postinst prerm postrm; do
  [ -x "$control/$script" ] || fail "no executable $script"
  sh -n "$control/$script" || fail "$script is not valid sh"
done
grep -q 'addgroup --system gpio' "$control/postinst" || fail "postinst does not create the gpio group"
grep -q 'gpiochip' "$control/postinst" || fail "postinst writes no udev rule for the GPIO chips"
grep -v '^ *#' "$control/postinst" | grep -q 'systemctl enable' && fail "postinst enables the service before it is configured"

depends=$(dpkg-deb -f "$deb" Depends)
for library in libopencv-core libopencv-imgcodecs libcpp-httplib libaravis-0.8 libgpiod libspdlog libyaml-cpp libc6 adduser udev; do
  printf '%s\n' "$depends" | grep -q "$library" || fail "Depends lacks $library: $depends"
done
for lab in libpcl libvtk; do
  printf '%s\n' "$depends" | grep -q "$lab" && fail "Depends names $lab, which only the tests and the benchmark use"
done
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "Version is $(dpkg-deb -f "$deb" Version)"

[ "$failures" -eq 0 ] && echo "package $(basename "$deb"): $(printf '%s\n' "$files" | grep -vc '/$') files, conffile and Depends as expected"
exit "$failures"
