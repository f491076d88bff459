#!/usr/bin/env bash
# A journal that fills the disk mid-run, tried as a user would: `curio-sim serve` and
# `curio-controller` on the UDP bus, the controller's --out on a small tmpfs. The run must stop
# at once with exit 1 and a message naming the journal and "No space left on device" (not a
# bus fault), its journal whole up to the episode before; moved to a roomy disk and resumed,
# it must finish with the archive checksum of an undisturbed run: nothing lost.
# The tmpfs is mounted in a private user and mount namespace (`unshare -rm`, no root needed);
# where the kernel refuses one the test is skipped (exit 77).
#   full_disk_journal.sh CURIO_SIM CURIO_CONTROLLER WORK_DIR
set -euo pipefail
sim=$(realpath "$1") controller=$(realpath "$2") work=$3
episodes=3400
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; for f in *.err; do echo "== $f"; tail -n 5 "$f"; done; exit 1; }
if ! unshare -rm sh -c 'mkdir -p probe && mount -t tmpfs -o size=64k none probe' 2> unshare.txt; then
  echo "SKIP: cannot mount a small tmpfs in a user namespace here ($(cat unshare.txt))"
  exit 77
fi
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || fail "no free UDP port pair on 127.0.0.1"
bus="udp:127.0.0.1:$port?ports=2"
"$sim" serve --bus "$bus" --physics kinematic --exit-after-idle 30 --status-every 0 2> serve.log &
serve_pid=$!
trap 'kill $serve_pid 2>/dev/null || true' EXIT
run=("$controller" --bus "$bus" --episodes $episodes --quiet --print-checksum)
checksum() { grep -o 'archive checksum 0x[0-9a-f]*' "$1" || true; }

"${run[@]}" --out reference > reference.out 2> reference.err || fail "undisturbed run failed"
want=$(checksum reference.out)
[ -n "$want" ] || fail "no checksum from the undisturbed run"

# 200 kB hold about 3,100 of the 3,500 journaled episodes (64 bytes each).
mkdir m
set +e
unshare -rm sh -c 'mount -t tmpfs -o size=200k none m || exit 99; "$@" --out m/run; rc=$?;
  cp -a m/run full_disk_run; exit $rc' sh "${run[@]}" > full.out 2> full.err
rc=$?
set -e
[ $rc != 99 ] || fail "could not mount the tmpfs"
[ $rc = 1 ] || fail "the run on a full disk exited $rc, not 1"
grep -q "journal.bin: cannot journal episode [0-9]*: No space left on device" full.err ||
  fail "the message does not name the journal and the full disk: $(tail -1 full.err)"
! grep -q "did not come back" full.err || fail "a full disk reported as a bus fault"
grep -q "controlled stop: quick stop to joints 1-7, all stood still" full.err ||
  fail "the full disk did not end in a controlled stop: $(grep 'controlled stop' full.err)"
stopped_at=$(sed -n 's/.*cannot journal episode \([0-9]*\).*/\1/p' full.err)

"${run[@]}" --out full_disk_run --resume > resumed.out 2> resumed.err ||
  fail "the resume on a roomy disk failed"
[ "$(checksum resumed.out)" = "$want" ] ||
  fail "resumed after the full disk: $(checksum resumed.out), undisturbed $want"
echo "journal full at episode $stopped_at: exit 1 naming the full disk; resumed elsewhere: $want as undisturbed"
