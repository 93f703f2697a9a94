#!/usr/bin/env bash
# Usage: command_line_test.sh BINPICKD
# binpickd's command line follows the conventions of binpick's programs: --help and --version on
# stdout with exit 0; a usage error is one line on stderr with a hint to --help, exit 2; settings
# that cannot be read are one line naming them, exit 1.
set -uo pipefail
binpickd=$1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

run() {  # run ARGS...: sets out, err, code
  "$binpickd" "$@" >"$scratch/out" 2>"$scratch/err"
  code=$?
  out=$(cat "$scratch/out")
  err=$(cat "$scratch/err")
}

run --help
[ "$code" -eq 0 ] || fail "--help exited $code"
[ -z "$err" ] || fail "--help wrote on stderr: $err"
for option in --config --port --port-file --check --verbose --version; do
  printf '%s\n' "$out" | grep -q -- "$option" || fail "--help does not list $option"
done

run --version
[ "$code" -eq 0 ] || fail "--version exited $code"
printf '%s\n' "$out" | grep -Eq '^binpickd [0-9]+\.[0-9]+\.[0-9]+( \(git [0-9a-f]+(-dirty)?\))?$' ||
  fail "--version printed '$out'"

usage_error() {  # usage_error WHAT ARGS...
  local what=$1
  shift
  run "$@"
  [ "$code" -eq 2 ] || fail "$what: exit $code, expected 2 ($err)"
  [ -z "$out" ] || fail "$what: wrote on stdout: $out"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "$what: not one line: $err"
  printf '%s\n' "$err" | grep -q -- "--help" || fail "$what: no hint to --help: $err"
}
usage_error "no --config"
usage_error "an unknown option" --config x.yaml --bogus
usage_error "--config without its value" --config
usage_error "a port that is no number" --config x.yaml --port abc
usage_error "a port out of range" --config x.yaml --port 70000
usage_error "a stray argument" --config x.yaml extra

run --config "$scratch/missing.yaml" --check
[ "$code" -eq 1 ] || fail "missing settings: exit $code, expected 1"
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] && printf '%s\n' "$err" | grep -q "missing.yaml" ||
  fail "missing settings: '$err'"

[ "$failures" -eq 0 ] && echo "binpickd's command line follows the conventions"
exit "$failures"
