#!/usr/bin/env bash
# Installs missing packages, then configures and builds binpick (Release) into build/: every
# target, or only those named (e.g. `bash scripts/build.sh binpick`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
