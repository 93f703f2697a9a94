#!/usr/bin/env bash
# `binpick simulate --empty-bin` from the command line: a bin of 3 parts emptied by the cell and the
# simulated robot, one line per cycle and the summary on stdout, emptying.json and the cell's files
# written; bad options refused with one line and exit code 1.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$binpick" simulate --part clamp --objects 3 --seed 2 --empty-bin --max-cycles 8 --out "$work/run" \
  >"$work/out.txt" 2>"$work/err.txt" || fail "simulate --empty-bin exited $?"
grep -q '^cycle 1: 3 in the bin' "$work/out.txt" || fail "no line for cycle 1: $(head -n 3 "$work/out.txt")"
summary=$(grep '^cleared ' "$work/out.txt")
[[ "$summary" =~ ^cleared\ ([0-9]+)/3\ in\ [0-9]+\ cycles,\ ([0-9]+)\ failed ]] || fail "no summary line: $summary"
[ "${BASH_REMATCH[1]:-0}" -ge 2 ] || fail "cleared only ${BASH_REMATCH[1]:-0} of 3: $summary"
for f in emptying.json cell/binpickd.yaml cell/part.ply cell/calib.yaml; do
  [ -s "$work/run/$f" ] || fail "no $f"
done
ls "$work"/run/cycles/cycle-*/overlay.png >/dev/null 2>&1 || fail "no overlay saved for any cycle"
grep -q '"end": "' "$work/run/emptying.json" || fail "emptying.json has no end"

# The output directory must be new; an unknown gripper is named.
"$binpick" simulate --part clamp --objects 3 --empty-bin --out "$work/run" 2>"$work/err2.txt"
[ $? -eq 1 ] || fail "an existing --out was accepted"
"$binpick" simulate --part clamp --objects 3 --empty-bin --gripper magnet --out "$work/other" 2>"$work/err3.txt"
[ $? -eq 1 ] && grep -q 'magnet' "$work/err3.txt" || fail "an unknown gripper was not named: $(cat "$work/err3.txt")"
# Options of the other modes are refused as usage errors (exit code 2), before any work.
"$binpick" simulate --part clamp --empty-bin --cloud-only --out "$work/mixed" 2>"$work/err4.txt"
[ $? -eq 2 ] && grep -q -- '--cloud-only excludes --empty-bin' "$work/err4.txt" || fail "--cloud-only was taken: $(cat "$work/err4.txt")"
"$binpick" simulate --part clamp --max-cycles 2 --out "$work/mixed" 2>"$work/err5.txt"
[ $? -eq 2 ] && grep -q -- '--max-cycles requires --empty-bin' "$work/err5.txt" || fail "--max-cycles was taken: $(cat "$work/err5.txt")"
[ ! -e "$work/mixed" ] || fail "a refused simulation wrote its directory"

[ "$failures" -eq 0 ] && echo "empty-bin command line: all checks passed"
exit "$failures"
