#!/usr/bin/env bash
# binpick calibrate rig on real captures (the shared real data set: five poses of a chessboard of
# 9 x 7 inner corners, 75 mm squares, under OpenCV's Gray codes at code step 2 (1024 x 768 codes:
# a 2048 x 1536 projector), with the authors'
# OpenCV calibration): five views calibrate with warnings naming what they leave loose, the
# camera's own solve agrees with the authors' within 1 %, the projector comes out at its true
# resolution, no distortion term fits worse than held, and the board given in the wrong
# convention is refused naming the right option. Skipped (exit 77) where the data set is missing.
set -uo pipefail
binpick="$1"
source "$(dirname "$0")/real_captures.sh"  # require_real_captures, import_real_capture
require_real_captures "$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

views=()
for i in 0 1 2 3 4; do
  import_real_capture "$i" "$work/capture_$i"
  views+=("$work/capture_$i")
done

board=(--board chessboard --inner-corners 9x7 --square-mm 75)
"$binpick" calibrate rig --views "${views[@]}" "${board[@]}" --out "$work/calib.yaml" >"$work/table.txt" \
  2>"$work/log.txt" || fail "calibrate rig exited $?: $(tail -n 3 "$work/log.txt")"
grep -q "^warning: only 5 views used, 8 or more recommended: poorly determined (own solves' standard deviations): camera cx +- " \
  "$work/log.txt" || fail "no fewer-views warning: $(cat "$work/log.txt")"
grep -q "^warning: the views do not pin the principal points" "$work/log.txt" ||
  fail "no principal point warning: $(cat "$work/log.txt")"
grep -q "5 of 5 views used" "$work/table.txt" || fail "$(cat "$work/table.txt")"
# Every corner the camera finds lies in the projector's light and gets its pixel.
[ "$(grep -c '^ *[^ ]*capture_[0-4]  *63  *63 ' "$work/table.txt")" -eq 5 ] || fail "corners lost: $(cat "$work/table.txt")"

# The figures, checked in Python: the camera's own solve against the XML's cam_int (the authors'
# cv::calibrateCamera), the projector's size and focal length in real projector pixels (code step
# 2: in codes it would be half), every chosen term's RMS fitted no worse than held.
python3 - "$data/calibration_result.xml" "$work/table.txt" "$work/calib.yaml" <<'PY' || failures=$((failures + 1))
import re, sys, xml.etree.ElementTree as ET
xml, table, calib = sys.argv[1:4]
def matrix(name):
    return [float(v) for v in ET.parse(xml).getroot().find(name).find("data").text.split()]
cam, proj = matrix("cam_int"), matrix("proj_int")
text = open(table).read()
ok = True
def check(what, got, want, share):
    global ok
    error = abs(got - want) / abs(want)
    print(f"{what}: {got:.2f} against {want:.2f} ({100 * error:.2f} %)")
    if error > share:
        print(f"FAIL: {what} off by more than {100 * share:.0f} %")
        ok = False
own = re.search(r"^camera +terms \S+: own solve RMS \S+ px +fx (\S+) +fy (\S+) +cx (\S+) +cy (\S+)$", text, re.M)
if not own:
    sys.exit(f"FAIL: no camera own-solve line in:\n{text}")
for name, got, want in zip(("fx", "fy", "cx", "cy"), map(float, own.groups()), (cam[0], cam[4], cam[2], cam[5])):
    check("camera " + name, got, want, 0.01)
yaml = open(calib).read()
if not re.search(r"^projector_width: 2048$", yaml, re.M) or not re.search(r"^projector_height: 1536$", yaml, re.M):
    print("FAIL: calib.yaml's projector is not 2048 x 1536")
    ok = False
fx = float(re.search(r"projector_matrix:.*?data: \[ *([-0-9.e+]+)", yaml, re.S).group(1))
check("projector fx (calib.yaml)", fx, proj[0], 0.10)
for fitted, held in re.findall(r" chosen RMS fitted (\S+) px, held (\S+) px", text):
    if float(fitted) > float(held):
        print(f"FAIL: a chosen term fits worse ({fitted} px) than held ({held} px)")
        ok = False
sys.exit(0 if ok else 1)
PY

# --hold-intrinsics: calib.yaml carries the camera's own solve, within 1 % of the XML's.
"$binpick" calibrate rig --views "${views[@]}" "${board[@]}" --hold-intrinsics --out "$work/held.yaml" \
  >/dev/null 2>&1 || fail "calibrate rig --hold-intrinsics exited $?"
python3 - "$data/calibration_result.xml" "$work/held.yaml" <<'PY' || failures=$((failures + 1))
import re, sys, xml.etree.ElementTree as ET
cam = [float(v) for v in ET.parse(sys.argv[1]).getroot().find("cam_int").find("data").text.split()]
yaml = open(sys.argv[2]).read()
data = re.search(r"camera_matrix:.*?data: \[([^\]]*)\]", yaml, re.S).group(1)
got = [float(v) for v in data.replace(",", " ").split()]
bad = [i for i in (0, 2, 4, 5) if abs(got[i] - cam[i]) > 0.01 * abs(cam[i])]
print("held camera matrix", [round(got[i], 2) for i in (0, 4, 2, 5)], "XML", [round(cam[i], 2) for i in (0, 4, 2, 5)])
sys.exit(f"FAIL: held camera matrix entries {bad} off by more than 1 %" if bad else 0)
PY

# The board given as squares with the numbers of its inner corners: refused, naming the option.
"$binpick" calibrate rig --views "${views[@]:0:3}" --board chessboard --squares 9x7 --square-mm 75 \
  --out "$work/x.yaml" >/dev/null 2>"$work/wrong.log"
[ $? -eq 1 ] || fail "a board of the wrong size did not fail"
tail -n 1 "$work/wrong.log" | grep -q "did you mean --inner-corners 9x7?" || fail "$(tail -n 1 "$work/wrong.log")"
[ ! -e "$work/x.yaml" ] || fail "a refused calibration wrote a file"

[ "$failures" -eq 0 ] && echo "calibrate rig on real captures: all checks passed"
exit "$failures"
