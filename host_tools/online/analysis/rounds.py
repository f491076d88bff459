#!/usr/bin/env python3
"""What each retrain of a curio-online run learned, round by round: the ball and distractor
latents by the factor report's linear rule (held-out uniform scenes and the agent's own images),
the segment verdict, the first goal modules, and every active latent's KL with its |corr| with
(ball x, ball y, distractor x, distractor y). Reads RUN/retrain_<r>.json (evaluation only).

  python3 host_tools/online/analysis/rounds.py RUN [RUN ...]
"""
import json, sys, glob, os
F = ("ball_x", "ball_y", "distractor_x", "distractor_y")
if not sys.argv[1:] or any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    sys.exit(0 if sys.argv[1:] else 2)


def fmt(rep):
    out = []
    for L in rep["latents"]:
        if L["active"]:
            out.append(f"z{L['index']} {L['kl']:.2f} ({' '.join('%.2f' % abs(L['corr'][k]) for k in F)})")
    return "; ".join(out)
for d in sys.argv[1:]:
    for f in sorted(glob.glob(f"{d}/retrain_*.json"), key=lambda p: int(p.split('_')[-1][:-5])):
        j = json.load(open(f))
        h, o = j["factor_report_heldout_evaluation_only"], j.get("factor_report_own_images_evaluation_only")
        print(f"{os.path.basename(d)} r{j['round']} ep{j['episode']}: ball held-out {j['ball_latents']} own {j.get('own_images_ball_latents', '-')} | segment verdict {j.get('segment_controllable_latents', '-')} | modules {j['modules'][:2]}")
        print(f"   held-out (recon {h['heldout_recon']:.0f}, MIG {h['mig']:.3f}):", fmt(h))
        if o:  # older runs report held-out scenes only
            print(f"   own      (recon {o.get('recon', 0):.0f}, MIG {o['mig']:.3f}):", fmt(o))
