#!/usr/bin/env bash
# binpick calibrate rig end to end: a rendered calibration sequence of the virtual cell (the one
# the library tests use) calibrated from its directory and through the live path against a fake
# camera; the written calib.yaml read back by reconstruct; and bad input refused with exit code 1
# and a message naming the view.
set -uo pipefail
binpick="$1"
data=$("$2") || { echo "FAIL: no test data"; exit 1; }
seq="$data/sequence"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# From a sequence directory: every pose, a table row each, the file with its quality.
"$binpick" calibrate rig --sequence "$seq" --out "$work/calib.yaml" >"$work/table.txt" 2>"$work/log.txt" ||
  fail "calibrate rig --sequence exited $?: $(cat "$work/log.txt")"
[ "$(grep -c '/pose_0[0-9][0-9] .* used$' "$work/table.txt")" -eq 10 ] || fail "table: $(cat "$work/table.txt")"
grep -q "10 of 10 views used; RMS camera" "$work/table.txt" || fail "no totals: $(cat "$work/table.txt")"
grep -q "^quality:" "$work/calib.yaml" || fail "calib.yaml holds no quality"
grep -q 'date: "20[0-9][0-9]-[01][0-9]-[0-3][0-9]T[0-9:.]*Z"' "$work/calib.yaml" || fail "calib.yaml holds no UTC date"
# Reconstruction reads the new calibration.
"$binpick" reconstruct --capture "$seq/pose_000" --calib "$work/calib.yaml" --out "$work/board.ply" \
  2>/dev/null || fail "reconstruct with the new calib.yaml exited $?"
[ -s "$work/board.ply" ] || fail "reconstruct wrote no cloud"

expect_error() {  # expect_error "pattern" command...
  local pattern="$1"; shift
  local err
  err=$("$@" 2>&1 >/dev/null </dev/null)
  local code=$?
  [ "$code" -eq 1 ] || fail "'$*' exited $code, expected 1"
  echo "$err" | tail -n 1 | grep -q -- "$pattern" || fail "'$*' said '$err', expected '$pattern'"
}
source "$(dirname "$0")/usage_error.sh"  # expect_usage_error
mkdir -p "$work/corrupt" && printf '{"format_version": 1, "source": ' > "$work/corrupt/capture.json"
# Views listed one by one; a view without the board is named among the unusable ones.
expect_error "1 usable view of 2, at least 3 needed; not usable: $data/no_board (board not found" \
  "$binpick" calibrate rig --views "$seq/pose_000" "$data/no_board" --out "$work/x.yaml"
expect_error "$data/no_rows: the capture has no row codes" \
  "$binpick" calibrate rig --views "$data/no_rows" "$seq/pose_000" --out "$work/x.yaml"
expect_error "$work/corrupt" "$binpick" calibrate rig --views "$work/corrupt" --out "$work/x.yaml"
expect_error "$work/empty: holds no capture directory" \
  bash -c "mkdir -p '$work/empty' && '$binpick' calibrate rig --sequence '$work/empty' --out '$work/x.yaml'"
expect_usage_error "--sequence, --views, --camera or --fake-camera is required" "$binpick" calibrate rig --out "$work/x.yaml"
expect_usage_error "--sequence excludes --views" "$binpick" calibrate rig --sequence "$seq" --views "$seq/pose_000" --out "$work/x.yaml"
expect_usage_error "--sequence excludes --record" "$binpick" calibrate rig --sequence "$seq" --record "$work/r" --out "$work/x.yaml"
expect_usage_error "--out is required" "$binpick" calibrate rig --sequence "$seq"
expect_error "board options" "$binpick" calibrate rig --sequence "$seq" --squares 2x7 --out "$work/x.yaml"
expect_usage_error "--squares excludes --inner-corners" "$binpick" calibrate rig --sequence "$seq" --squares 9x7 --inner-corners 8x6 --out "$work/x.yaml"
expect_error "--inner-corners 1x5: a chessboard needs at least 2x2 inner corners (3x3 squares); for the squares use --squares" \
  "$binpick" calibrate rig --sequence "$seq" --board chessboard --inner-corners 1x5 --out "$work/x.yaml"
expect_error "--squares 2x7: a board needs at least 3x3 squares (2x2 inner corners); for the inner corners use --inner-corners" \
  "$binpick" calibrate rig --sequence "$seq" --squares 2x7 --out "$work/x.yaml"
expect_usage_error "--min-views: must be at least 3" "$binpick" calibrate rig --sequence "$seq" --min-views 2 --out "$work/x.yaml"
expect_usage_error "--projector-distortion" "$binpick" calibrate rig --sequence "$seq" --projector-distortion k1,p1 --out "$work/x.yaml"
[ ! -e "$work/x.yaml" ] || fail "a refused calibration wrote a file"

# The live path: one view per line on stdin, each recorded before it is used.
printf '\n\n\n' | "$binpick" calibrate rig --fake-camera "$seq" --record "$work/live" --count 3 --min-views 3 \
  --out "$work/live.yaml" >/dev/null 2>"$work/live.log" || fail "live calibration exited $?: $(tail -n 3 "$work/live.log")"
for view in view_000 view_001 view_002; do
  [ -s "$work/live/$view/capture.json" ] || fail "live view $view was not recorded"
done
grep -q "^quality:" "$work/live.yaml" || fail "live calibration wrote no calib.yaml"
# Stopped early: what was taken stays on disk, and too few views is an error.
printf '\nq\n' | "$binpick" calibrate rig --fake-camera "$seq" --record "$work/short" --count 3 --min-views 3 \
  --out "$work/short.yaml" >/dev/null 2>"$work/short.log"
[ $? -eq 1 ] || fail "a session stopped after one view did not fail"
grep -q "1 usable view of 1, at least 3 needed" "$work/short.log" || fail "short session: $(tail -n 1 "$work/short.log")"
[ -s "$work/short/view_000/capture.json" ] && [ ! -e "$work/short/view_001" ] || fail "short session recorded the wrong views"
expect_error "$work/live: already exists and is not empty" \
  "$binpick" calibrate rig --fake-camera "$seq" --record "$work/live" --count 3 --out "$work/x.yaml"

[ "$failures" -eq 0 ] && echo "calibrate rig CLI: all checks passed"
exit "$failures"
