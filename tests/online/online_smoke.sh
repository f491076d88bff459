#!/usr/bin/env bash
# Smoke test of curio-online's short form (issue 17): a toy run (100 bootstrap + 300 episodes,
# retrains at 200 and 300, tiny trainings) must
#   1. finish and write its reports (summary.json with a verdict, curves.csv, retrain_<r>.json,
#      the three figures);
#   2. give bit-identical results when repeated (same seed, same thread count);
#   3. give the same results when stopped after its first retrain and resumed (--resume);
#   4. the same two with progressive latents, surprise sampling, novelty steps, anchoring, one
#      goal module per open latent, the additive decoder, the hinge capacity term with a price
#      per nat, density-skewed batches (the skew from the second training on) and goals at 2.5 × the
#      prior on: the first training uses 2 latents and the later ones
#      4, the training that opens the second group anchors the first (and no other does), the
#      held latents' KL is exactly 0, the goal modules are the open latents one by one, novelty
#      steps run and are reported, and stop + resume gives the uninterrupted run's results;
#   5. with progressive latents and the default goal modules, the modules are the opened groups
#      first, then the held ones;
#   6. --export-codes writes every scene's μ under a round's model, and refuses a missing round.
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
grep -q '"final_verdicts"' "$work/a/summary.json" || fail "summary.json has no per-module final verdicts"
grep -q '"archive_checksum"' "$work/a/summary.json" || fail "summary.json has no archive checksum"
grep -q '"cpu_seconds_this_process"' "$work/a/summary.json" || fail "summary.json has no CPU time"
grep -q '"verdict_names_own_image_ball_latents"' "$work/a/summary.json" || fail "summary.json has no verdict against the own-image ball latents"

# --export-codes: every scene's μ under a round's model, beside its true positions
"$bin" --out "$work/a" --export-codes 2 > "$work/codes.log" 2>&1 || { cat "$work/codes.log"; fail "--export-codes exited"; }
[ "$(wc -l < "$work/a/codes_round_2.csv")" = 401 ] || fail "codes_round_2.csv has not 400 scenes + header"
[ "$(head -n 1 "$work/a/codes_round_2.csv" | tr ',' '\n' | wc -l)" = 15 ] || fail "codes_round_2.csv has not 15 columns"
"$bin" --out "$work/a" --export-codes 7 > "$work/codes7.log" 2>&1 && fail "--export-codes of a round the run lacks succeeded"
grep -q "round_7.pt not found" "$work/codes7.log" || fail "--export-codes 7 did not say which model is missing"

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
grow=(--nats-per-latent 3 --surprise-fraction 0.5 --surprise-top 0.1 --novelty-fraction 0.5 --novelty-top 0.1
      --anchor-weight 5 --goal-modules open-singles --decoder additive --kl-penalty hinge --kl-weight 1
      --skew-alpha -1 --skew-neighbours 3 --goal-scale 2.5)
"$bin" "${toy[@]}" "${grow[@]}" --out "$work/d" > "$work/d.log" 2>&1 || { cat "$work/d.log"; fail "run d exited"; }
"$bin" "${toy[@]}" "${grow[@]}" --out "$work/e" --stop-after-retrain 1 > "$work/e1.log" 2>&1 \
  || { cat "$work/e1.log"; fail "run e (stop after round 1) exited"; }
"$bin" --out "$work/e" --resume --threads 1 > "$work/e2.log" 2>&1 || { cat "$work/e2.log"; fail "run e --resume exited"; }
python3 - "$work/d" <<'PY' || fail "run d: progressive latents, surprise sampling or novelty steps not as asked"
import json, sys
d = sys.argv[1]
for r, want in ((0, 2), (1, 4), (2, 4)):
    j = json.load(open(f"{d}/retrain_{r}.json"))
    assert j["training"]["open_latents"] == want, (r, j["training"]["open_latents"])
    assert all(k == 0.0 for k in j["kl_per_latent_on_agent_images"][want:]), (r, "held latent with KL")
    assert (j["training"]["surprising"] > 0) == (r > 0), (r, "surprise sampling")
    assert (0 < j["training"]["skew_ess"] <= 1) == (r > 0), (r, "density skew")
    assert j["training"]["anchored"] == (2 if r == 1 else 0), (r, "anchoring: only the training that opens z2, z3")
    assert sorted(j["modules"]) == [[l] for l in range(want)], (r, "modules are not the open latents one by one")
o = json.load(open(f"{d}/options.json"))
assert (o["decoder"], o["kl_penalty"], o["kl_weight"], o["goal_scale"]) == ("additive", "hinge", 1.0, 2.5), o
s = json.load(open(f"{d}/summary.json"))
# 60 steps of 5 episodes at a 0.5 chance each: 30 expected, so 10..50 (fails if it never fires)
assert 10 <= s["novelty_steps"] <= 50, ("novelty steps", s["novelty_steps"])
for k in ("ball_moved_share_novelty_episodes", "ball_moved_share_goal_episodes", "ball_moved_share_all"):
    assert 0.0 <= s[k] <= 1.0, (k, s[k])
PY
grep -q "novelty steps" "$work/a.log" && fail "novelty steps reported although --novelty-fraction is 0"
grep -q "novelty steps 0 " "$work/d.log" || fail "run d: no progress line before the first training shows 0 novelty steps"

[ "$(checksum "$work/d")" = "$(checksum "$work/e")" ] || fail "progressive run: stop + resume changed the archive checksum"
cmp -s "$work/d/curves.csv" "$work/e/curves.csv" || fail "progressive run: stop + resume changed curves.csv"
[ "$(checksum "$work/d")" != "$(checksum "$work/a")" ] || fail "progressive options changed nothing"

"$bin" "${toy[@]}" --nats-per-latent 3 --out "$work/f" > "$work/f.log" 2>&1 || { cat "$work/f.log"; fail "run f exited"; }
python3 - "$work/f" <<'PY' || fail "run f: with progressive latents the default goal modules are not the opened groups first"
import json, sys
for r, want in ((0, 2), (2, 4)):
    m = json.load(open(f"{sys.argv[1]}/retrain_{r}.json"))["modules"]
    assert len(m) == 5 and all(len(g) == 2 for g in m), (r, m)
    assert sorted(sum(m[:want // 2], [])) == list(range(want)), (r, m)
PY

echo "online_smoke: ok (checksum $(checksum "$work/a"); repeat and stop+resume identical, also progressive)"
tail -n 3 "$work/a.log"
