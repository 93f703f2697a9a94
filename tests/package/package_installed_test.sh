#!/usr/bin/env bash
# Usage: package_installed_test.sh DEB_DIR SYSTEMD_ANALYZE VERIFY_UNIT_SCRIPT
# The package as installed, in a scratch root (dpkg-deb -x): the unit passes systemd-analyze verify
# against the installed binpickd; `binpickd --check` accepts the installed example settings; and
# binpickd starts from them in replay mode and serves a robot (calibration not yet done: TRIGGER
# answers calibration_missing) and its web view, and runs a cycle once a calibration and a capture
# are in place.
set -uo pipefail
deb_dir=$1 analyze=$2 verify_unit=$3
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
scratch=$(mktemp -d)
daemon=""
cleanup() { [ -n "$daemon" ] && kill -9 "$daemon" 2>/dev/null; rm -rf "$scratch"; }
trap cleanup EXIT

deb=$(ls "$deb_dir"/binpick_*.deb 2>/dev/null | head -n 1)
[ -n "$deb" ] || { echo "FAIL: no package in $deb_dir (package_build makes it)"; exit 1; }
root=$scratch/root
dpkg-deb -x "$deb" "$root"
unit=$root/usr/lib/systemd/system/binpickd.service
binpickd=$root/usr/bin/binpickd
binpick=$root/usr/bin/binpick

grep -qxF 'ExecStart=/usr/bin/binpickd --config /etc/binpick/binpickd.yaml' "$unit" ||
  fail "the unit starts $(grep '^ExecStart=' "$unit")"
"$binpickd" --version | grep -q '^binpickd ' || fail "the installed binpickd does not run"
# verify insists that ExecStart's program exists: point it at the installed binary in the root.
mkdir -p "$scratch/verify"
sed "s#^ExecStart=/usr/bin/binpickd #ExecStart=$binpickd #" "$unit" >"$scratch/verify/binpickd.service"
sh "$verify_unit" "$analyze" "$scratch/verify/binpickd.service"
code=$?
[ "$code" -eq 0 ] || [ "$code" -eq 77 ] || fail "systemd-analyze verify refused the installed unit"

# The example settings, with the root's places for /etc/binpick, /usr/share/binpick and the state.
mkdir -p "$scratch/etc" "$scratch/state"
sed -e "s#/usr/share/binpick/#$root/usr/share/binpick/#g" -e "s#/etc/binpick/#$scratch/etc/#g" \
    -e "s#/var/lib/binpick/#$scratch/state/#g" "$root/etc/binpick/binpickd.yaml" >"$scratch/etc/binpickd.yaml"
# With the web view on, whose HTTP transport is a plugin the installed binpickd must find.
printf 'web: {bind_address: 127.0.0.1, port: 0}\n' >>"$scratch/etc/binpickd.yaml"
"$binpickd" --config "$scratch/etc/binpickd.yaml" --check >"$scratch/check.log" 2>&1 ||
  fail "--check on the example exited $?: $(cat "$scratch/check.log")"
grep -q "1 recipe(s) ready" "$scratch/check.log" || fail "--check said: $(cat "$scratch/check.log")"

"$binpickd" --config "$scratch/etc/binpickd.yaml" --port 0 --port-file "$scratch/port" 2>"$scratch/daemon.log" &
daemon=$!
for _ in $(seq 300); do [ -s "$scratch/port" ] && break; sleep 0.1; done
port=$(cat "$scratch/port" 2>/dev/null)
if [ -z "$port" ]; then
  fail "binpickd did not start from the example: $(cat "$scratch/daemon.log")"
else
  "$binpick" robot-client --port "$port" --send "PING;STATUS;TRIGGER" >"$scratch/client.log" 2>&1
  for expected in "PING ok" "STATUS ok" "TRIGGER calibration_missing"; do
    grep -q "^$expected" "$scratch/client.log" || fail "no '$expected' from binpickd: $(cat "$scratch/client.log")"
  done
  web_port=$(sed -n 's#.*web view on http://127.0.0.1:\([0-9]*\)/.*#\1#p' "$scratch/daemon.log" | head -n 1)
  if [ -z "$web_port" ]; then
    fail "no web view: $(cat "$scratch/daemon.log")"
  elif exec 3<>"/dev/tcp/127.0.0.1/$web_port"; then
    printf 'GET /api/status HTTP/1.0\r\n\r\n' >&3
    head -n 1 <&3 | grep -q '^HTTP/1.[01] 200' || fail "the web view does not answer /api/status"
    exec 3<&-
  else
    fail "cannot connect to the web view on port $web_port"
  fi
  # Calibrated and recorded: a capture of the virtual cell (with its calib.yaml) in the replay
  # directory, the settings reloaded (SIGHUP), and the next TRIGGER runs a cycle.
  "$binpick" simulate --part l_bracket --objects 3 --seed 2 --out "$scratch/state/replay/capture_0001" 2>/dev/null ||
    fail "the installed binpick cannot simulate a capture"
  cp "$scratch/state/replay/capture_0001/calib.yaml" "$scratch/etc/calib.yaml"
  kill -HUP "$daemon"
  for _ in $(seq 100); do grep -q "reloaded\|reload failed" "$scratch/daemon.log" && break; sleep 0.1; done
  "$binpick" robot-client --port "$port" --cycles 1 >"$scratch/cycle.log" 2>&1
  grep -q "^cycle 1: TRIGGER ok" "$scratch/cycle.log" || fail "no cycle after calibration: $(cat "$scratch/cycle.log")"
  kill -TERM "$daemon"
  wait "$daemon"
  code=$?
  daemon=""
  [ "$code" -eq 0 ] || fail "binpickd exited $code on SIGTERM: $(cat "$scratch/daemon.log")"
fi

[ "$failures" -eq 0 ] && echo "installed unit verified; the example settings check and serve"
exit "$failures"
