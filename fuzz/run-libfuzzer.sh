#!/bin/sh
# Fuzzes one target (fuzz/TARGET_fuzz.cpp) with libFuzzer, AddressSanitizer and UBSan: builds it
# into a temporary directory, then runs RUNS inputs (default 200000) from its seed corpus
# fuzz/corpus/TARGET under the limits every target must keep (10 s per input, 1 GB per
# allocation, 2 GB resident). Exits non-zero on a crash, a hang, a sanitizer report, an
# oversized allocation or a broken invariant.
#   usage: fuzz/run-libfuzzer.sh TARGET [RUNS] [LIBFUZZER_OPTION...]
#     TARGET: robot_protocol, capture, rig_calibration, cell_config, grasps_file, hand_eye_file,
#             recipe_settings, ply, pcd, stl, obj
#     options go to libFuzzer as they are; with -max_total_time=SECONDS and no RUNS it runs for
#     that long, e.g. `fuzz/run-libfuzzer.sh ply -max_total_time=600`
#   env:   CXX (default clang++), EIGEN_INCLUDE_DIR (default: from pkg-config eigen3),
#          BINPICK_BUILD_DIR (default build/: the file-reader targets link the project's static
#          libraries from a finished build of it), FUZZ_JOBS (default 2, RUNS shared out),
#          FUZZ_BUILD_JOBS (compilers at a time, default 2), FUZZ_SEED (default 1; job n uses
#          seed + n - 1), FUZZ_KEEP=1 keeps the directory (and any crash input)
set -eu

usage() {
  sed -n 's/^#   usage: //p' "$0" >&2
  exit 2
}

[ $# -ge 1 ] || usage
target=$1
shift
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
[ -f "$here/${target}_fuzz.cpp" ] && [ -d "$here/corpus/$target" ] || usage

runs=""
case "${1:-}" in
  '' | -*) ;;
  *) runs=$1; shift ;;
esac
case " $* " in
  *" -max_total_time="* | *" -runs="*) ;;
  *) runs=${runs:-200000} ;;
esac

cxx=${CXX:-clang++}
eigen=${EIGEN_INCLUDE_DIR:-$(pkg-config --cflags-only-I eigen3 | sed 's/^ *-I//; s/ .*//')}
build=${BINPICK_BUILD_DIR:-$root/build}
jobs=${FUZZ_JOBS:-2}
seed=${FUZZ_SEED:-1}

work=$(mktemp -d)
if [ "${FUZZ_KEEP:-0}" = 1 ]; then echo "working in $work"; else trap 'rm -rf "$work"' EXIT; fi

flags="-std=c++17 -O1 -gline-tables-only -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined"
flags="$flags -isystem $eigen -isystem /usr/include/opencv4"
for module in "$root"/src/*; do flags="$flags -I$module/include -I$module/src"; done

# Compiles SOURCES (paths under the root) with coverage and sanitizers, FUZZ_BUILD_JOBS at a time.
compile() {
  for source in "$@"; do echo "$root/$source"; done |
    xargs -P "${FUZZ_BUILD_JOBS:-2}" -I SOURCE sh -c '"$1" $2 -c "$3" -o "$4/$(basename "$3").o"' \
      _ "$cxx" "$flags $extra_flags" SOURCE "$work"
}

# The readers each target exercises are built here with coverage; whatever else they call (a
# settings struct's validate(), the OpenCV glue) is linked from the project's build, where
# libFuzzer does not look.
io=src/io/src
core=src/core/src
cell=src/cell/src
geometry="$io/geometry_io.cpp $io/validate.cpp $io/byte_io.cpp $io/text_io.cpp $core/file.cpp"
cell_settings="$cell/cell_config.cpp $cell/config_source.cpp $cell/config_recipes.cpp $cell/config_robot.cpp
  $cell/config_web.cpp $cell/grasps_file.cpp $core/yaml_section.cpp $core/pose_yaml.cpp $core/orientation.cpp
  $core/file.cpp src/reconstruction/src/reconstruction_config.cpp"
case "$target" in
  robot_protocol) readers="$core/orientation.cpp src/robot/src/protocol.cpp src/robot/src/ascii.cpp
                    src/robot/src/binary.cpp src/robot/src/pose.cpp" ;;
  capture) readers="$io/capture.cpp $io/capture_metadata.cpp $io/png_structure.cpp $io/byte_io.cpp
             $core/json_fields.cpp $core/file.cpp" ;;
  rig_calibration) readers="$io/rig_calibration.cpp $io/rig_calibration_quality.cpp $io/lens.cpp $core/file.cpp" ;;
  cell_config | grasps_file | hand_eye_file) readers=$cell_settings ;;
  recipe_settings) readers="src/estimation/src/config.cpp $core/yaml_section.cpp" ;;
  ply) readers="$geometry $io/ply_header.cpp $io/ply_reader.cpp $io/ply_writer.cpp" ;;
  pcd) readers="$geometry $io/pcd_header.cpp $io/pcd_ascii.cpp $io/pcd_reader.cpp $io/pcd.cpp" ;;
  stl) readers="$geometry $io/stl.cpp" ;;
  obj) readers="$geometry $io/obj.cpp" ;;
  *) usage ;;
esac

extra_flags=""
if [ "$target" = robot_protocol ]; then
  # Every file includes protocol.hpp, i.e. Eigen: precompiled once, it no longer dominates the
  # build. The protocol needs nothing else of the project, so no build of it either.
  "$cxx" $flags -x c++-header "$root/src/robot/include/binpick/robot/protocol.hpp" -o "$work/protocol.pch"
  extra_flags="-include-pch $work/protocol.pch"
  compile fuzz/robot_protocol_fuzz.cpp $readers
  "$cxx" -fsanitize=fuzzer,address,undefined "$work"/*.o -o "$work/fuzz_target"
else
  libraries=$(ls "$build"/src/*/libbinpick_*.a 2>/dev/null) ||
    { echo "no libbinpick_*.a under $build/src: build the project first (or set BINPICK_BUILD_DIR)" >&2; exit 2; }
  compile "fuzz/${target}_fuzz.cpp" $(printf '%s\n' $readers | sort -u)
  # shellcheck disable=SC2086  # word splitting of the library lists is intended
  "$cxx" -fsanitize=fuzzer,address,undefined "$work"/*.o -Wl,--start-group $libraries -Wl,--end-group \
    -Wl,--as-needed $(pkg-config --libs opencv4) -lyaml-cpp -lspdlog -lfmt -laravis-0.8 -lgpiodcxx -lgio-2.0 \
    -lgobject-2.0 -lglib-2.0 -lgomp -lpthread -o "$work/fuzz_target"
fi

# One fuzzer per job, each with its own seed and corpus so that a run can be repeated exactly
# (libFuzzer's own -jobs would give every job the same seed). Short malloc stacks and a small
# quarantine: the inputs are small, the runs many. The robot protocol's inputs are messages; a
# file may be as long as the largest seed (libFuzzer's default).
max_len=""
[ "$target" = robot_protocol ] && max_len="-max_len=512"
export ASAN_OPTIONS="${ASAN_OPTIONS:-malloc_context_size=4:quarantine_size_mb=16}"
pids=""
job=1
while [ "$job" -le "$jobs" ]; do
  cp -r "$here/corpus/$target" "$work/corpus$job"
  runs_option=""
  [ -n "$runs" ] && runs_option="-runs=$(( (runs + jobs - 1) / jobs ))"
  # shellcheck disable=SC2086
  "$work/fuzz_target" $runs_option -seed=$((seed + job - 1)) $max_len -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -print_final_stats=1 -artifact_prefix="$work/job$job-" "$@" "$work/corpus$job" \
    > "$work/log$job" 2>&1 &
  pids="$pids $!"
  job=$((job + 1))
done

status=0
job=1
for pid in $pids; do
  if wait "$pid"; then
    grep -E '^#[0-9]+[[:space:]]+DONE|^Done [0-9]+ runs|^stat::(number_of_executed_units|peak_rss_mb)' "$work/log$job"
  else
    status=1
    cat "$work/log$job"  # the report, and the failing input in Base64 when it is short
    echo "libFuzzer job $job of $target (seed $((seed + job - 1))) failed; FUZZ_KEEP=1 keeps its input" >&2
  fi
  job=$((job + 1))
done
exit "$status"
