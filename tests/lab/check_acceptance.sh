#!/usr/bin/env bash
# Issue 2's acceptance campaign: RPE, RGE-EFR, MGE-EFR × seeds 0–14, σ = 0.05, D = 1,
# bootstrap 100; the mean ratio at 9,666 episodes must lie within TOL of SPEC §4.
# usage: check_acceptance.sh CURIO_LAB PHYSICS TOL OUT_DIR
set -euo pipefail
lab=$1 physics=$2 tol=$3 out=$4
"$lab" run --algos RPE,RGE-EFR,MGE-EFR --seeds 0-14 --noise 0.05 --physics "$physics" \
  --episodes 10000 --bootstrap 100 --competence-clip 1 --out "$out" --json > "$out.json"
python3 - "$out.json" "$tol" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1])); tol = float(sys.argv[2])
ok = True
for row in summary["results"]:
    cp = next(c for c in row["checkpoints"] if c["episodes"] == 9666)
    ref = row["reference_9666"]["mean"]
    good = abs(cp["mean"] - ref) <= tol
    ok &= good
    print(f'{row["algorithm"]:8s} ratio@9666 {cp["mean"]:.3f} ± {cp["std"]:.3f}  reference {ref:.3f}  '
          f'diff {cp["mean"] - ref:+.3f}  {"ok" if good else "OUT OF TOLERANCE"} (±{tol})')
print("wall time %.1f s" % summary["wall_seconds"])
sys.exit(0 if ok else 1)
PY
