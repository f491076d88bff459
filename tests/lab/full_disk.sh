#!/usr/bin/env bash
# A full disk under `curio-lab run --out`: at every size from a nearly empty file system to one
# just too small for the report, the run ends with a non-zero exit and a message naming the
# full disk, and what it leaves is whole: no truncated PNG (each ends with its IEND chunk), no
# JSON that does not parse, no temporary file. Then the same with the records already there
# (the report rewritten from a finished campaign): gnuplot exits 0 when it cannot write its
# PNG, and that must not pass as success either.
# The small file system is a tmpfs mounted in a private user and mount namespace
# (`unshare -rm`), so no root is needed; where the kernel refuses that namespace the test is
# skipped (exit 77), saying so.
#   tests/lab/full_disk.sh CURIO_LAB WORK_DIR
set -euo pipefail
source "$(dirname "$0")/whole_outputs.sh"
lab=$(realpath "$1") work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
camp=(--algos RPE,MGE-EFR --seeds 0-1 --episodes 500 --threads 2 --quiet)

if ! unshare -rm sh -c 'mkdir -p m && mount -t tmpfs -o size=64k none m' 2> unshare.txt; then
  echo "SKIP: cannot mount a small tmpfs in a user namespace here ($(cat unshare.txt))"
  exit 77
fi

# The whole campaign on a roomy disk: its size is what the sweep below cuts short.
"$lab" run "${camp[@]}" --out full > /dev/null 2> err_full.txt || fail "the reference run failed"
total_k=$(du -sk full | cut -f1)
mkdir finished && cp -a full/manifest.json full/records finished/
records_k=$(du -sk finished | cut -f1)
echo "the campaign writes ${total_k} kB (records and manifest ${records_k} kB)"

# A run that exits 0 must have written everything the reference run wrote (the file system's
# page rounding makes "too small" approximate near the top of the sweep).
check_complete() {
  local dir=$1 what=$2
  diff <(cd full && find . -type f | sort) <(cd "$dir" && find . -type f | sort) > /dev/null ||
    fail "$what: exit 0 but files are missing"
  check_whole "$dir" "$what"
}

# Runs "$@" with --out on a tmpfs of SIZE_K kB; leaves the folder in ./on_disk_<size>,
# the exit code in $rc and stderr in err_<size>.txt. PRESEED: a folder copied in first.
run_on_tmpfs() {
  local size_k=$1 preseed=$2
  shift 2
  rm -rf "m_$size_k" "on_disk_$size_k" && mkdir "m_$size_k"
  set +e
  unshare -rm sh -c '
    size=$1 preseed=$2 mnt=$3; shift 3
    mount -t tmpfs -o size=${size}k none "$mnt" || exit 99
    [ -z "$preseed" ] || cp -a "$preseed" "$mnt/out" || exit 98
    "$@" --out "$mnt/out"; rc=$?
    cp -a "$mnt/out" "on_disk_$size" 2> /dev/null
    exit $rc' sh "$size_k" "$preseed" "m_$size_k" "$@" > /dev/null 2> "err_$size_k.txt"
  rc=$?
  set -e
  [[ $rc != 99 && $rc != 98 ]] || fail "could not mount or fill the tmpfs of ${size_k} kB"
}

# 1. A fresh run on disks from almost nothing to just short of the campaign's size.
sizes=()
for pct in 3 10 25 40 55 70 85 95; do sizes+=($((total_k * pct / 100 + 4))); done
refused=0
for size in "${sizes[@]}"; do
  run_on_tmpfs "$size" "" "$lab" run "${camp[@]}"
  if [[ $rc == 0 ]]; then
    check_complete "on_disk_$size" "${size} kB"
    echo "${size} kB: room enough after all (exit 0, every file whole)"
    continue
  fi
  refused=$((refused + 1))
  grep -qiE 'No space left on device|disk full' "err_$size.txt" ||
    fail "${size} kB: the message does not name the full disk: $(tail -3 "err_$size.txt")"
  [[ -d on_disk_$size ]] && check_whole "on_disk_$size" "${size} kB"
  echo "${size} kB: exit $rc, $(grep -ciE 'No space left on device|disk full' "err_$size.txt") line(s) name the full disk; what is left is whole"
done

[[ $refused -ge 5 ]] || fail "only $refused of ${#sizes[@]} disks were too small: the sweep tests nothing"

# 2. The finished campaign's records on a disk with room for them but not for the report.
for extra in 8 40 120; do
  size=$((records_k + extra))
  [[ $size -lt $total_k ]] || continue
  run_on_tmpfs "$size" "$work/finished" "$lab" run "${camp[@]}"
  if [[ $rc == 0 ]]; then
    check_complete "on_disk_$size" "report rewrite on ${size} kB"
    echo "report rewrite on ${size} kB: room enough after all (exit 0, every file whole)"
    continue
  fi
  grep -qiE 'No space left on device|disk full' "err_$size.txt" ||
    fail "report rewrite on ${size} kB: no message names the full disk: $(tail -3 "err_$size.txt")"
  check_whole "on_disk_$size" "report rewrite on ${size} kB"
  echo "report rewrite on ${size} kB: exit $rc, the full disk named; what is left is whole"
done
echo "full disk: every run refused with a message, nothing truncated left behind"
