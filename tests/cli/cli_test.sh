#!/usr/bin/env bash
# End to end through the command line: simulate a pile, detect with a model cache, evaluate, and
# check that bad input gives one line on stderr naming the problem and exit code 1 (exit code 2
# for a usage error).
set -uo pipefail
binpick="$1"
config_dir="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$binpick" simulate --part clamp --objects 8 --seed 5 --cloud-only --out "$work/pile" 2>/dev/null || fail "simulate exited $?"
for f in cloud.ply calib.yaml truth/objects.json truth/part.ply truth/depth.tiff truth/mask.png truth/cloud.ply; do
  [ -s "$work/pile/$f" ] || fail "simulate wrote no $f"
done
# A full capture: 52 pattern images and their metadata.
"$binpick" simulate --part clamp --objects 3 --seed 5 --out "$work/capture" 2>/dev/null || fail "simulate (images) exited $?"
[ "$(ls "$work/capture/images" | wc -l)" -eq 52 ] || fail "simulate wrote $(ls "$work/capture/images" | wc -l) images, expected 52"
grep -q '"gray_col_00_inv"' "$work/capture/capture.json" || fail "capture.json lists no gray_col_00_inv"
# Any mesh file can be piled instead of a built-in part.
"$binpick" simulate --export-part gear "$work/gear.stl" || fail "export-part exited $?"
"$binpick" simulate --mesh "$work/gear.stl" --objects 2 --cloud-only --out "$work/user" 2>/dev/null ||
  fail "simulate --mesh exited $?"
[ -s "$work/user/truth/part.ply" ] || fail "simulate --mesh wrote no truth/part.ply"

run_detect() {
  "$binpick" detect --model "$work/pile/truth/part.ply" --scene "$work/pile/cloud.ply" \
    --config "$config_dir/virtual-cell.yaml" --model-cache "$work/model.cache" --max-objects 8 --out "$1"
}
run_detect "$work/first.json" 2>"$work/detect.err" || fail "detect exited $?"
grep -q "no crop box" "$work/detect.err" && fail "detect with the virtual cell's crop box says it has none"
"$binpick" detect --model "$work/pile/truth/part.ply" --scene "$work/pile/cloud.ply" --model-cache "$work/model.cache" \
  --max-objects 2 --out "$work/uncropped.json" 2>"$work/detect.err" || fail "detect without a config exited $?"
grep -q "no crop box" "$work/detect.err" || fail "detect without a crop box gives no note: $(cat "$work/detect.err")"
[ -s "$work/model.cache" ] || fail "detect wrote no model cache"
run_detect "$work/second.json" || fail "detect with a cache exited $?"
grep -q '"detections"' "$work/first.json" || fail "result has no detections key"
# The cached model gives the same poses (timings differ).
diff <(grep -A4 '"pose"' "$work/first.json") <(grep -A4 '"pose"' "$work/second.json") >/dev/null ||
  fail "cached model changed the poses"

summary=$("$binpick" evaluate --result "$work/first.json" --truth "$work/pile" | tail -n 1)
found=$(echo "$summary" | sed -n 's/^found \([0-9]*\) of \([0-9]*\).*/\1 \2/p')
read -r got want <<<"$found"
# Recognition itself is measured by the estimation tests and the benchmark; here the pipeline
# must hold together and find parts.
[ -n "${want:-}" ] && [ "$got" -ge 1 ] || fail "evaluate: '$summary'"

expect_error() {  # expect_error "pattern" command...
  local pattern="$1"; shift
  local err
  err=$("$@" 2>&1 >/dev/null)
  local code=$?
  [ "$code" -eq 1 ] || fail "'$*' exited $code, expected 1"
  [ "$(echo "$err" | wc -l)" -eq 1 ] || fail "'$*' printed more than one line: $err"
  echo "$err" | grep -q -- "$pattern" || fail "'$*' said '$err', expected '$pattern'"
}
source "$(dirname "$0")/usage_error.sh"  # expect_usage_error
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\x01\x02' > "$work/truncated.ply"
printf 'not a cache' > "$work/bad.cache"
printf 'detection:\n  voting: {reference_fractoin: 0.3}\n' > "$work/typo.yaml"
expect_error "missing.ply" "$binpick" detect --model "$work/missing.ply" --scene "$work/pile/cloud.ply"
expect_error "truncated.ply" "$binpick" detect --model "$work/pile/truth/part.ply" --scene "$work/truncated.ply"
expect_error "reference_fractoin" "$binpick" detect --model "$work/pile/truth/part.ply" --scene "$work/pile/cloud.ply" --config "$work/typo.yaml"
expect_usage_error "--max-objects: needs a whole number, not '-3x'" "$binpick" detect --model "$work/pile/truth/part.ply" --scene "$work/pile/cloud.ply" --max-objects -3x
expect_usage_error "--scene or --capture is required" "$binpick" detect --model "$work/pile/truth/part.ply"
expect_usage_error "not expected: --modle x" "$binpick" detect --modle x
expect_error "gizmo" "$binpick" simulate --part gizmo --out "$work/x"
expect_error "bin_width" "$binpick" simulate --part clamp --bin-width -0.3 --out "$work/y"
expect_error "not empty" "$binpick" simulate --part clamp --objects 1 --out "$work/pile"
expect_error "BoardSpec\|board" "$binpick" simulate --calibration-board hexagons --out "$work/board"
# A corrupt cache is rebuilt from the model, not trusted.
"$binpick" detect --model "$work/pile/truth/part.ply" --scene "$work/pile/cloud.ply" --config "$config_dir/virtual-cell.yaml" \
  --model-cache "$work/bad.cache" --max-objects 1 >/dev/null || fail "a corrupt cache was not rebuilt"

# From pattern images: reconstruct alone, and detect straight from the capture directory.
"$binpick" reconstruct --capture "$work/capture" --out "$work/reconstructed.ply" --status "$work/status.png" \
  >"$work/reconstruct.log" || fail "reconstruct exited $?"
[ -s "$work/reconstructed.ply" ] && [ -s "$work/status.png" ] || fail "reconstruct wrote no cloud or status image"
grep -q "obj_info organized 1280 1024" "$work/reconstructed.ply" || fail "the reconstructed cloud is not organized"
grep -q "property float intensity" "$work/reconstructed.ply" || fail "the reconstructed cloud has no intensity"
grep -q "points of 1310720 pixels" "$work/reconstruct.log" || fail "reconstruct summary: $(cat "$work/reconstruct.log")"
"$binpick" detect --model "$work/capture/truth/part.ply" --capture "$work/capture" \
  --config "$config_dir/virtual-cell.yaml" --model-cache "$work/model.cache" --max-objects 3 --out "$work/captured.json" \
  2>/dev/null || fail "detect --capture exited $?"
summary=$("$binpick" evaluate --result "$work/captured.json" --truth "$work/capture" | tail -n 1)
echo "$summary" | grep -q "^found [1-9]" || fail "detect --capture: '$summary'"

# Damaged captures: one line naming what is wrong, exit code 1.
damaged() {  # a copy of the capture to damage
  rm -rf "$work/damaged" && cp -r "$work/capture" "$work/damaged"
}
damaged && rm "$work/damaged/images/012_gray_col_05.png"
expect_error "012_gray_col_05.png" "$binpick" reconstruct --capture "$work/damaged" --out "$work/x.ply"
damaged && printf 'not a png' > "$work/damaged/images/013_gray_col_05_inv.png"
expect_error "013_gray_col_05_inv.png" "$binpick" reconstruct --capture "$work/damaged" --out "$work/x.ply"
damaged && cp "$work/damaged/images/001_black.png" "$work/damaged/images/014_gray_col_06.png"
expect_error "gray_col_06.*a frame is missing, black or out of order" "$binpick" reconstruct --capture "$work/damaged" --out "$work/x.ply"
damaged && sed -i 's/"phase_steps": 4/"phase_steps": 3/' "$work/damaged/capture.json"
expect_error "pattern set" "$binpick" reconstruct --capture "$work/damaged" --out "$work/x.ply"
expect_error "missing.yaml" "$binpick" reconstruct --capture "$work/capture" --calib "$work/missing.yaml" --out "$work/x.ply"
sed 's/camera_width: 1280/camera_width: 640/' "$work/capture/calib.yaml" > "$work/small_camera.yaml"
expect_error "calibration's camera is 640x1024" "$binpick" reconstruct --capture "$work/capture" --calib "$work/small_camera.yaml" --out "$work/x.ply"
[ -e "$work/x.ply" ] && fail "a failed reconstruct wrote a cloud"

# The live path without hardware: a fake GigE Vision camera on loopback serves the capture's
# images behind a virtual projector; the recording equals them byte for byte and reconstructs.
"$binpick" capture --fake-camera "$work/capture" --out "$work/recorded" 2>/dev/null || fail "capture --fake-camera exited $?"
for image in "$work/capture/images/"*.png; do
  cmp -s "$image" "$work/recorded/images/$(basename "$image")" || fail "recorded $(basename "$image") differs"
done
[ -s "$work/recorded/calib.yaml" ] || fail "capture --fake-camera copied no calib.yaml"
"$binpick" reconstruct --capture "$work/recorded" --out "$work/recorded.ply" >/dev/null 2>&1 || fail "reconstruct of a recording exited $?"
expect_error "GPIO chip 'gpiochip9'" "$binpick" capture --camera 127.0.0.9 --trigger gpio:gpiochip9:3 --out "$work/live"
expect_usage_error "--camera or --fake-camera is required" "$binpick" capture --out "$work/live"
expect_usage_error "--projector requires --camera" "$binpick" capture --fake-camera "$work/capture" --projector 640x400 --out "$work/live"
[ -e "$work/live" ] && fail "a failed capture wrote a directory"

if [ "$failures" -eq 0 ]; then echo "cli: all checks passed"; else exit 1; fi
