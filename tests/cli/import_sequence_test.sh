#!/usr/bin/env bash
# Another rig's sequence described in a file and imported: a complementary Gray code (Gray words
# of half the phase period) with 4-step phase, in that rig's order and file names. Made from a
# virtual pile: the words' bits are the full Gray code's coarsest bits, so the pile's own images
# are that rig's. The imported capture reconstructs as the full one does; a file that does not
# describe the images is refused with one line.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$binpick" simulate --part l_bracket --objects 6 --seed 3 --out "$work/pile" >/dev/null 2>&1 ||
  { echo "FAIL: simulate exited $?"; exit 1; }

# The rig's order: per axis its phase steps first, then its Gray bits (1280 / 8 = 160 words of
# columns: 8 bits; 800 / 8 = 100 of rows: 7 bits), then white and black; files named by number.
mkdir -p "$work/rig"
n=0
take() {  # take PATTERN: the pile's image of PATTERN as the rig's next file
  n=$((n + 1))
  cp "$work/pile/images/"[0-9][0-9][0-9]_"$1".png "$work/rig/frame$n.png" || fail "no image $1"
}
for axis in col row; do
  bits=$([ "$axis" = col ] && echo 7 || echo 6)
  for k in 0 1 2 3; do take "phase_${axis}_$k"; done
  for b in $(seq -f %02g 0 "$bits"); do take "gray_${axis}_$b"; take "gray_${axis}_${b}_inv"; done
done
take white
take black
cat >"$work/rig.yaml" <<'YAML'
projector: {width: 1280, height: 800}
gray_unit: 8                  # half the phase period: a complementary Gray code
phase: {steps: 4, period: 16}
images:
  - phase: columns
  - gray: columns
  - phase: rows
  - gray: rows
  - white
  - black
YAML

"$binpick" import-capture --images "$work/rig" --sequence "$work/rig.yaml" --calib "$work/pile/calib.yaml" \
  --out "$work/imported" >"$work/import.log" 2>&1 || fail "import exited $?: $(cat "$work/import.log")"
grep -q "^imported 40 images (frame1.png as phase_col_0 .. frame40.png as black)" "$work/import.log" ||
  fail "$(cat "$work/import.log")"

points_of() {  # points_of CAPTURE_DIR: the valid points reconstruct reports
  "$binpick" reconstruct --capture "$1" --calib "$work/pile/calib.yaml" --out "$work/cloud.ply" 2>&1 |
    grep -o '^[0-9]* points of' | tr -dc '0-9'
}
full=$(points_of "$work/pile")
imported=$(points_of "$work/imported")
[ "${full:-0}" -gt 100000 ] || fail "the full capture gave ${full:-no} points"
# As many points as the full Gray code gives, to 1%.
[ "${imported:-0}" -ge $((full * 99 / 100)) ] || fail "imported ${imported:-no} points, the full capture $full"

# The same file without its gray_unit describes 52 images: refused, one line, nothing written.
grep -v gray_unit "$work/rig.yaml" >"$work/full.yaml"
"$binpick" import-capture --images "$work/rig" --sequence "$work/full.yaml" --calib "$work/pile/calib.yaml" \
  --out "$work/refused" >"$work/refused.log" 2>&1
code=$?
[ "$code" -eq 1 ] || fail "a sequence of another length exited $code"
[ "$(wc -l <"$work/refused.log")" -eq 1 ] || fail "more than one line: $(cat "$work/refused.log")"
grep -q "40 images (frame1.png .. frame40.png), but the sequence has 52" "$work/refused.log" ||
  fail "$(cat "$work/refused.log")"
[ ! -e "$work/refused" ] || fail "a refused import left a directory"

[ "$failures" -eq 0 ]
