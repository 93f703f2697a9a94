#!/usr/bin/env bash
# binpick's command line conventions: --help (the tool and every subcommand) and --version print
# on stdout with exit code 0 and nothing on stderr; a usage error exits 2 with one line on stderr
# that points to --help; a run error (bad input) still exits 1 with one line.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

expect_help() {  # expect_help ARGS...: usage on stdout, exit 0, stderr empty
  "$binpick" "$@" >"$work/out" 2>"$work/err"
  local code=$?
  [ "$code" -eq 0 ] || fail "'$*' exited $code: $(cat "$work/err")"
  [ ! -s "$work/err" ] || fail "'$*' wrote to stderr: $(cat "$work/err")"
  grep -q "^Usage: binpick" "$work/out" || fail "'$*' printed no usage: $(head -n 3 "$work/out")"
}

expect_help --help
expect_help -h
grep -q "^Subcommands:" "$work/out" || fail "binpick -h lists no subcommands"
for command in capture reconstruct detect simulate evaluate calibrate "calibrate rig" "calibrate hand-eye" grasps \
  robot-client; do
  # shellcheck disable=SC2086 # "calibrate rig" is two words
  expect_help $command --help
  grep -q "^Usage: binpick $command " "$work/out" || fail "'$command --help' is not its usage: $(head -n 2 "$work/out")"
done
# The options a subcommand declares are what its help shows: simulate's whole set.
"$binpick" simulate --help >"$work/out"
for option in --part --mesh --mesh-scale --objects --seed --threads --bit-depth --cloud-only --out --empty-bin \
  --gripper --max-cycles --cup-diameter --tool-radius --stroke --bin-length --bin-width --bin-wall-height \
  --camera-height --calibration-board --poses --hand-eye --views --robot-noise-mm --robot-noise-deg \
  --orientation --list-parts --export-part; do
  grep -q -- "^ *$option " "$work/out" || fail "simulate --help does not show $option"
done

"$binpick" --version >"$work/out" 2>"$work/err"
code=$?
[ "$code" -eq 0 ] && [ ! -s "$work/err" ] || fail "--version exited $code: $(cat "$work/err")"
grep -Eq '^binpick [0-9]+\.[0-9]+\.[0-9]+( \(git [^)]+\))?$' "$work/out" || fail "--version printed '$(cat "$work/out")'"

expect_usage_error() {  # expect_usage_error "pattern" ARGS...: exit 2, one line naming it and --help
  local pattern="$1"
  shift
  "$binpick" "$@" >"$work/out" 2>"$work/err" </dev/null
  local code=$?
  [ "$code" -eq 2 ] || fail "'$*' exited $code, expected 2: $(cat "$work/err")"
  [ "$(wc -l <"$work/err")" -eq 1 ] || fail "'$*' printed $(wc -l <"$work/err") lines: $(cat "$work/err")"
  grep -q -- "$pattern" "$work/err" || fail "'$*' said '$(cat "$work/err")', expected '$pattern'"
  grep -q -- "--help" "$work/err" || fail "'$*' gives no hint to --help: $(cat "$work/err")"
  [ ! -s "$work/out" ] || fail "'$*' wrote to stdout: $(cat "$work/out")"
}
expect_usage_error "subcommand is required"
expect_usage_error "not expected: frobnicate" frobnicate
expect_usage_error "subcommand is required.*binpick calibrate --help" calibrate
expect_usage_error "not expected: stereo" calibrate stereo
expect_usage_error "not expected: --modle" detect --model m.ply --scene s.ply --modle x
expect_usage_error "--model: 1 required MODEL missing" detect --scene s.ply --model
expect_usage_error "--max-objects: needs a whole number, not 'many'" detect --model m.ply --scene s.ply --max-objects many
expect_usage_error "--exposure-us: needs a number, not '1e'" capture --camera 10.0.0.9 --exposure-us 1e --out "$work/c"
expect_usage_error "--scene excludes --capture" detect --model m.ply --scene s.ply --capture "$work"
expect_usage_error "--model is required" detect --scene s.ply
expect_usage_error "--scene or --capture is required" detect --model m.ply
expect_usage_error "--calib requires --capture" detect --model m.ply --scene s.ply --calib c.yaml
# An option of one mode in another is refused, not ignored.
expect_usage_error "--poses requires --calibration-board" simulate --part clamp --poses 4 --out "$work/s"
expect_usage_error "--objects excludes --hand-eye" simulate --hand-eye eye-to-hand --objects 4 --out "$work/s"
expect_usage_error "--seed excludes --list-parts" simulate --list-parts --seed 3
expect_usage_error "--export-part: At least 2 required" simulate --export-part gear
expect_usage_error "--out is required" simulate --part clamp
expect_usage_error "--record requires --listen" calibrate hand-eye --views "$work" --calib c.yaml --setup eye-to-hand \
  --record "$work/r" --out h.yaml
expect_usage_error "--views or --listen is required" calibrate hand-eye --calib c.yaml --setup eye-to-hand --out h.yaml
expect_usage_error "--send excludes --cycles" robot-client --send PING --cycles 2
[ ! -e "$work/s" ] && [ ! -e "$work/c" ] || fail "a refused command wrote its output"

# A run error: the input is bad, not the command line.
"$binpick" detect --model "$work/missing.ply" --scene "$work/missing.ply" >"$work/out" 2>"$work/err"
code=$?
[ "$code" -eq 1 ] || fail "a missing file exited $code, expected 1"
[ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "missing.ply" "$work/err" || fail "a missing file said: $(cat "$work/err")"

[ "$failures" -eq 0 ] && echo "binpick help and usage errors: all checks passed"
exit "$failures"
