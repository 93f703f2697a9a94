#!/usr/bin/env bash
# Real captures from another rig (the shared real data set: five chessboard poses under OpenCV's
# Gray-code sequence, code step 2, an OpenCV XML calibration in millimetres) imported as they
# come and reconstructed, with no hand conversion (1024 x 768 codes of 2 x 2 pixels: a 2048 x 1536
# projector); a sequence that does not fit is refused with
# one line. Skipped (exit 77) where the data set is not beside the sources.
set -uo pipefail
binpick="$1"
source "$(dirname "$0")/real_captures.sh"  # require_real_captures, import_real_capture
require_real_captures "$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

for i in 0 1 2 3 4; do
  out="$work/capture_$i"
  import_real_capture "$i" "$out"
  grep -q "^imported 42 images (graycode_00.png as gray_col_00 .. graycode_41.png as black)" "$work/import.log" ||
    fail "capture_$i: $(cat "$work/import.log")"
  "$binpick" reconstruct --capture "$out" --out "$work/cloud.ply" >"$work/reconstruct.log" 2>&1 ||
    fail "reconstruct of capture_$i exited $?: $(cat "$work/reconstruct.log")"
  read -r points _ pixels _ < <(grep -o '^[0-9]* points of [0-9]* pixels' "$work/reconstruct.log" | tr -d 'a-z')
  # The wall behind the board and the board's white squares get points: 58-77% of the image.
  [ "${points:-0}" -gt $((pixels / 2)) ] || fail "capture_$i: ${points:-no} points of ${pixels:-?} pixels"
done

# 42 images are not binpick's 52: refused, one line naming both counts.
"$binpick" import-capture --images "$data/capture_0" --preset binpick --projector 2048x1536 \
  --opencv-calib "$data/calibration_result.xml" --out "$work/refused" >"$work/refused.log" 2>&1
code=$?
[ "$code" -eq 1 ] || fail "a sequence of another length exited $code"
[ "$(wc -l <"$work/refused.log")" -eq 1 ] || fail "more than one line: $(cat "$work/refused.log")"
grep -q "42 images (graycode_00.png .. graycode_41.png), but the sequence has" "$work/refused.log" ||
  fail "$(cat "$work/refused.log")"
[ ! -e "$work/refused" ] || fail "a refused import left a directory"

# The same patterns taken for a smaller projector: their row codes run past its bottom. Refused,
# one line naming the size and the options, nothing written.
"$binpick" import-capture --images "$data/capture_0" --preset opencv-graycode --projector 1920x1080 --code-step 2 \
  --opencv-calib "$data/calibration_result.xml" --out "$work/small" >"$work/small.log" 2>&1
code=$?
[ "$code" -eq 1 ] || fail "a projector too small for the codes exited $code"
grep -q "name codes beyond a 1920x1080 projector at code step 2 (960x540 codes): give the projector size" \
  "$work/small.log" || fail "$(cat "$work/small.log")"
[ ! -e "$work/small" ] || fail "a refused import left a directory"

[ "$failures" -eq 0 ]
