#!/usr/bin/env bash
# The cell from the robot's side: binpickd with the demo settings on a small simulated bin, and
# `binpick robot-client` triggering cycles, fetching every pick and sending single requests.
set -uo pipefail
binpick="$1"
binpickd="$2"
config_dir="$3"
work=$(mktemp -d)
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
daemon=""
cleanup() { [ -n "$daemon" ] && kill -9 "$daemon" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT

# The demo settings name ../demo-output relative to their directory: give them one in $work.
mkdir -p "$work/config"
cp "$config_dir/demo-binpickd.yaml" "$config_dir/virtual-cell.yaml" "$work/config/"
"$binpick" simulate --part l_bracket --objects 8 --seed 4 --out "$work/demo-output/capture" 2>/dev/null ||
  fail "simulate exited $?"

"$binpickd" --config "$work/config/demo-binpickd.yaml" --check >"$work/check.log" 2>&1 || fail "--check: $(cat "$work/check.log")"
"$binpickd" --config "$work/config/demo-binpickd.yaml" --port 0 --port-file "$work/port" 2>"$work/daemon.log" &
daemon=$!
for _ in $(seq 600); do [ -s "$work/port" ] && break; sleep 0.1; done
port=$(cat "$work/port" 2>/dev/null)
[ -n "$port" ] || fail "binpickd did not start: $(cat "$work/daemon.log")"

"$binpick" robot-client --port "$port" --cycles 2 --orientation euler_zyx >"$work/client.log" 2>&1 ||
  fail "robot-client exited $?: $(cat "$work/client.log")"
grep -q "^cycle 1: TRIGGER ok: cycle 1 (" "$work/client.log" || fail "no first cycle: $(cat "$work/client.log")"
grep -q "^cycle 2: [1-9][0-9]* picks" "$work/client.log" || fail "no picks in cycle 2: $(cat "$work/client.log")"
pick="NEXT ok: 0 remaining, object [0-9]*, grasp [0-9]*, at x [-0-9.]* y [-0-9.]* z [-0-9.]* mm, euler_zyx"
grep -q "$pick A [-0-9.]* B [-0-9.]* C [-0-9.]* (" "$work/client.log" || fail "no last pick with its pose"

"$binpick" robot-client --port "$port" --send "PING;STATUS;MODEL,l_bracket;MODEL,nut;FAILED" >"$work/send.log" 2>&1 ||
  fail "robot-client --send exited $?"
for expected in "PING ok (" "STATUS ok: state idle, model 0, 2 cycles done (" "MODEL ok: model 0 (" \
  "MODEL unknown_model: model 0 (" "FAILED ok: object [0-9]* ("; do
  grep -q "^$expected" "$work/send.log" || fail "--send: no '$expected' in $(cat "$work/send.log")"
done

kill -TERM "$daemon"
wait "$daemon"
code=$?
daemon=""
[ "$code" -eq 0 ] || fail "binpickd exited $code on SIGTERM"
[ -s "$work/demo-output/cycles/$(ls "$work/demo-output/cycles" | tail -n 1)/overlay.png" ] || fail "no overlay saved"

# Nobody listening: one line naming the address, exit code 1.
err=$("$binpick" robot-client --port "$port" --connect-timeout-ms 200 2>&1 >/dev/null)
code=$?
[ "$code" -eq 1 ] || fail "robot-client without a daemon exited $code"
echo "$err" | grep -q "cannot connect to 127.0.0.1:$port" || fail "robot-client said '$err'"

[ "$failures" -eq 0 ] && echo "robot-client test passed"
exit "$failures"
