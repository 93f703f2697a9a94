#!/bin/sh
# Usage: install_layout.sh CMAKE BUILD_DIR UNIT BINPICKD CONFIG EXPECT_BINPICKD EXPECT_CONFIG
# Installs the build into a scratch DESTDIR and checks that the unit lands at UNIT, that its
# ExecStart starts BINPICKD with CONFIG, and (when EXPECT_... is 1) that these two are installed.
# UNIT, BINPICKD and CONFIG are absolute installed paths (without DESTDIR).
set -u
cmake=$1 build=$2 unit=$3 binpickd=$4 config=$5 expect_binpickd=$6 expect_config=$7

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

if ! DESTDIR="$scratch/root" "$cmake" --install "$build" > "$scratch/install.log" 2>&1; then
  echo "cmake --install failed:"
  cat "$scratch/install.log"
  exit 1
fi

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

[ -f "$scratch/root$unit" ] || fail "the unit is not at $unit"
expected_exec="ExecStart=$binpickd --config $config"
if [ -f "$scratch/root$unit" ] && ! grep -qxF "$expected_exec" "$scratch/root$unit"; then
  fail "the unit has no line '$expected_exec'; it has: $(grep '^ExecStart=' "$scratch/root$unit")"
fi
if [ "$expect_binpickd" = 1 ] && [ ! -x "$scratch/root$binpickd" ]; then
  fail "binpickd is not installed at $binpickd, where the unit starts it"
fi
if [ "$expect_config" = 1 ] && [ ! -f "$scratch/root$config" ]; then
  fail "the example configuration is not installed at $config, where the unit reads it"
fi

if [ "$failures" -ne 0 ]; then
  echo "installed files:"
  (cd "$scratch/root" && find . -type f | sort)
  exit 1
fi
echo "unit, daemon and configuration installed where the unit expects them"
