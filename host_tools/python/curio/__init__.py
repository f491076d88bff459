"""Curio from Python: curiosity-driven exploration (RPE, RGE, MGE) on any world.

The C++ core of Curio (the firmware Explorer, the Arm-2-Balls worlds, the int8 encoder,
curio-lab's runs) behind a thin Python face; docs/python.md has a worked example.

    import curio
    ex = curio.Explorer("MGE-EFR", seed=0, episodes=1000)
    world = curio.World("kinematic", seed=0)
    ex.run(world)                       # in C++: curio-lab's run, bit for bit
    ex.outcomes                         # (1100, 4) float32 view of the archive
    ex.checksum()                       # FNV-1a of the archive, as curio-lab prints it

Your own environment: declare modules over its outcome vector and drive ask/tell,

    ex = curio.Explorer("MGE", modules=[[0, 1], [2, 3]], episodes=1000)
    while not ex.done:
        theta = ex.propose()            # 49 values in [-1, 1]
        ex.observe(my_env(theta))       # any outcome vector (here 4 values)

Contents: Explorer, World, Encoder, render, exploration_ratio, checkpoints,
controllability, campaign, read_campaign, Campaign.
"""
from __future__ import annotations

import csv
import json
import os
import re
from dataclasses import dataclass, field

import numpy as np

from . import _curio
from ._curio import (ARCHIVE_CAPACITY, IMAGE_SIZE, KIND_NAMES, MAX_OUTCOME_DIM, THETA_DIM,
                     Explorer, World, checkpoints, controllability, exploration_ratio, render)

__all__ = [
    "Explorer", "World", "Encoder", "render", "exploration_ratio", "checkpoints",
    "controllability", "campaign", "read_campaign", "Campaign", "KIND_NAMES", "THETA_DIM",
    "MAX_OUTCOME_DIM", "ARCHIVE_CAPACITY", "IMAGE_SIZE",
]

_HERE = os.path.dirname(os.path.abspath(__file__))


class Encoder(_curio.Encoder):
    __doc__ = _curio.Encoder.__doc__

    def decode(self, z, decoder_path=None):
        """The float decoder's image of latents z: (10,) -> (64, 64, 3), (N, 10) -> (N, 64, 64, 3),
        float32 in [0, 1]. Reads the float model file <name>.cfm (shipped beside the package
        when installed, else firmware/nn/models/ of the source tree) unless decoder_path names
        one."""
        if decoder_path is None:
            decoder_path = _model_file(self.name)
        return self._decode(z, os.fspath(decoder_path))


def _model_file(name):
    for folder in (os.path.join(_HERE, "models"), _curio._MODELS_DIR):
        path = os.path.join(folder, name + ".cfm")
        if os.path.exists(path):
            return path
    raise ValueError(f"decoder_path: no float model file {name}.cfm beside the package or in "
                     f"{_curio._MODELS_DIR}; pass decoder_path=")


@dataclass
class Campaign:
    """Results of a campaign (algorithms x seeds x sigmas), run here or read from a folder.

    ratio[i_sigma, i_algorithm, i_seed, k] is the exploration ratio after checkpoints[k]
    episodes (NaN where that run has no such checkpoint: runs of different lengths share one
    grid), grasps likewise. verdicts[i_sigma, i_algorithm, i_seed] is the controllable-feature
    verdict as curio-lab spells it ("ball", "z0,z2", "none"; "" for RPE), expected the ground
    truth in the same spelling. controllable[(sigma, algorithm, seed)] holds the per-module
    booleans, module_names[algorithm] the modules' names, interest[(sigma, algorithm, seed)]
    the pair (episodes, |cp| per module).
    """
    algorithms: list
    seeds: np.ndarray
    sigmas: np.ndarray
    checkpoints: np.ndarray
    ratio: np.ndarray
    grasps: np.ndarray
    verdicts: np.ndarray
    expected: np.ndarray
    module_names: dict = field(default_factory=dict)
    controllable: dict = field(default_factory=dict)
    interest: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)

    def final_ratio(self):
        """The last recorded ratio of every run, shape (sigmas, algorithms, seeds)."""
        out = np.full(self.ratio.shape[:3], np.nan)
        for idx in np.ndindex(*self.ratio.shape[:3]):
            row = self.ratio[idx]
            ok = ~np.isnan(row)
            if ok.any():
                out[idx] = row[ok][-1]
        return out

    def verdict_share(self, expected=True):
        """Share of seeds whose verdict equals the expected one, (sigmas, algorithms)."""
        match = (self.verdicts == self.expected) & (self.expected != "")
        return match.mean(axis=2) if expected else (~match).mean(axis=2)


def _assemble(runs, algorithms, seeds, sigmas):
    grid = sorted({int(c) for r in runs for c in r["checkpoints"]})
    index = {c: k for k, c in enumerate(grid)}
    shape = (len(sigmas), len(algorithms), len(seeds))
    ratio = np.full(shape + (len(grid),), np.nan)
    grasps = np.full(shape + (len(grid),), -1, dtype=np.int64)
    verdicts = np.full(shape, "", dtype=object)
    expected = np.full(shape, "", dtype=object)
    c = Campaign(list(algorithms), np.asarray(seeds, dtype=np.uint64),
                 np.asarray(sigmas, dtype=np.float64), np.asarray(grid, dtype=np.int64), ratio,
                 grasps, verdicts, expected)
    sigma_pos = {float(np.float32(s)): i for i, s in enumerate(sigmas)}
    for r in runs:
        i = sigma_pos[float(np.float32(r["sigma"]))]
        j = algorithms.index(r["algorithm"])
        k = list(int(s) for s in seeds).index(int(r["seed"]))
        key = (float(sigmas[i]), r["algorithm"], int(r["seed"]))
        if r.get("error"):
            c.errors[key] = r["error"]
        cols = [index[int(n)] for n in r["checkpoints"]]
        ratio[i, j, k, cols] = r["ratio"]
        grasps[i, j, k, cols] = r["grasps"]
        verdicts[i, j, k] = r.get("verdict", "")
        expected[i, j, k] = r.get("expected_verdict", "")
        c.module_names[r["algorithm"]] = list(r.get("module_names", []))
        c.controllable[key] = np.asarray(r.get("controllable", []), dtype=bool)
        c.interest[key] = (np.asarray(r.get("interest_episodes", [])), np.asarray(r.get("interest", [])))
    return c


def campaign(algorithms=("RPE", "RGE-EFR", "MGE-EFR"), seeds=(0, 1, 2), episodes=10000,
             sigmas=(0.05,), physics="kinematic", bootstrap=None, competence_clip=None,
             window=1000.0, epsilon=0.1, tie_rule="latest", competence_measure="clip",
             explore="spec", threads=0):
    """Runs a campaign in-process, as `curio-lab run` does (same runs, same results), on
    `threads` threads (0: all cores) with the GIL released; Ctrl-C stops it
    (KeyboardInterrupt). Returns a Campaign."""
    if isinstance(algorithms, str):
        algorithms = [algorithms]
    if isinstance(seeds, (int, np.integer)):
        seeds = [seeds]
    if isinstance(sigmas, (int, float)):
        sigmas = [sigmas]
    algorithms = [str(a) for a in algorithms]
    seeds = [int(s) for s in seeds]
    for s in seeds:
        if s < 0 or s >= 2**64:
            raise ValueError(f"seeds: {s} is outside 0 .. 2^64 - 1")
    sigmas = [float(s) for s in sigmas]
    runs = _curio._run_campaign(algorithms, seeds, int(episodes), sigmas, physics,
                                -1 if bootstrap is None else int(bootstrap),
                                -1.0 if competence_clip is None else float(competence_clip),
                                float(window), float(epsilon), tie_rule, competence_measure,
                                explore, int(threads))
    # curio-lab names an algorithm by its canonical name (MGE-bVAE -> MGE-βVAE).
    names = []
    for r in runs:
        if r["algorithm"] not in names:
            names.append(r["algorithm"])
    return _assemble(runs, names, seeds, sigmas)


_STEM = re.compile(r"^(?P<algo>.+)_sigma(?P<sigma>[^_]+)_seed(?P<seed>\d+)$")


def read_campaign(folder):
    """Reads a finished `curio-lab run --out FOLDER` or `curio-controller --out FOLDER` into a
    Campaign: runs/<algorithm>_sigma<σ>_seed<s>.csv (ratio and grasps at every checkpoint),
    runs/..._interest.csv, controllability.csv (the verdicts), and summary.json for the
    campaign's order and the verdicts' ground truth (expected: "" where the summary has none,
    as for single-module algorithms). The CSVs carry 6 significant digits."""
    folder = os.fspath(folder)
    runs_dir = os.path.join(folder, "runs")
    if not os.path.isdir(runs_dir):
        raise ValueError(f"folder: {folder!r} has no runs/ folder (not a curio-lab or "
                         "curio-controller output folder)")
    order, expected = None, {}
    summary = os.path.join(folder, "summary.json")
    if os.path.exists(summary):
        with open(summary, encoding="utf-8") as f:
            doc = json.load(f)
        order = doc.get("campaign")
        for row in doc.get("results", []):  # the ground truth of the verdicts, per algorithm and σ
            if "controllability" in row:
                expected[(row["algorithm"], float(np.float32(row["sigma"])))] = \
                    row["controllability"].get("expected", "")
    runs = {}
    for name in sorted(os.listdir(runs_dir)):
        if not name.endswith(".csv") or name.endswith("_interest.csv") or name.endswith("_scenes.csv"):
            continue
        m = _STEM.match(name[:-4])
        if not m:
            continue
        key = (m["algo"], float(m["sigma"]), int(m["seed"]))
        with open(os.path.join(runs_dir, name), newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        r = {"algorithm": key[0], "sigma": key[1], "seed": key[2],
             "checkpoints": [int(x["episodes"]) for x in rows],
             "ratio": [float(x["exploration_ratio"]) for x in rows],
             "grasps": [int(x["grasps"]) for x in rows], "controllable": [], "module_names": []}
        inter = os.path.join(runs_dir, name[:-4] + "_interest.csv")
        if os.path.exists(inter):
            with open(inter, newline="", encoding="utf-8") as f:
                rd = csv.reader(f)
                head = next(rd)
                body = [[float(v) for v in row] for row in rd]
            r["module_names"] = [h[len("interest_"):] for h in head[1:]]
            r["interest_episodes"] = [int(row[0]) for row in body]
            r["interest"] = [row[1:] for row in body]
        runs[key] = r
    if not runs:
        raise ValueError(f"folder: no run results in {runs_dir}")
    ctl = os.path.join(folder, "controllability.csv")
    if os.path.exists(ctl):
        with open(ctl, newline="", encoding="utf-8") as f:
            for row in csv.DictReader(f):
                key = (row["algorithm"], float(row["sigma"]), int(row["seed"]))
                if key not in runs:
                    continue
                r = runs[key]
                r.setdefault("_modules", []).append((row["module"], row["controllable"] == "1"))
    for r in runs.values():
        mods = r.pop("_modules", [])
        if not r["module_names"] and mods:
            r["module_names"] = [m for m, _ in mods]
        r["controllable"] = [c for _, c in mods]
        r["verdict"] = _verdict_text(mods) if mods else ""
        r["expected_verdict"] = expected.get((r["algorithm"], float(np.float32(r["sigma"]))), "")
    if order:
        # curio-lab records an algorithm under its canonical name (MGE-bVAE -> MGE-βVAE).
        algorithms = [_curio._canonical_algorithm(a) or a for a in order["algorithms"]]
        seeds = [int(s) for s in order["seeds"]]
        sigmas = [float(s) for s in order["sigmas"]]
        if {k[0] for k in runs} - set(algorithms):
            raise ValueError(f"folder: runs/ holds algorithms that summary.json does not list")
    else:
        algorithms = sorted({k[0] for k in runs})
        sigmas = sorted({k[1] for k in runs})
        seeds = sorted({k[2] for k in runs})
    return _assemble(list(runs.values()), algorithms, seeds, sigmas)


def _verdict_text(mods):
    names = [m for m, ok in mods if ok]
    if not names:
        return "none"
    if all(re.fullmatch(r"z\d+(\+z\d+)*", m) for m in names):
        latents = sorted(int(z[1:]) for m in names for z in m.split("+"))
        return ",".join(f"z{z}" for z in latents)
    return ",".join(names)
