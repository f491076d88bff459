"""curio.Explorer against curio-lab: the same seed gives the same archive checksum for every
algorithm (the real curio-lab binary, a few episodes each), ask/tell equals ex.run, and the
arrays are views of the archive."""
import re

import numpy as np
import pytest

import curio
from conftest import run_lab

# Every algorithm curio-lab knows (curio-lab run --help lists them), short runs.
ALGORITHMS = ["RPE", "RGE-EFR", "MGE-EFR", "RGE-VAE", "MGE-VAE", "RGE-βVAE", "MGE-βVAE",
              "MGE-VAE-10", "MGE-βVAE-10"]
SEEDS = [0, 7]
BOOTSTRAP, EPISODES = 20, 40
CHECKSUM = re.compile(r"curio-lab: (\S+) seed (\d+) σ=(\S+): archive checksum (0x[0-9a-f]{8}) "
                      r"\((\d+) episodes\)")


@pytest.fixture(scope="module")
def lab_checksums(curio_lab, tmp_path_factory):
    """{(algorithm, seed, explore): checksum} printed by curio-lab run --print-checksum."""
    out = {}
    for explore, algos in (("spec", ALGORITHMS), ("beyond", ["MGE-EFR", "RGE-EFR"])):
        folder = tmp_path_factory.mktemp("lab_" + explore)
        p = run_lab(curio_lab, ["--algos", ",".join(algos), "--seeds", ",".join(map(str, SEEDS)),
                                "--episodes", str(EPISODES), "--bootstrap", str(BOOTSTRAP),
                                "--explore", explore, "--threads", "2", "--quiet",
                                "--print-checksum", "--out", str(folder / "out")])
        for m in CHECKSUM.finditer(p.stderr):
            assert int(m[5]) == BOOTSTRAP + EPISODES
            out[(m[1], int(m[2]), explore)] = int(m[4], 16)
        out[("folder", explore)] = folder / "out"
    return out


@pytest.mark.parametrize("algorithm", ALGORITHMS)
def test_run_matches_curio_lab(lab_checksums, algorithm):
    for seed in SEEDS:
        ex = curio.Explorer(algorithm, seed=seed, episodes=EPISODES, bootstrap=BOOTSTRAP)
        assert ex.run(curio.World("kinematic", seed=seed)) == BOOTSTRAP + EPISODES
        assert ex.done and len(ex) == BOOTSTRAP + EPISODES
        assert ex.checksum() == lab_checksums[(ex.algorithm, seed, "spec")], (algorithm, seed)


def test_beyond_strategy_matches_curio_lab(lab_checksums):
    for algorithm in ("MGE-EFR", "RGE-EFR"):
        ex = curio.Explorer(algorithm, seed=7, episodes=EPISODES, bootstrap=BOOTSTRAP,
                            explore="beyond")
        ex.run(curio.World(seed=7))
        assert ex.checksum() == lab_checksums[(algorithm, 7, "beyond")]
    # and the strategy matters: spec's archive differs
    ex = curio.Explorer("MGE-EFR", seed=7, episodes=EPISODES, bootstrap=BOOTSTRAP)
    ex.run(curio.World(seed=7))
    assert ex.checksum() != lab_checksums[("MGE-EFR", 7, "beyond")]


def test_ratio_curve_and_verdicts_match_the_lab_folder(lab_checksums):
    c = curio.read_campaign(lab_checksums[("folder", "spec")])
    assert c.algorithms == ALGORITHMS and list(c.seeds) == SEEDS
    i = ALGORITHMS.index("MGE-EFR")
    for k, seed in enumerate(SEEDS):
        ex = curio.Explorer("MGE-EFR", seed=seed, episodes=EPISODES, bootstrap=BOOTSTRAP)
        ex.run(curio.World(seed=seed))
        cps = curio.checkpoints(ex.total_episodes)
        ours = curio.exploration_ratio(ex.scenes[:, :2], cps)
        theirs = c.ratio[0, i, k, np.searchsorted(c.checkpoints, cps)]
        np.testing.assert_allclose(ours, theirs, atol=1e-6)  # the CSV has 6 digits
        grasps = np.cumsum(np.concatenate([[0], ex.grasped]))[cps]
        np.testing.assert_array_equal(grasps, c.grasps[0, i, k, np.searchsorted(c.checkpoints, cps)])
        v = ex.verdicts()
        np.testing.assert_array_equal(v["controllable"], c.controllable[(0.05, "MGE-EFR", seed)])


def test_ask_tell_equals_run():
    a = curio.Explorer("MGE-EFR", seed=3, episodes=100, bootstrap=20)
    a.run(curio.World(seed=3))
    b = curio.Explorer("MGE-EFR", seed=3, episodes=100, bootstrap=20)
    world = curio.World(seed=3)
    while not b.done:
        theta = b.propose()
        assert theta.shape == (49,) and theta.dtype == np.float32
        assert np.all(np.abs(theta) <= 1)
        np.testing.assert_array_equal(b.propose(), theta)  # idempotent until observed
        b.observe(world.run(theta))
    assert a.checksum() == b.checksum()
    np.testing.assert_array_equal(a.outcomes, b.outcomes)
    np.testing.assert_array_equal(a.choices, b.choices)
    np.testing.assert_array_equal(a.interest, b.interest)
    # the archive's θ are the proposed ones
    c = curio.Explorer("MGE-EFR", seed=3, episodes=100, bootstrap=20)
    w = curio.World(seed=3)
    thetas = []
    while not c.done:
        thetas.append(c.propose())
        c.observe(w.run(thetas[-1]))
    np.testing.assert_array_equal(c.thetas(), np.array(thetas))
    np.testing.assert_array_equal(c.theta(57), thetas[57])


def test_learned_ask_tell_with_images_equals_run():
    a = curio.Explorer("MGE-βVAE", seed=1, episodes=20, bootstrap=10)
    a.run(curio.World(seed=1))
    b = curio.Explorer("MGE-bVAE", seed=1, episodes=20, bootstrap=10)
    assert b.learned and b.outcome_dim == 10 and b.n_modules == 5
    world = curio.World(seed=1)
    while not b.done:
        world.run(b.propose())
        b.observe(world.render())  # the camera image, encoded by the int8 encoder
    assert a.checksum() == b.checksum()


def test_arrays_are_views_that_grow_with_the_run():
    ex = curio.Explorer("MGE-EFR", seed=0, episodes=50, bootstrap=10)
    world = curio.World(seed=0)
    ex.run(world, episodes=30)
    out = ex.outcomes
    assert out.shape == (30, 4) and out.dtype == np.float32 and not out.flags.writeable
    assert out.base is not None  # a view of the archive, not a copy
    ex.run(world)
    assert ex.outcomes.shape == (60, 4)
    np.testing.assert_array_equal(ex.outcomes[:30], out)
    np.testing.assert_array_equal(ex.outcomes[:, 2:], ex.scenes[:, :2])  # ball x, y
    kinds = [curio.KIND_NAMES[k] for k in ex.kinds]
    assert kinds[:10] == ["bootstrap"] * 10 and kinds[14] == "exploit"
    assert (ex.choices[:10] == -1).all() and (ex.choices[10:] >= 0).all()
    exploit = ex.kinds == curio.KIND_NAMES.index("exploit")
    assert np.isnan(ex.progress[~exploit]).all() and not np.isnan(ex.progress[exploit]).any()
    assert ex.module_choices.sum() == exploit.sum() == 10
    assert list(ex.interest_episodes) == [0, 50] and ex.interest.shape == (2, 2)
    assert ex.module_names == ["distractor", "ball"] and ex.module_dims == [[0, 1], [2, 3]]
    assert np.isnan(ex.goals[:10]).all() and np.all(np.abs(ex.goals[10:]) <= 1)
    del ex  # the views keep the explorer alive
    assert out.sum() == out.sum()


def test_custom_modules_on_a_python_world():
    rng = np.random.default_rng(0)
    W = rng.normal(size=(49, 3)).astype(np.float32)

    def world(theta):  # any callable: outcome = 3 values
        return np.tanh(0.1 * theta @ W)

    ex = curio.Explorer("MGE", modules=[[0], [1, 2]], seed=5, episodes=100, bootstrap=20,
                        goals="box")
    assert ex.run(world) == 120
    assert ex.outcomes.shape == (120, 3) and ex.module_names == ["o0", "o1+o2"]
    same = curio.Explorer("MGE", modules=[[0], [1, 2]], seed=5, episodes=100, bootstrap=20)
    while not same.done:
        same.observe(world(same.propose()))
    assert same.checksum() == ex.checksum()
    rge = curio.Explorer("RGE", modules=[[0, 1, 2]], seed=5, episodes=100, bootstrap=20)
    rge.run(world)
    assert rge.checksum() != ex.checksum()


def test_run_releases_the_gil_and_guards_its_world():
    import threading
    ex = curio.Explorer("MGE-EFR", seed=0, episodes=5000, bootstrap=100)
    world = curio.World(seed=0)
    t = threading.Thread(target=ex.run, args=(world,))
    seen, refused = set(), 0
    t.start()
    while t.is_alive():
        e = ex.episode  # Python runs while the episodes run in C++
        seen.add(e)
        if 0 < e < ex.total_episodes:
            try:
                world.render()
            except ValueError as err:
                assert "in use" in str(err)
                refused += 1
    t.join()
    assert ex.done and len([e for e in seen if 0 < e < ex.total_episodes]) >= 2
    assert refused >= 1
    world.render()  # free again
