#!/bin/sh
# Usage: verify_unit.sh SYSTEMD_ANALYZE UNIT_FILE
# Runs `systemd-analyze verify` on the unit and fails on any line naming it (a warning is a
# failure). Lines not naming the unit are the analyzer's own (in a container it may complain
# about the manager) and are shown but ignored. Exits 77 (skipped) when there is no
# systemd-analyze, or when it does not report a deliberately broken copy of the unit: then it
# cannot check anything here, and passing would be a lie.
set -u
analyze=$1
unit=$2
name=$(basename "$unit")

if [ -z "$analyze" ] || [ ! -x "$analyze" ]; then
  echo "systemd-analyze not found (Debian package systemd): skipped"
  exit 77
fi
[ -f "$unit" ] || { echo "$unit: no such unit file"; exit 1; }

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

mkdir "$scratch/broken"
awk '{ print } /^\[Service\]$/ { print "NoSuchSettingForTheCanary=1" }' "$unit" > "$scratch/broken/$name"
canary=$("$analyze" verify "$scratch/broken/$name" 2>&1)
if ! printf '%s\n' "$canary" | grep -F "$name" | grep -q NoSuchSettingForTheCanary; then
  echo "systemd-analyze does not report a broken unit here; skipped. Its output:"
  printf '%s\n' "$canary"
  exit 77
fi

output=$("$analyze" verify "$unit" 2>&1)
status=$?
complaints=$(printf '%s\n' "$output" | grep -F "$name")
if [ -n "$complaints" ]; then
  echo "systemd-analyze verify $unit (exit status $status) complains:"
  printf '%s\n' "$complaints"
  exit 1
fi
echo "$unit: no complaints (exit status $status)"
[ -n "$output" ] && printf 'unrelated analyzer output:\n%s\n' "$output"
exit 0
