"""Speed of the curio Python package beside the same exploration in C++ (label bench).

10,000 MGE-EFR episodes (+ 100 bootstrap, kinematic world, seed 0), each way on one thread:
  C++ in-process   curio-lab's run_exploration (curio.campaign with one run, one thread)
  ex.run           curio.Explorer.run(curio.World): the episode loop in C++, the GIL released
  ask/tell         a Python loop: ex.observe(world.run(ex.propose())) on curio.World
  Python world     the same loop on a pure-Python world (a numpy point mass, 4 outcome values)
All four make the same archive but the last. Prints one line per figure and the ratios to the
C++ run; each figure is the best of `repeats` (default 2) to damp a busy machine.

    PYTHONPATH=build/default/host_tools/python /usr/bin/python3 tests/python/bench_python.py [repeats]
"""
import sys
import time

import numpy as np

import curio

EPISODES, BOOTSTRAP, SEED = 10000, 100, 0


def best(fn, repeats):
    times, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return min(times), result


def cpp_in_process():
    runs = curio._curio._run_campaign(["MGE-EFR"], [SEED], EPISODES, [0.05], "kinematic",
                                      BOOTSTRAP, -1.0, 1000.0, 0.1, "latest", "clip", "spec", 1)
    assert not runs[0]["error"], runs[0]["error"]
    return runs[0]["ratio"][-1]


def explorer_run():
    ex = curio.Explorer("MGE-EFR", seed=SEED, episodes=EPISODES, bootstrap=BOOTSTRAP)
    ex.run(curio.World("kinematic", seed=SEED))
    return ex


def ask_tell():
    ex = curio.Explorer("MGE-EFR", seed=SEED, episodes=EPISODES, bootstrap=BOOTSTRAP)
    world = curio.World("kinematic", seed=SEED)
    propose, observe, run = ex.propose, ex.observe, world.run
    while not ex.done:
        observe(run(propose()))
    return ex


class PointMass:
    """docs/python.md's pure-Python world: a point mass at tanh(0.5 θ·W), a distractor walking."""

    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)
        self.W = np.random.default_rng(1).normal(size=(49, 2)) / 7
        self.distractor = np.zeros(2)

    def run(self, theta):
        pos = np.tanh(0.5 * (theta @ self.W))
        self.distractor = np.clip(self.distractor + self.rng.normal(0.0, 0.1, 2), -1.0, 1.0)
        return np.concatenate([pos, self.distractor])


def python_world():
    ex = curio.Explorer("MGE", modules=[[0, 1], [2, 3]], seed=SEED, episodes=EPISODES,
                        bootstrap=BOOTSTRAP)
    world = PointMass(SEED)
    while not ex.done:
        ex.observe(world.run(ex.propose()))
    return ex


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    n = EPISODES + BOOTSTRAP
    t_cpp, _ = best(cpp_in_process, repeats)
    t_run, ex_run = best(explorer_run, repeats)
    t_ask, ex_ask = best(ask_tell, repeats)
    t_py, _ = best(python_world, repeats)
    c_run = ex_run.checksum()  # (outside the timings: it regenerates every θ)
    assert c_run == ex_ask.checksum(), "ask/tell and ex.run made different archives"
    print(f"python bench: {n} MGE-EFR episodes (kinematic, seed {SEED}), best of {repeats}, one thread")
    print(f"  C++ in-process (curio-lab's run) {t_cpp:7.2f} s  {n / t_cpp:8.0f} episodes/s")
    print(f"  ex.run(curio.World)              {t_run:7.2f} s  {n / t_run:8.0f} episodes/s  "
          f"{t_run / t_cpp:.2f}x the C++ time (target <= 1.1x)")
    print(f"  Python ask/tell on curio.World   {t_ask:7.2f} s  {n / t_ask:8.0f} episodes/s  "
          f"{t_ask / t_cpp:.2f}x the C++ time (target <= 2x)")
    print(f"  Python ask/tell, pure-Python world {t_py:5.2f} s  {n / t_py:8.0f} episodes/s "
          f"(numpy point mass, MGE over 2 modules)")
    print(f"  archive checksum 0x{c_run:08x} (ex.run = ask/tell)")


if __name__ == "__main__":
    main()
