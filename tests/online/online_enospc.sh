#!/usr/bin/env bash
# curio-online on a disk that fills at its Nth write (LD_PRELOAD shim tests/common/enospc_shim.c):
# a toy run (400 + 300 episodes, three retrains) tried with the disk full from every STRIDEth of
# its writes (checkpoints, their .crc, scenes, state, reports, figures) ends with exit 1 and a
# last line naming the file and "No space left on device", never an abort (LibTorch's file
# writer throws from its destructor on a full disk: checkpoints are serialised in memory), and
# leaves no temporary file.
#   tests/online/online_enospc.sh CURIO_ONLINE SHIM.so WORK_DIR [STRIDE, default 10]
set -euo pipefail
online=$(realpath "$1") shim=$(realpath "$2") work=$3 stride=${4:-10}
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
toy=(--seed 3 --episodes 300 --retrain-every 100 --first-iterations 20 --retrain-iterations 10
     --no-baselines --threads 1 --quiet)
LD_PRELOAD=$shim CURIO_ENOSPC_COUNT=$PWD/count.txt "$online" "${toy[@]}" --out ref > /dev/null 2> ref.err ||
  fail "the dry run failed: $(tail -1 ref.err)"
total=$(sort -n count.txt | tail -1)
tried=0
for n in $(seq 1 "$stride" "$total") "$total"; do
  rm -rf out
  rc=0
  LD_PRELOAD=$shim CURIO_ENOSPC_AT=$n "$online" "${toy[@]}" --out out > /dev/null 2> err.txt || rc=$?
  [ $rc = 1 ] || fail "disk full from write $n: exit $rc, not 1: $(tail -3 err.txt)"
  tail -1 err.txt | grep -q "No space left on device" ||
    fail "disk full from write $n: the last line does not name the full disk: $(tail -1 err.txt)"
  [ -z "$(find out -name '*.tmp.*' 2> /dev/null)" ] || fail "disk full from write $n: temporary files left"
  tried=$((tried + 1))
done
echo "curio-online: $tried of its $total writes failing (every ${stride}th and the last): exit 1 naming the full disk"
