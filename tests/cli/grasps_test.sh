#!/usr/bin/env bash
# `binpick grasps`: suction grasps for a built-in part written as a grasps file with a picture, and
# bad input reported on one line with exit code 1.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$binpick" grasps --part l_bracket --gripper suction --out "$work/grasps.yaml" --image "$work/grasps.png" \
  >"$work/stdout" 2>"$work/stderr" || fail "grasps exited $?: $(cat "$work/stderr")"
[ -s "$work/grasps.yaml" ] || fail "no grasps file"
[ -s "$work/grasps.png" ] || fail "no image"
head -c 8 "$work/grasps.png" | od -An -c | grep -q "P   N   G" || fail "the image is not a PNG"
grep -q '^grasps:' "$work/grasps.yaml" || fail "the file has no grasps: key"
entries=$(grep -c '^  - name: "suction ' "$work/grasps.yaml")
[ "$entries" -ge 1 ] || fail "the file lists no suction grasps"
grep -q 'convention: quaternion' "$work/grasps.yaml" || fail "no quaternion convention"
[ "$(wc -l <"$work/stdout")" -eq "$entries" ] || fail "stdout has $(wc -l <"$work/stdout") lines for $entries grasps"

"$binpick" grasps --part l_bracket --gripper parallel --stroke 0.05 --out "$work/jaws.yaml" >/dev/null 2>&1 ||
  fail "parallel grasps exited $?"
grep -q '^  - name: "parallel ' "$work/jaws.yaml" || fail "the file lists no parallel grasps"

"$binpick" grasps --part l_bracket --gripper vacuum --out "$work/x.yaml" 2>"$work/err"; code=$?
[ "$code" -eq 1 ] || fail "an unknown gripper exited $code"
grep -q 'vacuum' "$work/err" || fail "the error does not name the gripper: $(cat "$work/err")"
"$binpick" grasps --part l_bracket --gripper suction --cup-diameter -1 --out "$work/x.yaml" 2>"$work/err"; code=$?
[ "$code" -eq 1 ] && grep -q 'cup_diameter' "$work/err" || fail "a negative cup gave $code: $(cat "$work/err")"
# A size of the other gripper is a usage mistake, not a setting to ignore.
"$binpick" grasps --part l_bracket --gripper parallel --cup-diameter 0.01 --out "$work/x.yaml" 2>"$work/err"; code=$?
[ "$code" -eq 2 ] && grep -q -- '--cup-diameter excludes --gripper parallel' "$work/err" ||
  fail "a suction size for a parallel gripper gave $code: $(cat "$work/err")"

# A model file: its symmetry found from the mesh and printed, unless the options give one.
"$binpick" simulate --export-part ring_magnet "$work/magnet.ply" >/dev/null 2>&1 || fail "export exited $?"
"$binpick" grasps --model "$work/magnet.ply" --gripper suction --cup-diameter 0.004 --out "$work/magnet.yaml" \
  >/dev/null 2>"$work/err" || fail "grasps on a model file exited $?: $(cat "$work/err")"
grep -q '^symmetry from the mesh: revolved about (0, 0, 1), flips over: any turn about (0, 0, 1) with 2 rotations$' \
  "$work/err" || fail "no symmetry from the mesh: $(cat "$work/err")"
"$binpick" grasps --model "$work/magnet.ply" --gripper suction --cup-diameter 0.004 --symmetry-order 2 \
  --symmetry-axis 1,0,0 --out "$work/told.yaml" >/dev/null 2>"$work/err" || fail "grasps as told exited $?"
grep -q '^symmetry as given: 2 rotations$' "$work/err" || fail "the given symmetry was not kept: $(cat "$work/err")"

[ "$failures" -eq 0 ] && echo "grasps CLI: all checks passed"
exit "$failures"
