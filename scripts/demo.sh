#!/usr/bin/env bash
# The main job on the embedded virtual cell: drop 20 parts into a bin (rigid-body physics), render
# what the structured-light camera records under each of the 52 projected patterns, reconstruct
# the point cloud from those images, find every part's pose and score the result against the
# truth. Output: demo-output/ (capture with truth, cloud.ply, result.json, model cache).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
part="${1:-l_bracket}"
out=demo-output
rm -rf "$out/capture"
./build/src/apps/binpick simulate --part "$part" --objects 20 --seed 3 --out "$out/capture"
./build/src/apps/binpick reconstruct --capture "$out/capture" --out "$out/cloud.ply"
./build/src/apps/binpick detect --model "$out/capture/truth/part.ply" --scene "$out/cloud.ply" \
  --config config/virtual-cell.yaml --model-cache "$out/model.cache" --out "$out/result.json"
./build/src/apps/binpick evaluate --result "$out/result.json" --truth "$out/capture" --part "$part"
