#!/usr/bin/env bash
# Smoke test of curio-online's short form. A toy run (the 400 bootstrap episodes + 300, retrains
# at 400, 500 and 600 with tiny trainings, otherwise the defaults) must
#   1. list at most 15 options in --help, and refuse usage errors (unknown option, bad choice,
#      malformed number, an invalid value, run options beside --resume, an --out that holds a
#      run) with exit 2, one line naming the option, and nothing written;
#   2. finish and write its reports (summary.json with a verdict, curves.csv, retrain_<r>.json,
#      the three figures), with options.json holding the default configuration (progressive
#      latents at 3 nats, novelty steps at 0.3, anchoring at 10) and novelty steps run;
#   3. --export-codes writes every scene's μ under a round's model and refuses a missing round;
#      an options.json with removed options at their old defaults is read, one that sets one
#      to another value is refused (exit 2).
# A smaller run (its options.json written here and started by --resume with no checkpoint yet:
# 100 bootstrap episodes, 50 held-out images, the capacity schedule shortened) must
#   4. open 2, then 4 latents, anchor the first two in the training that opens the next (and in
#      no other), hold the rest exactly at the prior, and make the opened groups the first goal
#      modules; --quiet prints the final line only;
#   5. give the same results when stopped after its first retrain and resumed (--resume).
# Usage: online_smoke.sh CURIO_ONLINE WORK_DIR
set -euo pipefail
bin=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
toy=(--seed 3 --episodes 300 --retrain-every 100 --first-iterations 20 --retrain-iterations 10
     --no-baselines --threads 1)
fail() { echo "online_smoke: FAIL: $*" >&2; exit 1; }

# 1. --help and usage errors
"$bin" --help > "$work/help.txt" || fail "--help exited $?"
n_options=$(grep -cE '^ +--' "$work/help.txt" | tr -d ' ')
[ "$n_options" -le 16 ] || fail "--help lists $n_options options (at most 15 beyond --help)"
usage_error() {  # usage_error WHAT_THE_LINE_NAMES ARGS...: exit 2, one stderr line naming it, no --out
  local name=$1; shift
  set +e; "$bin" "$@" > "$work/usage.out" 2> "$work/usage.err"; local rc=$?; set -e
  [ "$rc" = 2 ] || fail "'$*' exited $rc, not 2"
  [ "$(wc -l < "$work/usage.err")" = 1 ] || fail "'$*' wrote not one stderr line: $(cat "$work/usage.err")"
  grep -q -- "$name" "$work/usage.err" || fail "'$*': the error does not name $name: $(cat "$work/usage.err")"
  [ ! -e "$work/never" ] || fail "'$*' wrote $work/never"
}
usage_error --bogus --out "$work/never" --bogus
usage_error --physics --out "$work/never" --physics odd
usage_error --seed --out "$work/never" --seed x
usage_error --seed --out "$work/never" --seed -1
usage_error --anchor-weight --out "$work/never" --anchor-weight inf
usage_error --episodes --out "$work/never" --episodes 7
usage_error --novelty-fraction --out "$work/never" --novelty-fraction 1.5
usage_error --seed --out "$work/never" --resume --seed 4
usage_error options.json --out "$work/never" --resume

# 2. a run with the defaults
"$bin" "${toy[@]}" --out "$work/a" > "$work/a.log" 2>&1 || { cat "$work/a.log"; fail "run a exited $?"; }
for f in options.json summary.json curves.csv scenes.csv retrain_0.json retrain_1.json retrain_2.json \
         ratio.png interest.png latents.png; do
  [ -s "$work/a/$f" ] || fail "run a wrote no $f"
done
usage_error "options.json exists" "${toy[@]}" --out "$work/a"
python3 - "$work/a" <<'PY' || fail "run a: not the default configuration, or no novelty steps"
import json, sys
d = sys.argv[1]
o = json.load(open(f"{d}/options.json"))
assert (o["nats_per_latent"], o["novelty_fraction"], o["anchor_weight"]) == (3.0, 0.3, 10.0), o
for gone in ("unmix", "surprise_fraction", "skew_alpha", "kl_penalty", "decoder", "goal_modules", "goal_scale"):
    assert gone not in o, gone
s = json.load(open(f"{d}/summary.json"))
for k in ("verdict_latents", "final_verdicts", "archive_checksum", "cpu_seconds_this_process",
          "verdict_names_own_image_ball_latents"):
    assert k in s, k
# 60 steps of 5 episodes at a 0.3 chance each: 18 expected
assert 3 <= s["novelty_steps"] <= 40, ("novelty steps", s["novelty_steps"])
for k in ("ball_moved_share_novelty_episodes", "ball_moved_share_goal_episodes", "ball_moved_share_all"):
    assert 0.0 <= s[k] <= 1.0, (k, s[k])
for r in range(3):
    assert json.load(open(f"{d}/retrain_{r}.json"))["training"]["open_latents"] == 2, r
PY

# 3. --export-codes, and options.json of earlier versions
"$bin" --out "$work/a" --export-codes 2 > "$work/codes.log" 2>&1 || { cat "$work/codes.log"; fail "--export-codes exited"; }
[ "$(wc -l < "$work/a/codes_round_2.csv")" = 701 ] || fail "codes_round_2.csv has not 700 scenes + header"
[ "$(head -n 1 "$work/a/codes_round_2.csv" | tr ',' '\n' | wc -l)" = 15 ] || fail "codes_round_2.csv has not 15 columns"
"$bin" --out "$work/a" --export-codes 7 > "$work/codes7.log" 2>&1 && fail "--export-codes of a round the run lacks succeeded"
grep -q "round_7.pt not found" "$work/codes7.log" || fail "--export-codes 7 did not say which model is missing"
cp -r "$work/a" "$work/old"
python3 - "$work/old/options.json" 0.0 <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))
o.update({"unmix": False, "surprise_fraction": float(sys.argv[2]), "surprise_top": 0.05})
json.dump(o, open(sys.argv[1], "w"))
PY
"$bin" --out "$work/old" --export-codes 1 > "$work/old.log" 2>&1 \
  || { cat "$work/old.log"; fail "--export-codes refused an options.json with removed options at their defaults"; }
python3 - "$work/old/options.json" 0.5 <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))
o["surprise_fraction"] = float(sys.argv[2])
json.dump(o, open(sys.argv[1], "w"))
PY
usage_error surprise_fraction --out "$work/old" --resume

# 4. and 5. a smaller run: latents open and anchor; stop + resume
mkdir -p "$work/b" "$work/c"
python3 - "$work/a/options.json" "$work/b/options.json" "$work/c/options.json" <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))
# C reaches 6 (one group exactly), 9 and 12 nats at the ends of the three trainings
o.update({"bootstrap": 100, "eval_images": 50, "capacity_iters": 40})
for f in sys.argv[2:]:
    json.dump(o, open(f, "w"))
PY
"$bin" --out "$work/b" --resume --quiet > "$work/b.log" 2>&1 || { cat "$work/b.log"; fail "run b exited"; }
[ "$(wc -l < "$work/b.log")" = 1 ] && grep -q '^done: ' "$work/b.log" || fail "--quiet printed more than the final line"
python3 - "$work/b" <<'PY' || fail "run b: latents did not open or anchor as the capacity schedule asks"
import json, sys
d = sys.argv[1]
for r, want in ((0, 2), (1, 4), (2, 4)):
    j = json.load(open(f"{d}/retrain_{r}.json"))
    assert j["episode"] == 100 * (r + 1), (r, j["episode"])
    assert j["training"]["open_latents"] == want, (r, j["training"]["open_latents"])
    assert all(k == 0.0 for k in j["kl_per_latent_on_agent_images"][want:]), (r, "held latent with KL")
    assert j["training"]["anchored"] == (2 if r == 1 else 0), (r, "anchoring: only the training that opens z2, z3")
    m = j["modules"]
    assert len(m) == 5 and all(len(g) == 2 for g in m), (r, m)
    assert sorted(sum(m[:want // 2], [])) == list(range(want)), (r, "opened groups first", m)
PY
"$bin" --out "$work/c" --resume --stop-after-retrain 1 > "$work/c1.log" 2>&1 \
  || { cat "$work/c1.log"; fail "run c (stop after round 1) exited"; }
[ -f "$work/c/summary.json" ] && fail "run c wrote a summary although it stopped after round 1"
"$bin" --out "$work/c" --resume --threads 1 > "$work/c2.log" 2>&1 \
  || { cat "$work/c2.log"; fail "run c --resume exited"; }
checksum() { sed -n 's/.*"archive_checksum": *"\([0-9a-f]*\)".*/\1/p' "$1/summary.json"; }
[ "$(checksum "$work/b")" = "$(checksum "$work/c")" ] \
  || fail "stop + resume changed the archive checksum ($(checksum "$work/c"), uninterrupted $(checksum "$work/b"))"
for f in scenes.csv curves.csv; do
  cmp -s "$work/b/$f" "$work/c/$f" || fail "stop + resume changed $f"
done

echo "online_smoke: ok (checksums $(checksum "$work/a") $(checksum "$work/b"); stop + resume identical, usage errors exit 2)"
tail -n 3 "$work/a.log"
