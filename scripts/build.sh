#!/usr/bin/env bash
# Installs missing packages, then configures and builds binpick (Release) into build/: every
# target, or only those named (e.g. `bash scripts/build.sh binpick`). BINPICK_WARNINGS_AS_ERRORS=ON
# in the environment (CI: .ci/run) makes a warning in binpick's own code fail the build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
options=()
# Passed only when set, so that a build/ configured by hand keeps its own choice.
if [[ -n "${BINPICK_WARNINGS_AS_ERRORS:-}" ]]; then
  options+=(-DBINPICK_WARNINGS_AS_ERRORS="$BINPICK_WARNINGS_AS_ERRORS")
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${options[@]}" >/dev/null
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
