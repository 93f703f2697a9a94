#!/usr/bin/env bash
# The main job on the embedded virtual cell: simulate a pile of 20 parts in a bin as a depth
# camera sees it, then find every part's pose. Output: demo-output/ (scene, model, truth, result).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
part="${1:-l_bracket}"
out=demo-output
./build/src/apps/binpick simulate --part "$part" --objects 20 --seed 3 --out "$out"
./build/src/apps/binpick detect --model "$out/model.ply" --scene "$out/scene.ply" \
  --config config/virtual-cell.yaml --model-cache "$out/model.cache" --out "$out/result.json"
./build/src/apps/binpick evaluate --result "$out/result.json" --truth "$out/truth.json" --part "$part"
