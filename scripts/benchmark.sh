#!/usr/bin/env bash
# Builds binpick and regenerates the benchmark (docs/BENCHMARK.md's figures) in docs/benchmark/:
# results.md (the paper's Tables II and III for every method, on the exact and the reconstructed
# cloud; Figure 5; scaling), outcomes.csv (one row per method, scene and input) and the PNG plots.
#   bash scripts/benchmark.sh            quick: 2 scenes per part; OpenCV's and PCL's matchers, which
#                                        take minutes per scene, on one l_bracket scene (15 minutes
#                                        on 2 cores)
#   bash scripts/benchmark.sh --full     the paper's 50 scenes per part, the peers on 5 of every
#                                        part (days on 2 cores: mostly PCL)
#   bash scripts/benchmark.sh ARGS...    any bench_paper options, e.g. --methods binpick,ppf5
#   bash scripts/benchmark.sh --emptying [ARGS...]
#                                        bin emptying instead (docs/benchmark/emptying.md): every
#                                        part, 5 bins of 20, suction; any bench_emptying options
#   bash scripts/benchmark.sh --soak [ARGS...]
#                                        binpickd's soak instead (docs/benchmark/soak.md): 1000
#                                        cycles with reloads and robots coming and going; any
#                                        bench_daemon_soak options, e.g. --cycles 50
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--soak" ]; then
  bash scripts/build.sh bench_daemon_soak  # and binpickd, which it starts
  exec ./build/bench/bench_daemon_soak --out docs/benchmark "${@:2}"
fi
bash scripts/build.sh
if [ "${1:-}" = "--emptying" ]; then
  exec ./build/bench/bench_emptying --out docs/benchmark "${@:2}"
fi
args=(--peer-parts l_bracket "$@")
if [ "${1:-}" = "--full" ]; then
  args=(--scenes 50 --scaling-scenes 5 --peer-scenes 5 "${@:2}")
fi
./build/bench/bench_paper --out docs/benchmark "${args[@]}"
