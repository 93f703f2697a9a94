#!/usr/bin/env bash
# The guided hand-eye session from the robot's side. `binpick calibrate hand-eye --listen` takes
# its images from a simulated eye-to-hand session (--replay: the virtual cell's camera);
# `binpick robot-client` plays the robot, sending the simulated flange poses as POSE requests.
# First run (ASCII): two views, a malformed POSE, a view of the bin without the board, then
# SIGTERM. Second run (binary, little-endian): the same command continues the session, takes the
# last three views and calibrates; the result must be near the simulation's truth.
set -uo pipefail
binpick="$1"
work=$(mktemp -d)
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
session=""
pile=""
cleanup() {
  for pid in $session $pile; do kill -9 "$pid" 2>/dev/null; done
  rm -rf "$work"
}
trap cleanup EXIT

# A bin under white light: an image of the right size without any board. Both renders at once.
"$binpick" simulate --part l_bracket --objects 1 --seed 2 --out "$work/pile" >/dev/null 2>&1 &
pile=$!
"$binpick" simulate --hand-eye eye-to-hand --views 5 --seed 5 --orientation euler_zyx \
  --out "$work/sim" >"$work/simulate.log" 2>&1 || fail "simulate --hand-eye: $(cat "$work/simulate.log")"
wait "$pile" || fail "simulate --part exited $?"
pile=""

# The camera of each run, in name order: the bin comes third, after view_01.
mkdir -p "$work/camera1" "$work/camera2"
cp "$work/sim/view_00.png" "$work/sim/view_01.png" "$work/camera1/"
cp "$work/pile/images/000_white.png" "$work/camera1/view_01x.png"
cp "$work/sim"/view_0[2-4].png "$work/camera2/"

# The simulated poses (x y z A B C) as requests: pose N is line N + 1.
grep '^view_' "$work/sim/poses.txt" |
  awk '{ printf "POSE,%s,%s,%s,%s,%s,%s\n", $2, $3, $4, $5, $6, $7 }' >"$work/requests"
pose() { sed -n "$(($1 + 1))p" "$work/requests"; }

common=(calibrate hand-eye --listen --record "$work/rec" --count 5 --min-views 5 --port 0 --port-file "$work/port"
        --calib "$work/sim/calib.yaml" --setup eye-to-hand --orientation euler_zyx
        --out "$work/hand_eye.yaml")
port=""
start_session() {  # CAMERA_DIR LOG [options]
  local camera="$1" log="$2"
  shift 2
  rm -f "$work/port"
  "$binpick" "${common[@]}" --replay "$camera" "$@" >"$log" 2>&1 &
  session=$!
  for _ in $(seq 600); do
    [ -s "$work/port" ] && break
    kill -0 "$session" 2>/dev/null || break
    sleep 0.1
  done
  port=$(cat "$work/port" 2>/dev/null)
  [ -n "$port" ] || fail "the session did not start: $(cat "$log")"
}
expect_lines() {  # FILE LINE...: each line starts a line of FILE
  local file="$1"
  shift
  for line in "$@"; do grep -q "^$line" "$file" || fail "no '$line' in: $(cat "$file")"; done
}

# --- first run: ASCII, and robots silent for a second disconnected
start_session "$work/camera1" "$work/session1.log" --idle-timeout-s 1
"$binpick" robot-client --port "$port" --orientation euler_zyx --send "PING;STATUS;$(pose 0)" \
  >"$work/robot1.log" 2>&1 || fail "robot-client exited $?: $(cat "$work/robot1.log")"
# robot-client sends only well-formed requests: this one goes straight onto the socket.
exec 3<>"/dev/tcp/127.0.0.1/$port"
printf 'POSE,600,0,nan,180,0,0\r\n' >&3
IFS= read -r -t 60 malformed <&3
exec 3>&-
[ "${malformed%$'\r'}" = "POSE,8" ] || fail "a malformed POSE was answered '$malformed'"
# A robot that says nothing: closed after --idle-timeout-s (read sees the end: 1, not a time-out).
exec 3<>"/dev/tcp/127.0.0.1/$port"
IFS= read -r -t 60 silent <&3
idle_read=$?
exec 3>&-
[ "$idle_read" -eq 1 ] || fail "a silent robot was not disconnected after --idle-timeout-s 1 (read returned $idle_read)"
# The second is taken of the bin without the board.
"$binpick" robot-client --port "$port" --orientation euler_zyx --send "$(pose 1);$(pose 1)" \
  >>"$work/robot1.log" 2>&1 || fail "robot-client exited $?: $(cat "$work/robot1.log")"
expect_lines "$work/robot1.log" "PING ok" "STATUS ok: state waiting, 0 views accepted, 5 wanted" \
  "POSE ok: 1 views accepted, 5 wanted" "POSE ok: 2 views accepted, 5 wanted" \
  "POSE board_not_found: 2 views accepted, 5 wanted"
kill -TERM "$session"
wait "$session"
code=$?
session=""
[ "$code" -ne 0 ] || fail "stopped with 2 of 5 views, the session exited 0"
grep -q "stopped with 2 of 5 views" "$work/session1.log" || fail "no stop message: $(cat "$work/session1.log")"
[ "$(grep -c ': accepted as view_' "$work/session1.log")" -eq 2 ] || fail "not one line per accepted view"
[ "$(cd "$work/rec" && echo *.png)" = "view_000.png view_001.png" ] || fail "views: $(ls "$work/rec")"
[ -s "$work/rec/rejected/attempt_003.png" ] || fail "the view without a board was not kept"
grep -q "^attempt_003 " "$work/rec/rejected/poses.txt" || fail "its pose was not kept"
[ "$(grep -c '^attempt_' "$work/rec/received.txt")" -eq 3 ] || fail "received: $(cat "$work/rec/received.txt")"

# The recorded poses are in euler_zyx: a robot sending quaternions cannot add to them.
timeout 60 "$binpick" "${common[@]/euler_zyx/quaternion}" --replay "$work/camera2" >"$work/mismatch.log" 2>&1 &&
  fail "a session in another orientation convention was continued"
grep -q "euler_zyx" "$work/mismatch.log" || fail "the refusal does not say why: $(cat "$work/mismatch.log")"

# Mistakes are told before the robot is waited for.
refused() {  # CODE TEXT OPTION...: the command exits CODE (1 bad input, 2 a usage error) naming TEXT
  local expected="$1" text="$2"
  shift 2
  out=$(timeout 60 "$binpick" calibrate hand-eye --listen --record "$work/other" --port 0 \
    --calib "$work/sim/calib.yaml" --setup eye-to-hand --out "$work/other.yaml" "$@" 2>&1)
  code=$?
  [ "$code" -eq "$expected" ] && echo "$out" | grep -q -- "$text" || fail "$* gave $code: $out"
}
refused 1 "at least the views the calibration needs" --count 3 --replay "$work/camera2"
refused 2 "--replay excludes --camera" --count 6 --replay "$work/camera2" --camera 10.0.0.9
refused 2 "--camera or --replay is required" --count 6
refused 2 "--count is required" --replay "$work/camera2"
refused 2 "--exposure-us requires --camera" --count 6 --replay "$work/camera2" --exposure-us 100
refused 1 "orientation 'abc' is unknown" --count 6 --replay "$work/camera2" --orientation abc
[ ! -e "$work/other" ] || fail "a refused session created its directory"

# --- second run: binary, little-endian; the robot disconnects after the last view
start_session "$work/camera2" "$work/session2.log" --framing binary --byte-order little
"$binpick" robot-client --port "$port" --orientation euler_zyx --framing binary --byte-order little \
  --send "STATUS;$(pose 2);$(pose 3);$(pose 4)" >"$work/robot2.log" 2>&1 ||
  fail "robot-client exited $?: $(cat "$work/robot2.log")"
expect_lines "$work/robot2.log" "STATUS ok: state waiting, 2 views accepted, 5 wanted" \
  "POSE ok: 3 views accepted, 5 wanted" "POSE ok: 4 views accepted, 5 wanted" "POSE ok: 5 views accepted, 5 wanted"
wait "$session"
code=$?
session=""
[ "$code" -eq 0 ] || fail "the calibration exited $code: $(cat "$work/session2.log")"

# The first transform of a hand_eye.yaml: "tx ty tz qw qx qy qz" (metres, quaternion).
transform() {
  awk '/translation:/ && t == "" { gsub(/.*\[|\].*/, ""); gsub(/,/, " "); t = $0 }
       /rotation:/ && r == "" { gsub(/.*\[|\].*/, ""); gsub(/,/, " "); r = $0 }
       END { print t, r }' "$1"
}
if [ -s "$work/hand_eye.yaml" ]; then
  error=$(echo "$(transform "$work/hand_eye.yaml") $(transform "$work/sim/truth/hand_eye.yaml")" |
    awk '{ mm = 1000 * sqrt(($1 - $8)^2 + ($2 - $9)^2 + ($3 - $10)^2)
           dot = $4 * $11 + $5 * $12 + $6 * $13 + $7 * $14; if (dot < 0) dot = -dot; if (dot > 1) dot = 1
           printf "%.3f %.4f", mm, 2 * atan2(sqrt(1 - dot * dot), dot) * 180 / 3.14159265358979 }')
  echo "T_base_camera against the truth: ${error% *} mm, ${error#* } deg"
  awk -v e="$error" 'BEGIN { split(e, v, " "); exit !(v[1] < 1.0 && v[2] < 0.1) }' ||
    fail "T_base_camera is ${error% *} mm and ${error#* } deg from the truth"
else
  fail "no hand_eye.yaml: $(cat "$work/session2.log")"
fi

[ "$failures" -eq 0 ] && echo "guided hand-eye session test passed"
exit "$failures"
