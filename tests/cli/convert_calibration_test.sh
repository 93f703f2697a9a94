#!/usr/bin/env bash
# `binpick convert-calibration`: another tool's OpenCV calibration written as calib.yaml (the real
# rig's file of the shared data set when it is there, a hand-typed one always), its mistakes
# reported on one line; and the calibration check `reconstruct` prints, near zero on the virtual
# cell and large under a calibration that does not fit.
# usage: convert_calibration_test.sh BINPICK REALDATA_DIR
set -uo pipefail
binpick="$1"
realdata="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Exit 1 and one line on stderr matching $1.
expect_error() {
  local pattern="$1"
  shift
  "$@" >/dev/null 2>"$work/err"
  local code=$?
  [ "$code" -eq 1 ] || fail "$* exited $code, not 1: $(cat "$work/err")"
  [ "$(wc -l <"$work/err")" -eq 1 ] || fail "$* wrote more than one line: $(cat "$work/err")"
  grep -q -- "$pattern" "$work/err" || fail "$*: no '$pattern' in: $(cat "$work/err")"
}

kamino="$realdata/kamino410-procam-calibration/calibration_result.xml"
if [ -f "$kamino" ]; then
  "$binpick" convert-calibration --opencv-calib "$kamino" --projector 2048x1536 --out "$work/kamino.yaml" \
    >"$work/out" 2>"$work/err" || fail "convert-calibration of the real file exited $?: $(cat "$work/err")"
  grep -q "camera 1280x1024 .*projector 2048x1536 .*baseline 644.2 mm" "$work/out" || fail "summary: $(cat "$work/out")"
  grep -q "^camera_width: 1280" "$work/kamino.yaml" || fail "no camera_width in the written calib.yaml"
  expect_error "no projector image size (tried .*; give --projector WxH)" \
    "$binpick" convert-calibration --opencv-calib "$kamino" --out "$work/x.yaml"
  expect_error "is the file in millimetres (--units mm)?" \
    "$binpick" convert-calibration --opencv-calib "$kamino" --projector 2048x1536 --units m --out "$work/x.yaml"
else
  echo "note: $kamino is missing: the real rig's file is not checked"
fi

# A hand-typed file: other key names, metres, a rotation vector.
cat >"$work/typed.yml" <<'YAML'
%YAML:1.0
imageSize: [ 1280, 1024 ]
K1: [ 1600, 0, 639.5, 0, 1600, 511.5, 0, 0, 1 ]
D1: [ 0, 0, 0, 0 ]
K2: [ 1400, 0, 639.5, 0, 1400, 790, 0, 0, 1 ]
D2: [ 0, 0, 0, 0, 0 ]
rvec_cp: [ 0, 0.2, 0 ]
T: [ -0.2, 0, 0.02 ]
YAML
"$binpick" convert-calibration --opencv-calib "$work/typed.yml" --projector 1280x800 --units m \
  --key rotation=rvec_cp --out "$work/typed.yaml" >"$work/out" 2>"$work/err" ||
  fail "convert-calibration of a typed file exited $?: $(cat "$work/err")"
grep -q "baseline 201.0 mm" "$work/out" || fail "typed file summary: $(cat "$work/out")"
expect_error "no rotation from camera to projector (tried R, rotation, roration, .*; give --key rotation=NAME)" \
  "$binpick" convert-calibration --opencv-calib "$work/typed.yml" --projector 1280x800 --units m --out "$work/x.yaml"
expect_error "key needs ROLE=NAME" \
  "$binpick" convert-calibration --opencv-calib "$work/typed.yml" --key rvec_cp --out "$work/x.yaml"

# The calibration check: the rig that rendered the capture fits it; one with the projector moved
# up by 40 mm does not.
"$binpick" simulate --part clamp --objects 4 --seed 2 --out "$work/capture" >/dev/null 2>&1 || fail "simulate exited $?"
"$binpick" reconstruct --capture "$work/capture" --out "$work/cloud.ply" >"$work/out" 2>&1 ||
  fail "reconstruct exited $?: $(cat "$work/out")"
grep -q "^calibration check: decoded rays miss each other by 0\.[0-4][0-9] mm (median), 0\.[0-9]* projector px; " \
  "$work/out" || fail "virtual cell check: $(cat "$work/out")"
grep -q "warning" "$work/out" && fail "the virtual cell's own calibration gave a warning: $(cat "$work/out")"
python3 - "$work/capture/calib.yaml" "$work/moved.yaml" <<'PY' || fail "cannot edit calib.yaml"
import re, sys
text = open(sys.argv[1]).read()
# T's data: x, y, z; the camera sits 40 mm lower in the projector's frame.
head, data = text.split("\nT: ", 1)
values = re.search(r"data: \[(.*?)\]", data, re.S)
x, y, z = (float(v) for v in values.group(1).replace("\n", " ").split(","))
data = data[:values.start(1)] + " %r, %r, %r " % (x, y + 0.04, z) + data[values.end(1):]
open(sys.argv[2], "w").write(head + "\nT: " + data)
PY
"$binpick" reconstruct --capture "$work/capture" --calib "$work/moved.yaml" --out "$work/cloud.ply" >"$work/out" 2>&1 ||
  fail "reconstruct with the moved projector exited $?: $(cat "$work/out")"
grep -q "^calibration check: decoded rays miss each other by [0-9.]* mm .*; [0-9.]*% beyond the" "$work/out" &&
  grep -q "^warning: " "$work/out" || fail "a calibration that does not fit gave: $(cat "$work/out")"

[ "$failures" -eq 0 ] && echo "convert-calibration and the calibration check: all checks passed"
exit "$failures"
