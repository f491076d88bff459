#!/usr/bin/env python3
"""Where a run's exploration ratio comes from: docs/spec.md §4.1's 30×30 cells over [-1, 1]² that
hold a final ball position among the first N episodes, split into rings by the cell centre's
Chebyshev distance from the arena's centre (ring k: distance in [k/R, (k+1)/R)). A goal space
whose periphery does not map to the arena's periphery leaves the outer rings empty however
high its goals reach (evaluation only: reads the run's scenes.csv, the true positions).

  python3 host_tools/online/analysis/rings.py runs_online/gs_seed{0,3} [--n 9666] [--rings 6]
"""
import argparse, csv, os

SIDE = 30  # cells per side, as host_tools/experiment/exploration_ratio.hpp


def cell_of(v):
    """host_tools/experiment/exploration_ratio.hpp's cell_of: -1 outside [-1, 1]."""
    if not -1.0 <= v <= 1.0:
        return -1
    return min(int((v + 1.0) * 0.5 * SIDE), SIDE - 1)


def rings(scenes_csv, n, k):
    visited = set()
    with open(scenes_csv) as f:
        for i, r in enumerate(csv.DictReader(f)):
            if i >= n:
                break
            cx, cy = cell_of(float(r["ball_x"])), cell_of(float(r["ball_y"]))
            if cx >= 0 and cy >= 0:
                visited.add((cx, cy))
    hit, total = [0] * k, [0] * k
    for cx in range(SIDE):
        for cy in range(SIDE):
            d = max(abs((cx + 0.5) / (SIDE / 2) - 1), abs((cy + 0.5) / (SIDE / 2) - 1))
            b = min(int(d * k), k - 1)
            total[b] += 1
            hit[b] += (cx, cy) in visited
    return len(visited) / SIDE ** 2, [h / t for h, t in zip(hit, total)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="run directories holding scenes.csv (curio-online)")
    ap.add_argument("--n", type=int, default=9666, help="episodes counted (docs/spec.md §4.1's N)")
    ap.add_argument("--rings", type=int, default=6, help="rings from the centre out")
    a = ap.parse_args()
    print("| run | ratio at %d | share of each ring's cells reached, centre → edge |" % a.n)
    print("|---|---|---|")
    for d in a.runs:
        path = os.path.join(d, "scenes.csv")
        if not os.path.exists(path):
            print("| %s | no scenes.csv | |" % d)
            continue
        ratio, shares = rings(path, a.n, a.rings)
        print("| %s | %.3f | %s |" % (d, ratio, " / ".join("%.2f" % s for s in shares)))


if __name__ == "__main__":
    main()
