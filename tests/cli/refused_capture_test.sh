#!/usr/bin/env bash
# Captures that lie about what they show: `binpick reconstruct` refuses each with exit code 1 and
# one line on stderr naming the culprit; the untouched capture reconstructs, its summary on stdout.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$binpick" simulate --part clamp --objects 3 --seed 5 --out "$work/capture" 2>/dev/null || fail "simulate exited $?"

"$binpick" reconstruct --capture "$work/capture" --out "$work/cloud.ply" >"$work/out.txt" 2>"$work/err.txt" ||
  fail "reconstruct of the untouched capture exited $?: $(cat "$work/err.txt")"
grep -q "points of 1310720 pixels" "$work/out.txt" || fail "no summary on stdout: '$(cat "$work/out.txt")'"
[ -s "$work/err.txt" ] && fail "reconstruct of the untouched capture wrote to stderr: $(cat "$work/err.txt")"

expect_refusal() {  # expect_refusal "pattern" DIR [reconstruct options...]: exit 1, one stderr line naming it
  local pattern="$1" dir="$2"; shift 2
  local err code
  err=$("$binpick" reconstruct --capture "$dir" --out "$work/refused.ply" "$@" 2>&1 >/dev/null)
  code=$?
  [ "$code" -eq 1 ] || fail "reconstruct of $dir exited $code, expected 1"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "reconstruct of $dir printed more than one line: $err"
  printf '%s\n' "$err" | grep -q -- "$pattern" || fail "reconstruct of $dir said '$err', expected '$pattern'"
  [ -e "$work/refused.ply" ] && fail "a refused capture wrote a cloud"
}
damaged() {  # damaged NAME: a copy of the capture to damage
  cp -r "$work/capture" "$work/$1"
}
swap() {  # swap A B: exchange two files
  mv "$1" "$1.tmp" && mv "$2" "$1" && mv "$1.tmp" "$2"
}

damaged phase && swap "$work/phase/images/025_phase_col_1.png" "$work/phase/images/027_phase_col_3.png"
expect_refusal "capture $work/phase: column phase steps out of order (step 1 and step 3 swapped?" "$work/phase"

damaged gray && swap "$work/gray/images/008_gray_col_03.png" "$work/gray/images/009_gray_col_03_inv.png"
expect_refusal "capture $work/gray: images 008_gray_col_03 and 009_gray_col_03_inv are swapped (pattern and inverse)" \
  "$work/gray"

sed -e 's/projector_width: 1280/projector_width: 1024/' -e 's/projector_height: 800/projector_height: 768/' \
  "$work/capture/calib.yaml" >"$work/other_projector.yaml"
grep -q "projector_width: 1024" "$work/other_projector.yaml" || fail "calib.yaml has no projector_width: 1280"
expect_refusal "pattern set is for a 1280x800 projector but the calibration's projector is 1024x768" \
  "$work/capture" --calib "$work/other_projector.yaml"

# A PNG cut short inside its pixel data: libpng would print its own complaint first.
damaged truncated && head -c 3000 "$work/capture/images/014_gray_col_06.png" >"$work/truncated/images/014_gray_col_06.png"
expect_refusal "014_gray_col_06.png: not a readable PNG image: truncated" "$work/truncated"

[ "$failures" -eq 0 ] || exit 1
echo "all refused-capture checks passed"
