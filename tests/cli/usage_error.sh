# Sourced by the command-line tests: expect_usage_error "pattern" command... checks a usage error:
# exit code 2 and one line on stderr that contains the pattern and a hint to --help. The caller
# defines fail().
expect_usage_error() {
  local pattern="$1"; shift
  local err
  err=$("$@" 2>&1 >/dev/null </dev/null)
  local code=$?
  [ "$code" -eq 2 ] || fail "'$*' exited $code, expected 2 (a usage error)"
  [ "$(echo "$err" | wc -l)" -eq 1 ] || fail "'$*' printed more than one line: $err"
  echo "$err" | grep -q -- "$pattern" && echo "$err" | grep -q -- "--help" || fail "'$*' said '$err', expected '$pattern' and a hint to --help"
}
