#!/bin/sh
# Usage: unit_exposure.sh SYSTEMD_ANALYZE UNIT_FILE THRESHOLD
# `systemd-analyze security --offline` on the unit file: fails when its overall exposure is above
# THRESHOLD tenths (15: 1.5), printing what the analyzer holds against it. Exits 77 (skipped)
# when there is no systemd-analyze or it cannot analyse unit files offline (before systemd 250).
set -u
analyze=$1
unit=$2
threshold=$3

if [ -z "$analyze" ] || [ ! -x "$analyze" ]; then
  echo "systemd-analyze not found (Debian package systemd): skipped"
  exit 77
fi
if ! "$analyze" security --help 2>&1 | grep -q -- "--offline"; then
  echo "systemd-analyze cannot analyse unit files offline here: skipped"
  exit 77
fi
output=$("$analyze" security --offline=yes --threshold="$threshold" "$unit" 2>&1)
status=$?
printf '%s\n' "$output" | grep -E "✗|Overall"
if [ "$status" -ne 0 ]; then
  echo "$unit: exposure above $threshold/10"
  exit 1
fi
exit 0
