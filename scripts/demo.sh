#!/usr/bin/env bash
# The main job on the embedded virtual cell: empty a bin. 20 parts are dropped into a bin (rigid-body
# physics); then, cycle after cycle, the structured-light capture of the pile is rendered, the cell
# service binpickd runs (capture, reconstruct, detect, plan grasps generated from the part's model),
# a simulated robot fetches the first pick over the robot protocol and executes it against the
# truth, a part it holds leaves the bin and the pile re-settles, until binpickd reports the bin empty.
# Output: demo-output/ (emptying.json, the cell's settings under cell/, every cycle's overlay and
# detections under cycles/; overlay.png: the first cycle's, the full pile with the picks it offered).
# While it runs, the cell's web view (docs/binpickd.md, "Web view") is on http://127.0.0.1:8080/, or
# the next free port; the URL is printed first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh binpick
out=demo-output
rm -rf "$out"
# The cell's web view while the run lasts: 8080, or the next free port.
port_in_use() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
web_port=8080
while port_in_use "$web_port" && [ "$web_port" -lt 8180 ]; do web_port=$((web_port + 1)); done
echo "web view: http://127.0.0.1:$web_port/ (while the demo runs)"
./build/src/cli/binpick simulate --part l_bracket --objects 20 --seed 3 --empty-bin --web-port "$web_port" --out "$out"
overlay=$(ls -d "$out"/cycles/cycle-*/overlay.png 2>/dev/null | sort -V | head -n 1 || true)
if [ -n "$overlay" ]; then
  cp "$overlay" "$out/overlay.png"
  echo "demo: the first cycle's picks drawn on the camera image: $out/overlay.png; the run: $out/emptying.json"
fi
