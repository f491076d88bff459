# Per round: active latents' KL (agent images) and |corr| with (bx, by, dx, dy), held-out and on own images.
import json, sys, glob, os
F = ("ball_x", "ball_y", "distractor_x", "distractor_y")
def fmt(rep):
    out = []
    for L in rep["latents"]:
        if L["active"]:
            out.append(f"z{L['index']} {L['kl']:.2f} ({' '.join('%.2f' % abs(L['corr'][k]) for k in F)})")
    return "; ".join(out)
for d in sys.argv[1:]:
    for f in sorted(glob.glob(f"{d}/retrain_*.json"), key=lambda p: int(p.split('_')[-1][:-5])):
        j = json.load(open(f))
        h, o = j["factor_report_heldout_evaluation_only"], j["factor_report_own_images_evaluation_only"]
        print(f"{os.path.basename(d)} r{j['round']} ep{j['episode']}: ball held-out {j['ball_latents']} own {j['own_images_ball_latents']} | segment verdict {j['segment_controllable_latents']} | modules {j['modules'][:2]}")
        print(f"   held-out (recon {h['heldout_recon']:.0f}, MIG {h['mig']:.3f}):", fmt(h))
        print(f"   own      (recon {o.get('recon', 0):.0f}, MIG {o['mig']:.3f}):", fmt(o))
