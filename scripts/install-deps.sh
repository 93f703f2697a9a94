#!/usr/bin/env bash
# Installs the Debian 12 packages binpick needs to build, test and run, skipping those present.
# Safe to run repeatedly; uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build
  libeigen3-dev libnanoflann-dev
  libopencv-dev libopencv-contrib-dev
  libpcl-dev
  libbullet-dev libbullet-extras-dev libembree-dev
  libaravis-dev
  libgpiod-dev
  libspdlog-dev libfmt-dev
  libcli11-dev                   # the command lines of binpick and binpickd
  libcpp-httplib-dev             # binpickd's web view
  nlohmann-json3-dev libyaml-cpp-dev
  libgtest-dev libgmock-dev
  systemd                        # systemd-analyze checks the service unit in the tests
  dpkg-dev file                  # the Debian package: dpkg-shlibdeps finds its Depends, dpkg-deb reads it back
  chromium chromium-driver python3-selenium  # the web view's test in a real headless browser
  clang libclang-rt-14-dev       # libFuzzer for the robot protocol's fuzz test
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
