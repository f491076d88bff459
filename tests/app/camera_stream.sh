#!/usr/bin/env bash
# A camera on the controller's computer, as on a real bench: `curio-sim serve --no-camera-node
# --camera-stream SOCK` streams its scene (raw RGB24, fixed frame rate, wall clock) with no
# camera node on the bus, and `curio-controller --camera 'ffmpeg ... -i unix:SOCK ... -'` reads
# it through ffmpeg, paced (--period-us), for MGE-βVAE. Checked:
#   - the arm comes up without node 32 (the serve answers nothing as 0x20, no capture served);
#   - every encoded frame is fresh (arrived after the settle time, each a new frame);
#   - the archive (θ and latents of every episode) equals a CAN-camera run's, bit for bit,
#     when the stream is the exact 64x64 render;
#   - the summary says the ratio was not measured; curio-lab score with the serve's positions
#     gives the CAN-camera run's ratio, and scoring the CAN-camera run itself gives its live
#     figure (the ratio files identical);
#   - with RESIZED=1 also a 128x128 stream (resampled to 64x64 by the controller): the
#     bootstrap's latents within 0.05 of the exact run's.
#   camera_stream.sh CURIO_SIM CURIO_CONTROLLER CURIO_LAB WORKDIR [BOOTSTRAP EPISODES RESIZED]
set -euo pipefail
sim=$1 controller=$2 lab=$3 work=$4 bootstrap=${5:-40} episodes=${6:-10} resized=${7:-0}
settle=${CAMERA_SETTLE_MS:-250}
total=$((bootstrap + episodes))
command -v ffmpeg > /dev/null || { echo "ffmpeg is not installed (toolchain/setup-debian.sh)"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
serve_pid=
trap '[ -z "$serve_pid" ] || kill $serve_pid 2>/dev/null || true' EXIT
run_opts=(--algo MGE-bVAE --seed 7 --bootstrap "$bootstrap" --episodes "$episodes" --print-checksum)

# 1. The reference: the CAN camera node (ground truth and frame over the bus).
"$sim" serve --bus "$bus" --seed 7 --exit-after-idle 20 --status-every 0 --positions "$work/can_positions.csv" \
  2> "$work/can_serve.log" &
serve_pid=$!
"$controller" --bus "$bus" "${run_opts[@]}" --out "$work/can" --quiet > "$work/can.out" 2> "$work/can.err" ||
  { cat "$work/can.err" "$work/can_serve.log"; exit 1; }
kill -INT $serve_pid; wait $serve_pid || true; serve_pid=

# A camera run: serve streaming WxH with no camera node, the controller reading it via ffmpeg.
camera_run() {  # NAME SIZE
  local name=$1 size=$2 sock="$work/$1.sock"
  "$sim" serve --bus "$bus" --seed 7 --exit-after-idle 20 --status-every 0 --no-camera-node \
    --camera-stream "$sock" --camera-size "$size" --camera-fps 50 --positions "$work/${name}_positions.csv" \
    2> "$work/${name}_serve.log" &
  serve_pid=$!
  for _ in $(seq 100); do [ -S "$sock" ] && break; sleep 0.05; done
  local ffmpeg="ffmpeg -nostdin -hide_banner -loglevel error -f rawvideo -pix_fmt rgb24 -video_size $size \
-framerate 50 -i unix:$sock -f rawvideo -pix_fmt rgb24 -flush_packets 1 -"
  # Exit 3: a fault (a late feedback on a loaded machine) was replayed; without a camera node
  # the controller cannot know that the serve replays the episode's scene, so it marks the
  # results. The serve does replay it: the checksum below must still match.
  local rc=0
  "$controller" --bus "$bus" "${run_opts[@]}" --camera "$ffmpeg" --camera-size "$size" --settle-ms "$settle" \
    --period-us 1000 --save-frames --out "$work/$name" --quiet > "$work/$name.out" 2> "$work/$name.err" || rc=$?
  [ $rc = 0 ] || [ $rc = 3 ] || { cat "$work/$name.err" "$work/${name}_serve.log" "$work/$name/camera.log"; exit 1; }
  [ $rc = 0 ] || echo "($name: a fault was replayed, exit 3: $(tail -1 "$work/$name.err"))"
  kill -INT $serve_pid; wait $serve_pid || true; serve_pid=
  cat "$work/$name.out"
}
start=$(date +%s.%N)
camera_run exact 64x64
echo "camera run: $(python3 -c "import time; print(f'{time.time() - $start:.1f}')") s for $total episodes"

# Without node 32: the serve said so, served no capture, and the controller never asked it.
grep -q "no camera node" "$work/exact_serve.log" || { echo "the serve ran a camera node"; exit 1; }
grep -q " 0 captures" "$work/exact_serve.log" || { echo "captures were served:"; cat "$work/exact_serve.log"; exit 1; }
grep -q "exploration ratio after $total episodes: not measured" "$work/exact.out" ||
  { echo "the summary does not say the ratio was not measured"; exit 1; }
can_sum=$(sed -n 's/^archive checksum \(0x[0-9a-f]*\).*/\1/p' "$work/can.out")
cam_sum=$(sed -n 's/^archive checksum \(0x[0-9a-f]*\).*/\1/p' "$work/exact.out")
[ -n "$can_sum" ] && [ "$can_sum" = "$cam_sum" ] ||
  { echo "archive checksum $cam_sum over ffmpeg differs from the CAN camera's $can_sum"; exit 1; }
python3 - "$work/exact/summary.json" "$total" "$work/exact/frames" "$settle" <<'PY'
import json, os, sys
s = json.load(open(sys.argv[1])); total = int(sys.argv[2]); c = s["camera"]
assert s["ground_truth"] is False and s["exploration_ratio"] is None and "not measured" in s["exploration_ratio_why"], s
assert c["frames_taken"] == total and c["every_frame_fresh"] is True, c
assert c["wait_ms"]["p50"] >= c["settle_ms"] == float(sys.argv[4]), c
assert len(s["modules"]) == 5 and all(0 < m["latent_coverage"] <= 1 for m in s["modules"]), s["modules"]
frames = sorted(os.listdir(sys.argv[3]))
assert len(frames) == total and frames[0] == "episode_000000.png", frames[:3]
print(f"every one of {total} frames fresh: last period to frame p50 {c['wait_ms']['p50']:.1f} ms, "
      f"max {c['wait_ms']['max']:.1f} ms (settle {c['settle_ms']:.0f} ms), frame interval max {c['frame_interval_ms']['max']:.0f} ms; {c['frames_read']} frames read")
PY

# Scored later: the camera run with the serve's positions = the CAN run's live figures, and
# the CAN run scored with its own positions = its live figures.
"$lab" score --run "$work/exact" --positions "$work/exact_positions.csv" --quiet > "$work/score_exact.out"
"$lab" score --run "$work/can" --positions "$work/can_positions.csv" --quiet > "$work/score_can.out"
cat "$work/score_exact.out"
live=$(sed -n 's/^exploration ratio after \([0-9]*\) episodes: \([0-9.]*\).*/\1 \2/p' "$work/can.out")
for f in score_exact score_can; do
  got=$(sed -n 's/^exploration ratio after \([0-9]*\) episodes: \([0-9.]*\).*/\1 \2/p' "$work/$f.out")
  [ -n "$live" ] && [ "$got" = "$live" ] || { echo "$f: ratio '$got', live '$live'"; exit 1; }
done
for d in exact/score can/score; do
  cmp "$work/can/runs/MGE-βVAE_sigma0.05_seed7.csv" "$work/$d/runs/MGE-βVAE_sigma0.05_seed7.csv" ||
    { echo "$d: ratio file differs from the live run's"; exit 1; }
done

if [ "$resized" = 1 ]; then
  camera_run resized 128x128
  python3 - "$work/exact/latents.csv" "$work/resized/latents.csv" "$bootstrap" <<'PY'
import csv, sys
a = list(csv.reader(open(sys.argv[1])))[1:]; b = list(csv.reader(open(sys.argv[2])))[1:]
n = int(sys.argv[3])  # random θ: the same episodes whatever the latents
worst = max(abs(float(x) - float(y)) for ra, rb in zip(a[:n], b[:n]) for x, y in zip(ra[1:], rb[1:]))
print(f"128x128 resampled: largest latent difference over {n} episodes {worst:.4f}")
assert worst <= 0.05, worst
PY
fi
echo "camera over ffmpeg: comes up without node 32, every frame fresh, archive equal to the CAN camera's"
