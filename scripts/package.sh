#!/usr/bin/env bash
# Builds the Debian package of the cell PC: dist/binpick_<version>_<arch>.deb (cmake/Packaging.cmake,
# docs/install.md). Install it with `apt install ./dist/binpick_*.deb`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh binpick binpickd binpick_example_model
rm -rf build/dist
(cd build && cpack -G DEB >/dev/null)
mkdir -p dist
cp build/dist/binpick_*.deb dist/
ls build/dist/binpick_*.deb | sed 's#^build/##'
