#!/usr/bin/env bash
# A disk that fills at a chosen write, tried at the writes of `curio-lab run` (the shim
# tests/common/enospc_shim.c makes the Nth write to a regular file, and every later one, fail
# with ENOSPC, as SQLite's tests inject I/O errors): at each N the run exits non-zero with a
# last line naming the file and "No space left on device", and leaves nothing truncated and no
# temporary file. Every write of a report rewritten from finished records is tried, and the
# writes of a fresh run (its journal appends dominate) at a stride. One write beyond the last
# the command succeeds. gnuplot writes its PNGs through glibc's internal calls, which the shim
# does not see: tests/lab/full_disk.sh covers those on a real full tmpfs.
#   tests/lab/enospc_every_write.sh CURIO_LAB SHIM.so WORK_DIR [STRIDE for the fresh run, default 40]
set -euo pipefail
source "$(dirname "$0")/whole_outputs.sh"
lab=$(realpath "$1") shim=$(realpath "$2") work=$3 stride=${4:-40}
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
camp=(--algos RPE,MGE-EFR --seeds 0 --episodes 300 --threads 1 --quiet)

# How many writes a command makes: the largest count over its processes.
writes_of() {  # writes_of PRESEED -- command...: the count; the command must succeed
  local preseed=$1
  shift
  rm -rf out count.txt
  [ -z "$preseed" ] || cp -a "$preseed" out
  LD_PRELOAD=$shim CURIO_ENOSPC_COUNT=$PWD/count.txt "$@" --out out > /dev/null 2> err.txt ||
    fail "the dry run failed: $(tail -1 err.txt)"
  sort -n count.txt | tail -1
}

# Runs the command with the disk full from write N; checks what it did.
try_at() {  # try_at N PRESEED WHAT -- command...
  local n=$1 preseed=$2 what=$3 rc=0
  shift 3
  rm -rf out
  [ -z "$preseed" ] || cp -a "$preseed" out
  LD_PRELOAD=$shim CURIO_ENOSPC_AT=$n "$@" --out out > /dev/null 2> err.txt || rc=$?
  [ $rc != 0 ] || fail "$what, disk full from write $n: exit 0"
  tail -1 err.txt | grep -q "No space left on device" ||
    fail "$what, disk full from write $n: the last line does not name the full disk: $(tail -1 err.txt)"
  [ ! -d out ] || check_whole out "$what, disk full from write $n"
}

"$lab" run "${camp[@]}" --out finished > /dev/null 2>&1 || fail "the reference run failed"
mkdir records_only && cp -a finished/manifest.json finished/records records_only/

total=$(writes_of records_only "$lab" run "${camp[@]}")
for n in $(seq 1 "$total"); do try_at "$n" records_only "report rewrite" "$lab" run "${camp[@]}"; done
rm -rf out && cp -a records_only out
LD_PRELOAD=$shim CURIO_ENOSPC_AT=$((total + 1)) "$lab" run "${camp[@]}" --out out > /dev/null 2>&1 ||
  fail "report rewrite: failed with room for every write"
echo "report rewrite: each of its $total writes failing: exit 1 naming the full disk, nothing truncated"

total=$(writes_of "" "$lab" run "${camp[@]}")
tried=0
for n in $(seq 1 "$stride" "$total") "$total"; do
  try_at "$n" "" "fresh run" "$lab" run "${camp[@]}"
  tried=$((tried + 1))
done
echo "fresh run: $tried of its $total writes failing (every ${stride}th and the last): exit 1 naming the full disk, nothing truncated"
