#!/usr/bin/env bash
# Hand-eye calibration through the command line: simulate an eye-to-hand session, calibrate it,
# compare with the truth; then bad input, each exiting 1 with an error naming the problem.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

views="$work/views"
"$binpick" simulate --hand-eye eye-to-hand --views 6 --seed 4 --robot-noise-mm 0.1 \
  --robot-noise-deg 0.05 --orientation fixed_xyz --out "$views" 2>/dev/null || fail "simulate exited $?"
for f in poses.txt calib.yaml truth/hand_eye.yaml view_00.png view_05.png; do
  [ -s "$views/$f" ] || fail "simulate wrote no $f"
done
grep -q '^orientation: fixed_xyz$' "$views/poses.txt" || fail "poses.txt is not in fixed_xyz"

calibrate() {  # calibrate VIEWS_DIR [options...]: the common options, then the given ones
  local dir="$1"; shift
  "$binpick" calibrate hand-eye --views "$dir" --calib "$views/calib.yaml" "$@"
}
calibrate "$views" --setup eye-to-hand --out "$work/hand_eye.yaml" >"$work/table.txt" 2>"$work/warnings.txt" ||
  fail "calibrate exited $?: $(cat "$work/warnings.txt")"
grep -q '^view_03  *48/48 ' "$work/table.txt" || fail "no row for view_03 with 48 corners: $(cat "$work/table.txt")"
grep -q '^eye-to-hand, method auto (.*+refine), 6 views: residual RMS' "$work/table.txt" || fail "no result line"
grep -q '^  T_base_camera:$' "$work/hand_eye.yaml" || fail "hand_eye.yaml has no T_base_camera"

# The recovered camera position within 3 mm of the truth (6 noisy views).
position() { grep -A1 "^  T_base_camera:" "$1" | sed -n 's/.*translation: \[\(.*\)\].*/\1/p' | tr -d ','; }
read -r x y z <<<"$(position "$work/hand_eye.yaml")"
read -r tx ty tz <<<"$(position "$views/truth/hand_eye.yaml")"
error_mm=$(awk -v x="$x" -v y="$y" -v z="$z" -v a="$tx" -v b="$ty" -v c="$tz" \
  'BEGIN { printf "%.3f", 1000 * sqrt((x-a)^2 + (y-b)^2 + (z-c)^2) }')
awk -v e="$error_mm" 'BEGIN { exit !(e < 3.0) }' || fail "T_base_camera is $error_mm mm off the truth"

expect_error() {  # expect_error "pattern" command...: exit code 1, the last stderr line names it
  local pattern="$1"; shift
  local err
  err=$("$@" 2>&1 >/dev/null)
  local code=$?
  [ "$code" -eq 1 ] || fail "'$*' exited $code, expected 1"
  echo "$err" | tail -n 1 | grep -q -- "$pattern" || fail "'$*' said '$err', expected '$pattern'"
}
source "$(dirname "$0")/usage_error.sh"  # expect_usage_error
# The wrong setup is the same mistake as inverted poses: detected, never a silent calibration.
expect_error "robot poses look inverted" calibrate "$views" --setup eye-in-hand --out "$work/x.yaml"
[ -e "$work/x.yaml" ] && fail "a failed calibration wrote its file"
expect_error "needs at least 7 usable views, got 6" calibrate "$views" --setup eye-to-hand --min-views 7 --out "$work/x.yaml"
expect_error "unknown hand-eye method 'kabsch'" calibrate "$views" --setup eye-to-hand --method kabsch --out "$work/x.yaml"
expect_usage_error "--setup is required" calibrate "$views" --out "$work/x.yaml"
expect_usage_error "--port requires --listen" calibrate "$views" --setup eye-to-hand --port 0 --out "$work/x.yaml"
expect_usage_error "--views excludes --listen" calibrate "$views" --setup eye-to-hand --listen --out "$work/x.yaml"

spoiled() {  # a copy of the views to spoil
  rm -rf "$work/spoiled"
  cp -r "$views" "$work/spoiled"
}
spoiled
rm "$work/spoiled/view_04.png"
expect_error "view view_04 has a robot pose but no image" calibrate "$work/spoiled" --setup eye-to-hand --out "$work/x.yaml"
spoiled
cp "$views/view_01.png" "$work/spoiled/extra.png"
expect_error "view extra has an image but no robot pose" calibrate "$work/spoiled" --setup eye-to-hand --out "$work/x.yaml"
spoiled
sed -i 's/^view_02 \([^ ]*\) /view_02 nan /' "$work/spoiled/poses.txt"
expect_error "poses.txt:5: view view_02: 'nan' is not a finite number" calibrate "$work/spoiled" --setup eye-to-hand --out "$work/x.yaml"
# Two images swapped: the views no longer fit their robot poses, and the failure names them.
spoiled
mv "$work/spoiled/view_01.png" "$work/swap.png"
mv "$work/spoiled/view_02.png" "$work/spoiled/view_01.png"
mv "$work/swap.png" "$work/spoiled/view_02.png"
expect_error "hand-eye calibration failed, nothing written: .* without view_0[12] view_0[12]: check" \
  calibrate "$work/spoiled" --setup eye-to-hand --out "$work/x.yaml"

# Mistakes a person makes writing the poses or the board, each named for what it likely is.
spoiled
awk '/^view_/ { $2 /= 1000; $3 /= 1000; $4 /= 1000 } { print }' "$views/poses.txt" >"$work/spoiled/poses.txt"
expect_error "units? the robot positions look like metres, expected millimetres" \
  calibrate "$work/spoiled" --setup eye-to-hand --out "$work/x.yaml"
spoiled
awk '/^view_03/ { $2 += 20 } { print }' "$views/poses.txt" >"$work/spoiled/poses.txt"
calibrate "$work/spoiled" --setup eye-to-hand --out "$work/x.yaml" >/dev/null 2>"$work/warnings.txt" ||
  fail "one bad pose failed the calibration: $(cat "$work/warnings.txt")"
grep -q "view view_03 disagrees with the others.*--drop-outliers" "$work/warnings.txt" ||
  fail "no warning naming view_03: $(cat "$work/warnings.txt")"
calibrate "$work/spoiled" --setup eye-to-hand --drop-outliers --min-views 5 --out "$work/x.yaml" \
  >"$work/table.txt" 2>"$work/warnings.txt" || fail "--drop-outliers exited $?: $(cat "$work/warnings.txt")"
grep -q "view view_03 disagrees with the others.*: dropped" "$work/warnings.txt" ||
  fail "--drop-outliers did not name view_03: $(cat "$work/warnings.txt")"
grep -q "^view_03 .* dropped$" "$work/table.txt" || fail "the table does not show view_03 dropped"
calibrate "$views" --setup eye-to-hand --square-mm 29 --marker-mm 21.27 --out "$work/x.yaml" >/dev/null \
  2>"$work/warnings.txt" || fail "--square-mm 29 exited $?: $(cat "$work/warnings.txt")"
grep -q "warning: the board size looks wrong.*--square-mm" "$work/warnings.txt" ||
  fail "no warning about the board size: $(cat "$work/warnings.txt")"

[ "$failures" -eq 0 ] || exit 1
echo "hand-eye CLI: all checks passed ($error_mm mm off the truth)"
