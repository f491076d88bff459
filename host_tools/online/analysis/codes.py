#!/usr/bin/env python3
"""What the latents of an online run's model hold, on the agent's own images (evaluation only).

  curio-online --out RUN --export-codes R          # writes RUN/codes_round_R.csv
  python3 host_tools/online/analysis/codes.py RUN/codes_round_R.csv [--latents 0 1 2 3] [--pair 2 3] [--plot code.png]

Per latent: its spread over all images and over the images where the ball never left its rest
spot (there the ball is fixed, so any spread follows the distractor), and on the images where
the ball moved, how well the ball's or the distractor's position predicts it (5-NN regression
R² on a held-out 1,500). Then how well groups of latents predict the ball's (x, y) on the same
images: a group that holds the ball as a 2-D chart has R² near 1 for both, whether or not its
code is linear (the |corr| ≥ .5 rule of the factor report sees only linear codes). --plot draws
the --pair's code coloured by ball x and by ball y (gray: ball at rest). A last line says
whether the pair's code periphery is the arena's periphery (goals beyond the prior, e.g.
--goal-scale, land at the code's periphery). Pure Python: a few minutes for 10,400 images.
"""
import argparse, csv, heapq, os, random, subprocess, tempfile


def moved(r):
    return abs(float(r["ball_x"]) - 0.6) > 1e-3 or abs(float(r["ball_y"]) - 0.6) > 1e-3


def sd(v):
    m = sum(v) / len(v)
    return (sum((x - m) ** 2 for x in v) / len(v)) ** 0.5


def knn_r2(rows, xs, ys, k=5, ntest=1500, seed=0):
    ntest = min(ntest, len(rows) // 3)
    data = rows[:]
    random.Random(seed).shuffle(data)
    test, ref = data[:ntest], data[ntest:]
    X = [[float(r[c]) for c in xs] for r in ref]
    Y = [[float(r[c]) for c in ys] for r in ref]
    Yt = [[float(r[c]) for c in ys] for r in test]
    mean = [sum(y[j] for y in Yt) / len(Yt) for j in range(len(ys))]
    se, var = [0.0] * len(ys), [0.0] * len(ys)
    for r, yt in zip(test, Yt):
        x = [float(r[c]) for c in xs]
        near = heapq.nsmallest(k, range(len(X)), key=lambda i: sum((a - b) ** 2 for a, b in zip(X[i], x)))
        for j in range(len(ys)):
            p = sum(Y[i][j] for i in near) / k
            se[j] += (yt[j] - p) ** 2
            var[j] += (yt[j] - mean[j]) ** 2
    return [1 - s / v for s, v in zip(se, var)]


def rest_goal_share(rows, pair, goals=2000, seed=0):
    """The share of goals drawn from N(0, 1) in the pair's plane (docs/spec.md §2.3) whose nearest
    image (the 1-NN inverse model's choice) has the ball at rest: goals the ball module can
    only meet by leaving the ball where it is."""
    pts = [(float(r["mu%d" % pair[0]]), float(r["mu%d" % pair[1]]), moved(r)) for r in rows]
    rng = random.Random(seed)
    hits = 0
    for _ in range(goals):
        g = (rng.gauss(0, 1), rng.gauss(0, 1))
        hits += not min(pts, key=lambda p: (p[0] - g[0]) ** 2 + (p[1] - g[1]) ** 2)[2]
    return hits / goals


def periphery(mv, pair):
    """Does the pair's code periphery map to the arena's periphery? Over the images where the ball
    moved: the correlation of the code's radius with the ball's Chebyshev distance from the
    arena's centre, that distance's mean, and its mean over the 10 % of images with the largest
    code radius (where goals far out in the code find their nearest outcomes)."""
    rc = [(float(r["mu%d" % pair[0]]) ** 2 + float(r["mu%d" % pair[1]]) ** 2) ** 0.5 for r in mv]
    ra = [max(abs(float(r["ball_x"])), abs(float(r["ball_y"]))) for r in mv]
    n, mc, ma = len(mv), sum(rc) / len(mv), sum(ra) / len(mv)
    corr = sum((c - mc) * (d - ma) for c, d in zip(rc, ra)) / n / (sd(rc) * sd(ra))
    top = sorted(zip(rc, ra), reverse=True)[: max(1, n // 10)]
    return corr, ma, sum(d for _, d in top) / len(top)


def plot(rows, pair, png, title):
    a, b = ("mu%d" % pair[0]), ("mu%d" % pair[1])
    with tempfile.TemporaryDirectory() as tmp:
        mv, rest = os.path.join(tmp, "moved.dat"), os.path.join(tmp, "rest.dat")
        with open(mv, "w") as f:
            f.writelines("%s %s %s %s\n" % (r[a], r[b], r["ball_x"], r["ball_y"]) for r in rows if moved(r))
        with open(rest, "w") as f:
            f.writelines("%s %s\n" % (r[a], r[b]) for r in rows if not moved(r))
        pts = "w p pt 7 ps 0.3"
        script = (
            "set terminal pngcairo size 1200,560; set output '%s';"
            "set multiplot layout 1,2 title \"%s\" noenhanced;"
            "set xlabel 'mu z%d'; set ylabel 'mu z%d'; set xrange [-3:3]; set yrange [-3:3];"
            "set palette rgbformulae 33,13,10;"
            "set title 'colour: ball x'; plot '%s' u 1:2 %s lc rgb '#bbbbbb' title 'ball at rest', '%s' u 1:2:3 %s palette notitle;"
            "set title 'colour: ball y'; plot '%s' u 1:2 %s lc rgb '#bbbbbb' title 'ball at rest', '%s' u 1:2:4 %s palette notitle\n"
            % (png, title.replace('"', "'"), pair[0], pair[1], rest, pts, mv, pts, rest, pts, mv, pts))
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print("wrote " + png)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("codes", help="codes_round_R.csv from curio-online --export-codes R")
    ap.add_argument("--latents", type=int, nargs="+", default=[0, 1, 2, 3], help="latents to report")
    ap.add_argument("--pair", type=int, nargs=2, help="the ball group to test and plot (default: the last two --latents)")
    ap.add_argument("--plot", help="write the --pair's code to this PNG")
    ap.add_argument("--title", default="", help="figure title")
    ap.add_argument("--upto", type=int, help="only the episodes before this one (the archive a round's model was trained on)")
    a = ap.parse_args()
    rows = list(csv.DictReader(open(a.codes)))
    if a.upto:
        rows = [r for r in rows if int(r["episode"]) < a.upto]
    mv = [r for r in rows if moved(r)]
    rest = [r for r in rows if not moved(r)]
    if len(mv) < 200 or len(rest) < 200:
        raise SystemExit("codes.py: needs ≥ 200 images with the ball moved and ≥ 200 at rest (%d moved, %d at rest)"
                         % (len(mv), len(rest)))
    pair = a.pair or a.latents[-2:]
    print("%s: %d images, the ball moved in %d" % (a.codes, len(rows), len(mv)))
    ball, dis = ["ball_x", "ball_y"], ["distractor_x", "distractor_y"]
    print("| latent | sd, all images | sd, ball at rest | R² from ball position (moved) | from distractor position | from both |")
    print("|---|---|---|---|---|---|")
    for l in a.latents:
        m = "mu%d" % l
        print("| z%d | %.2f | %.2f | %.2f | %.2f | %.2f |" % (
            l, sd([float(r[m]) for r in rows]), sd([float(r[m]) for r in rest]), knn_r2(mv, ball, [m])[0],
            knn_r2(mv, dis, [m])[0], knn_r2(mv, ball + dis, [m])[0]))
    others = [l for l in a.latents if l not in pair]
    print("\n| latents | R² of ball x from them (moved) | of ball y |")
    print("|---|---|---|")
    for g in ([pair[0]], [pair[1]], list(pair), others, a.latents):
        if not g:
            continue
        r = knn_r2(mv, ["mu%d" % l for l in g], ball)
        print("| %s | %.2f | %.2f |" % (",".join("z%d" % l for l in g), r[0], r[1]))
    r = [knn_r2(rest, dis, ["mu%d" % l])[0] for l in pair]
    print("\nball at rest (%d images): R² of z%d, z%d from the distractor's position %.2f, %.2f"
          % (len(rest), pair[0], pair[1], r[0], r[1]))
    print("N(0, 1) goals in (z%d, z%d) whose nearest image has the ball at rest: %.1f %%"
          % (pair[0], pair[1], 100 * rest_goal_share(rows, pair)))
    c, whole, outer = periphery(mv, pair)
    print("code radius of (z%d, z%d) against the ball's distance from the arena's centre (moved): corr %.2f; "
          "distance %.2f on average, %.2f at the code's outer 10 %%" % (pair[0], pair[1], c, whole, outer))
    if a.plot:
        plot(rows, pair, a.plot, a.title or "the code of z%d, z%d on the agent's own images" % tuple(pair))


if __name__ == "__main__":
    main()
