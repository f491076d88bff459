#!/usr/bin/env bash
# The learned-goal-space acceptance campaign: RGE/MGE on the shipped VAE and β-VAE goal spaces ×
# seeds 0–14, σ = 0.05 (bootstrap 400, D 2: curio-lab's defaults for learned goal spaces). Checks,
# at 9,666 episodes: MGE-βVAE ≥ 0.64; RGE-βVAE, RGE-VAE, MGE-VAE within ±0.05 of SPEC §4; MGE-βVAE >
# RGE-βVAE > MGE-VAE; the MGE-βVAE verdict names exactly the ball's latents in ≥ 13 seeds.
# usage: check_learned_acceptance.sh CURIO_LAB PHYSICS OUT_DIR
set -euo pipefail
lab=$1 physics=$2 out=$3
"$lab" run --replace --algos RGE-VAE,MGE-VAE,RGE-βVAE,MGE-βVAE --seeds 0-14 --noise 0.05 \
  --physics "$physics" --episodes 10000 --out "$out" --json > "$out.json"
python3 - "$out.json" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))
rows = {r["algorithm"]: r for r in summary["results"]}
ratio = {a: next(c for c in r["checkpoints"] if c["episodes"] == 9666) for a, r in rows.items()}
ok = True
def check(good, text):
    global ok
    ok &= good
    print(f'{"ok  " if good else "FAIL"} {text}')
for a, cp in ratio.items():
    ref = rows[a]["reference_9666"]["mean"]
    line = f'{a:9s} ratio@9666 {cp["mean"]:.3f} ± {cp["std"]:.3f}  reference {ref:.3f}  diff {cp["mean"] - ref:+.3f}'
    if a == "MGE-βVAE":
        check(cp["mean"] >= 0.64, line + "  (want ≥ 0.64)")
    else:
        check(abs(cp["mean"] - ref) <= 0.05, line + "  (want ±0.05)")
m = {a: ratio[a]["mean"] for a in ratio}
check(m["MGE-βVAE"] > m["RGE-βVAE"] > m["MGE-VAE"], "ranking MGE-βVAE > RGE-βVAE > MGE-VAE")
for a in ("MGE-βVAE", "MGE-VAE"):
    c = rows[a]["controllability"]
    counts = ", ".join(f'{{{v}}} {n}' for v, n in c["counts"].items())
    text = f'{a} verdicts: {counts}; ball latents {{{c.get("expected", "?")}}} in {c.get("seeds_matching_expected", 0)}/15'
    check(a != "MGE-βVAE" or c.get("seeds_matching_expected", 0) >= 13,
          text + ("  (want ≥ 13)" if a == "MGE-βVAE" else "  (reported)"))
print("wall time %.1f s" % summary["wall_seconds"])
sys.exit(0 if ok else 1)
PY
