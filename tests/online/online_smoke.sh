#!/usr/bin/env bash
# Smoke test of curio-online's short form (issue 17): a toy run (100 bootstrap + 300 episodes,
# retrains at 200 and 300, tiny trainings) must
#   1. finish and write its reports (summary.json with a verdict, curves.csv, retrain_<r>.json,
#      the three figures);
#   2. give bit-identical results when repeated (same seed, same thread count);
#   3. give the same results when stopped after its first retrain and resumed (--resume).
# Usage: online_smoke.sh CURIO_ONLINE WORK_DIR
set -euo pipefail
bin=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
toy=(--seed 3 --bootstrap 100 --episodes 300 --retrain-every 100 --last-retrain 300
     --first-iterations 40 --retrain-iterations 20 --batch 16 --capacity-iters 100
     --eval-images 50 --interest-every 20 --progress-every 100 --no-baselines --threads 1)
fail() { echo "online_smoke: FAIL: $*" >&2; exit 1; }

"$bin" "${toy[@]}" --out "$work/a" > "$work/a.log" 2>&1 || { cat "$work/a.log"; fail "run a exited $?"; }
for f in summary.json curves.csv scenes.csv retrain_0.json retrain_1.json retrain_2.json \
         ratio.png interest.png latents.png; do
  [ -s "$work/a/$f" ] || fail "run a wrote no $f"
done
grep -q '"verdict_latents"' "$work/a/summary.json" || fail "summary.json has no verdict"
grep -q '"archive_checksum"' "$work/a/summary.json" || fail "summary.json has no archive checksum"

"$bin" "${toy[@]}" --out "$work/b" > "$work/b.log" 2>&1 || { cat "$work/b.log"; fail "run b exited"; }
"$bin" "${toy[@]}" --out "$work/c" --stop-after-retrain 1 > "$work/c1.log" 2>&1 \
  || { cat "$work/c1.log"; fail "run c (stop after round 1) exited"; }
[ -f "$work/c/summary.json" ] && fail "run c wrote a summary although it stopped after round 1"
"$bin" --out "$work/c" --resume --threads 1 > "$work/c2.log" 2>&1 \
  || { cat "$work/c2.log"; fail "run c --resume exited"; }

checksum() { sed -n 's/.*"archive_checksum": *"\([0-9a-f]*\)".*/\1/p' "$1/summary.json"; }
for run in b c; do
  [ "$(checksum "$work/a")" = "$(checksum "$work/$run")" ] \
    || fail "archive checksum of run $run ($(checksum "$work/$run")) != run a's ($(checksum "$work/a"))"
  for f in scenes.csv curves.csv; do
    cmp -s "$work/a/$f" "$work/$run/$f" || fail "$f of run $run differs from run a's"
  done
done
echo "online_smoke: ok (checksum $(checksum "$work/a"); repeat and stop+resume identical)"
tail -n 3 "$work/a.log"
