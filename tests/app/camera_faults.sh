#!/usr/bin/env bash
# A camera on the controller's computer that fails during the run stops it in a controlled way,
# exit 4, naming the cause, the journal keeping every whole episode (--resume continues there):
# the command ends, stalls, or sends a partial frame (frames of another size). The camera is
# ffmpeg's test pattern (any picture does: the goal space encodes whatever it is shown); the arm
# is curio-sim serve --no-camera-node.
#   camera_faults.sh CURIO_SIM CURIO_CONTROLLER WORKDIR
set -euo pipefail
sim=$1 controller=$2 work=$3
command -v ffmpeg > /dev/null || { echo "ffmpeg is not installed (toolchain/setup-debian.sh)"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
"$sim" serve --bus "$bus" --seed 2 --no-camera-node --exit-after-idle 30 --status-every 0 2> "$work/serve.log" &
serve_pid=$!
trap 'kill $serve_pid 2>/dev/null || true' EXIT
pattern="ffmpeg -nostdin -loglevel error -re -f lavfi -i testsrc=size=64x64:rate=25"
raw="-f rawvideo -pix_fmt rgb24 -flush_packets 1 -"
run() {  # NAME CAMERA [OPTIONS...]: expects exit 4
  local name=$1 camera=$2; shift 2
  set +e
  "$controller" --bus "$bus" --algo MGE-bVAE --seed 2 --bootstrap 300 --episodes 100 --camera "$camera" \
    --settle-ms 20 --camera-stall 500 --quiet --out "$work/$name" "$@" > "$work/$name.out" 2> "$work/$name.err"
  local rc=$?
  set -e
  [ $rc = 4 ] || { echo "$name: exit $rc, not 4"; cat "$work/$name.err"; exit 1; }
}
journaled() {  # episodes in the run's journal, from a resume that continues it
  sed -n 's/.*continuing at episode \([0-9]*\).*/\1/p' "$1"
}
check() {  # NAME REGEX: the cause named, some episodes kept, and a resume continues from them
  local name=$1 regex=$2
  grep -Eq "the camera failed: $regex" "$work/$name.err" || { echo "$name: cause not named:"; cat "$work/$name.err"; exit 1; }
  grep -q "camera_failed" "$work/$name.err" || { echo "$name: fault not named"; cat "$work/$name.err"; exit 1; }
  # A resume with a camera that ends at once: it replays the journal first, then stops again.
  set +e
  "$controller" --bus "$bus" --algo MGE-bVAE --seed 2 --bootstrap 300 --episodes 100 --resume \
    --camera "$pattern -frames:v 2 $raw" --settle-ms 20 --out "$work/$name" > "$work/$name.resume" 2>&1
  set -e
  local n ran; n=$(journaled "$work/$name.resume")
  ran=$(sed -n 's/^curio-controller: \([0-9]*\) episodes (.*/\1/p' "$work/$name.err")
  [ -n "$n" ] && [ "$n" -ge 3 ] && [ "$n" = "$ran" ] ||
    { echo "$name: the run archived '$ran' episodes, the journal kept '$n'"; cat "$work/$name.resume"; exit 1; }
  echo "$name: $(grep -o 'the camera failed: [^;]*' "$work/$name.err"); $n whole episodes journaled"
}
run ends "$pattern -t 1 $raw"
check ends "the command exited with status 0 after [0-9]+ frames"
run stalls "sh -c '$pattern -t 1 $raw; sleep 20'"
check stalls "stalled: no frame for 500 ms \(--camera-stall\) after [0-9]+ frames"
run partial "sh -c '$pattern -t 1 $raw; head -c 100 /dev/zero'"
check partial "the command exited with status 0 after [0-9]+ whole frames and 100 bytes more: its frames are not 64x64 RGB24"
echo "a camera that ends, stalls or sends another size stops the run (exit 4), the journal keeps every whole episode"
