#!/bin/sh
# Fuzzes the robot protocol with libFuzzer, AddressSanitizer and UBSan: builds the target and the
# protocol sources into a temporary directory, then runs RUNS inputs (default 200000) from a
# small seed corpus. Exits non-zero on a crash, a sanitizer report or a broken invariant.
#   usage: fuzz/run-libfuzzer.sh [RUNS]
#   env:   CXX (default clang++), EIGEN_INCLUDE_DIR (default: from pkg-config eigen3),
#          FUZZ_JOBS (default 2, RUNS shared out), FUZZ_SEED (default 1; job n uses seed + n - 1),
#          FUZZ_KEEP=1 keeps the directory (and any crash input)
set -eu

runs=${1:-200000}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
cxx=${CXX:-clang++}
eigen=${EIGEN_INCLUDE_DIR:-$(pkg-config --cflags-only-I eigen3 | sed 's/^ *-I//; s/ .*//')}

work=$(mktemp -d)
if [ "${FUZZ_KEEP:-0}" = 1 ]; then echo "working in $work"; else trap 'rm -rf "$work"' EXIT; fi

# Every file includes robot_protocol.hpp, i.e. Eigen: precompiled once, it no longer dominates
# the build. Then two compilers at a time: the sources are independent.
flags="-std=c++17 -O1 -gline-tables-only -fsanitize=fuzzer-no-link,address,undefined"
flags="$flags -fno-sanitize-recover=undefined -I$root/src/core/include -I$root/src/robot/include -isystem $eigen"
"$cxx" $flags -x c++-header "$root/src/robot/include/binpick/robot/protocol.hpp" -o "$work/protocol.pch"
ls "$here/robot_protocol_fuzz.cpp" "$root"/src/core/src/orientation.cpp \
   "$root"/src/robot/src/protocol.cpp "$root"/src/robot/src/ascii.cpp "$root"/src/robot/src/binary.cpp \
   "$root"/src/robot/src/pose.cpp |
  xargs -P 2 -I SOURCE sh -c '"$1" $2 -include-pch "$4/protocol.pch" -c "$3" -o "$4/$(basename "$3").o"' \
    _ "$cxx" "$flags" SOURCE "$work"
"$cxx" -fsanitize=fuzzer,address,undefined "$work"/*.o -o "$work/robot_protocol_fuzz"

# Seeds: the first byte picks the codec parameters (see the target), the rest is the stream.
mkdir "$work/seeds"
printf '\000PING\r\nTRIGGER,bolt\r\nNEXT\r\n' > "$work/seeds/ascii"
printf '\005FAILED,12\r\nMODEL\r\nFOO\r\n' > "$work/seeds/ascii-errors"
printf '\000\000\000\000\003\000\000\000\005\000\000\000\004\377\377\377\377' > "$work/seeds/binary"
printf '\001NEXT,0,2,17,1,100.00,-200.00,300.50,0.00000,0.00000,90.00000\r\n' > "$work/seeds/reply"
printf '\001POSE,600,0,400,180,0,0\r\nPOSE,1,2\r\nPOSE,0,3,12\r\n' > "$work/seeds/pose"
printf '\000\000\000\000\007\000\000\047\020\377\377\261\340\000\000\165\142\000\000\047\020'\
'\000\000\000\000\000\000\000\000\000\000\000\000' > "$work/seeds/binary-pose"

# One fuzzer per core, each with its own seed and corpus so that a run can be repeated exactly
# (libFuzzer's own -jobs would give every job the same seed). Short malloc stacks and a small
# quarantine: the messages are small, the runs many.
jobs=${FUZZ_JOBS:-2}
seed=${FUZZ_SEED:-1}
export ASAN_OPTIONS="${ASAN_OPTIONS:-malloc_context_size=4:quarantine_size_mb=16}"
pids=""
job=1
while [ "$job" -le "$jobs" ]; do
  cp -r "$work/seeds" "$work/corpus$job"
  "$work/robot_protocol_fuzz" -runs=$(( (runs + jobs - 1) / jobs )) -seed=$((seed + job - 1)) \
    -max_len=512 -artifact_prefix="$work/job$job-" "$work/corpus$job" > "$work/log$job" 2>&1 &
  pids="$pids $!"
  job=$((job + 1))
done

status=0
job=1
for pid in $pids; do
  if wait "$pid"; then
    grep -E '^#[0-9]+[[:space:]]+DONE' "$work/log$job"
  else
    status=1
    cat "$work/log$job"  # the report, and the failing input in Base64 when it is short
    echo "libFuzzer job $job (seed $((seed + job - 1))) failed; FUZZ_KEEP=1 keeps its input" >&2
  fi
  job=$((job + 1))
done
exit "$status"
