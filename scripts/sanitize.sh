#!/usr/bin/env bash
# Runs the suites with threads, sockets and parsers of untrusted input under the sanitizers: the
# core, robot, cell, web and daemon tests (ctest labels; binpickd as the daemon and web suites
# start it) and the fuzz targets' smoke drivers on their corpora (fuzz/corpus/TARGET/), twice:
#   address   AddressSanitizer + LeakSanitizer + UndefinedBehaviorSanitizer, in build-asan/
#   thread    ThreadSanitizer, in build-tsan/ (without OpenMP: cmake/Sanitize.cmake says why)
# Each build (RelWithDebInfo at -O1, cmake -DBINPICK_SANITIZE=...) holds only what these suites need (target
# sanitize_suites). Every process's reports are written to build-*/sanitizer-reports/ (a binpickd
# a test starts too, whose stderr the test may not show) and printed at the end; any report, or a
# failed test, fails the run. Suppressions, each with its reason: sanitizers/*.supp.
#
#   bash scripts/sanitize.sh                  both, address first
#   bash scripts/sanitize.sh address|thread   one of them
#   env: JOBS (default: nproc) compilers and tests at a time; FUZZ_INPUTS (default 5000) seeded
#        inputs per fuzz target after its corpus; CTEST_ARGS extra ctest arguments (e.g. "-R Daemon"
#        for part of the suites)
#
# Time on 2 cores: see README, "Sanitizers". Too long for every CI run: run it before every release.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
jobs=${JOBS:-$(nproc)}
suites='^(core|robot|cell|web|daemon)$'
fuzz_inputs=${FUZZ_INPUTS:-5000}

case "${1:-all}" in
  all) sanitizers=(address thread) ;;
  address|thread) sanitizers=("$1") ;;
  *) echo "usage: scripts/sanitize.sh [address|thread]" >&2; exit 2 ;;
esac

bash scripts/install-deps.sh

now() { date +%s; }
summary=()
status=0

# run_corpora BUILD: every fuzz/corpus/TARGET/ through TARGET's smoke driver (TARGET_fuzz_driver,
# fuzz/random_input_driver.cpp): each corpus file as it is, then FUZZ_INPUTS seeded mutations.
run_corpora() {
  local build=$1 corpus target driver result=0
  for corpus in fuzz/corpus/*/; do
    [ -d "$corpus" ] || continue
    target=$(basename "$corpus")
    driver=$(find "$build" -type f -perm -u+x -name "${target}_fuzz_driver" | head -n 1)
    if [ -z "$driver" ]; then
      echo "sanitize: fuzz/corpus/$target has no smoke driver ${target}_fuzz_driver" >&2
      result=1
      continue
    fi
    echo "sanitize: fuzz/corpus/$target through ${target}_fuzz_driver"
    "$driver" "$corpus" "$fuzz_inputs" || { echo "sanitize: ${target}_fuzz_driver failed" >&2; result=1; }
  done
  return "$result"
}

for sanitizer in "${sanitizers[@]}"; do
  case "$sanitizer" in
    address) build=build-asan; flags=address,undefined ;;
    thread) build=build-tsan; flags=thread ;;
  esac
  reports=$root/$build/sanitizer-reports

  start=$(now)
  # RelWithDebInfo: -g and NDEBUG (the sanitizers' -O1 replaces its -O2). Eigen's own index checks
  # (on without NDEBUG) made detection 5 times slower again, enough for a cycle under TSan to miss
  # its processing deadline; out-of-bounds access to Eigen's heap arrays is what ASan finds anyway.
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBINPICK_SANITIZE="$flags" -DBINPICK_BUILD_BENCH=OFF \
    >/dev/null
  cmake --build "$build" -j"$jobs" --target sanitize_suites
  built=$(now)

  rm -rf "$reports"
  mkdir -p "$reports"
  # Reports go to files named after the tool and the process id, whichever process writes them.
  export ASAN_OPTIONS="log_path=$reports/asan:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:detect_leaks=1"
  export LSAN_OPTIONS="suppressions=$root/sanitizers/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="log_path=$reports/ubsan:print_stacktrace=1:halt_on_error=1:suppressions=$root/sanitizers/ubsan.supp"
  export TSAN_OPTIONS="log_path=$reports/tsan:suppressions=$root/sanitizers/tsan.supp:second_deadlock_stack=1:print_suppressions=0"

  failed=0
  # shellcheck disable=SC2086
  # The suites, without libFuzzer (label fuzz: a clang build of its own) and the fuzz smoke tests
  # (run_corpora runs every corpus).
  (cd "$build" && ctest -L "$suites" -LE fuzz -E '_fuzz_smoke$' --output-on-failure -j"$jobs" ${CTEST_ARGS:-}) ||
    failed=1
  run_corpora "$build" || failed=1
  unset ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS TSAN_OPTIONS
  ran=$(now)

  # GCC's UBSan runtime ignores log_path when ASan is linked too: its reports (which abort the
  # process, failing its test) are on stderr, which ctest keeps in LastTest.log.
  log=$build/Testing/Temporary/LastTest.log
  if [ -f "$log" ] && grep -q 'runtime error:' "$log"; then
    grep -B2 -A12 'runtime error:' "$log" > "$reports/ubsan-from-test-output"
  fi
  found=$(find "$reports" -type f | wc -l)
  if [ "$found" -gt 0 ]; then
    for report in "$reports"/*; do
      echo "===== $sanitizer: ${report#"$root"/}"
      cat "$report"
    done
    failed=1
  fi
  summary+=("$sanitizer: build $((built - start)) s, tests $((ran - built)) s, $found report(s)$([ "$failed" = 0 ] || echo ", FAILED")")
  [ "$failed" = 0 ] || status=1
done

printf 'sanitize: %s\n' "${summary[@]}"
exit "$status"
