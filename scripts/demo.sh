#!/usr/bin/env bash
# The main job on the embedded virtual cell: drop 20 parts into a bin (rigid-body physics) and
# render what the structured-light camera records under each of the 52 projected patterns; start
# the cell service binpickd replaying that capture; play the robot with `binpick robot-client`:
# trigger a cycle (capture, reconstruct, detect, plan) and fetch every pick in the robot base
# frame, with timings. Output: demo-output/ (capture with truth, model cache, cycles/ with the
# cycle's cloud, detections and overlay; overlay.png: the picks drawn on the camera image).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=demo-output
rm -rf "$out/capture" "$out/cycles" "$out/port"
./build/src/apps/binpick simulate --part l_bracket --objects 20 --seed 3 --out "$out/capture"

./build/src/apps/binpickd --config config/demo-binpickd.yaml --port 0 --port-file "$out/port" &
daemon=$!
trap 'kill "$daemon" 2>/dev/null || true' EXIT
for _ in $(seq 600); do [ -s "$out/port" ] && break; sleep 0.1; done
[ -s "$out/port" ] || { echo "demo: binpickd did not start" >&2; exit 1; }

./build/src/apps/binpick robot-client --port "$(cat "$out/port")" --orientation euler_zyx
kill -TERM "$daemon"
wait "$daemon"
trap - EXIT
cp "$(ls -d "$out"/cycles/cycle-* | tail -n 1)/overlay.png" "$out/overlay.png"
echo "demo: the picks drawn on the camera image: $out/overlay.png"
