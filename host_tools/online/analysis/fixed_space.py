#!/usr/bin/env python3
"""Explore in one round's learned goal space held fixed: does that latent space, left to stay put,
let the agent make learning progress and spread the ball?

  python3 host_tools/online/analysis/fixed_space.py RUN R OUT [key=value ...]
  curio-online --out OUT --resume --threads 1        # ≈ 20 s of exploration, no training

OUT becomes a run folder whose round 0 is RUN's round-R model (weights copied as
models/round_0.pt, its training record kept) with retrain_every 0 (no retrain) and no
baselines; key=value pairs (JSON values) override options, e.g. novelty_fraction=0. The resume
replays the 400 bootstrap episodes (random θ: the same scenes for any model, which the recorded
scene hash checks), loads the model where round 0 would train, and explores the remaining
10,000 episodes in its goal space. summary.json then has the ratio and, over episodes
5,400–10,400, each module's progress t and the verdict (campaign.py OUT prints them). Compare
with the passive MGE-βVAE ratio of the same seed (RUN's summary.json) and the t of its ball
module (curio-lab run --algos MGE-βVAE).
"""
import json, os, shutil, sys

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    sys.exit(0)
if len(sys.argv) < 4:
    print(__doc__, file=sys.stderr)
    sys.exit(2)
src, rnd, dst = sys.argv[1], int(sys.argv[2]), sys.argv[3]
if os.path.exists(dst):
    sys.exit("fixed_space.py: %s exists; choose a new OUT" % dst)
state = json.load(open(os.path.join(src, "state.json")))
if rnd >= len(state["rounds"]):
    sys.exit("fixed_space.py: %s has %d rounds, no round %d" % (src, len(state["rounds"]), rnd))
os.makedirs(os.path.join(dst, "models"))
shutil.copy(os.path.join(src, "models", "round_%d.pt" % rnd), os.path.join(dst, "models", "round_0.pt"))
fixed = {"rounds": [dict(state["rounds"][0], training=state["rounds"][rnd]["training"])]}
json.dump(fixed, open(os.path.join(dst, "state.json"), "w"), indent=2)
o = json.load(open(os.path.join(src, "options.json")))
o.update({"retrain_every": 0, "baselines": False})
for kv in sys.argv[4:]:
    k, v = kv.split("=", 1)
    o[k] = json.loads(v)
json.dump(o, open(os.path.join(dst, "options.json"), "w"), indent=2)
print("%s: round %d of %s as a fixed goal space; now: curio-online --out %s --resume --threads 1" % (dst, rnd, src, dst))
