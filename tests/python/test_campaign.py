"""curio.campaign (curio-lab's runs on threads) and curio.read_campaign (a curio-lab output
folder) give the same Campaign; the metric helpers equal curio-lab's."""
import numpy as np

import curio
from conftest import run_lab

ALGOS = ["RPE", "RGE-EFR", "MGE-EFR"]


def test_campaign_equals_curio_lab_folder(curio_lab, tmp_path):
    c = curio.campaign(ALGOS, seeds=[0, 1, 2], episodes=100, bootstrap=20, threads=2)
    assert c.ratio.shape == (1, 3, 3, len(c.checkpoints))
    assert c.checkpoints[-1] == 120 and not np.isnan(c.ratio).any()
    assert (np.diff(c.ratio, axis=-1) >= 0).all()  # coverage only grows
    assert c.verdicts.shape == (1, 3, 3) and c.verdicts[0, 0, 0] == ""  # RPE: no modules
    assert set(c.verdicts[0, 2]) <= {"ball", "none", "distractor", "distractor,ball"}
    assert (c.expected[0, 1:] == "ball").all()
    out = tmp_path / "out"
    run_lab(curio_lab, ["--algos", ",".join(ALGOS), "--seeds", "0-2", "--episodes", "100",
                        "--bootstrap", "20", "--quiet", "--threads", "2", "--out", str(out)])
    r = curio.read_campaign(out)
    assert r.algorithms == ALGOS and list(r.seeds) == [0, 1, 2]
    np.testing.assert_array_equal(r.checkpoints, c.checkpoints)
    np.testing.assert_allclose(r.ratio, c.ratio, atol=1e-6)
    np.testing.assert_array_equal(r.grasps, c.grasps)
    np.testing.assert_array_equal(r.verdicts[:, 1:], c.verdicts[:, 1:])
    assert (r.expected[0, 2] == "ball").all() and (r.expected[0, :2] == "").all()
    for key, v in c.controllable.items():
        np.testing.assert_array_equal(r.controllable[key], v)
    e, i = c.interest[(0.05, "MGE-EFR", 1)]
    e2, i2 = r.interest[(0.05, "MGE-EFR", 1)]
    np.testing.assert_array_equal(e, e2)
    np.testing.assert_allclose(i, i2, rtol=1e-5)
    assert r.module_names["MGE-EFR"] == c.module_names["MGE-EFR"] == ["distractor", "ball"]
    np.testing.assert_allclose(r.final_ratio(), c.final_ratio(), atol=1e-6)


def test_campaign_run_equals_explorer_run():
    c = curio.campaign("MGE-EFR", seeds=4, episodes=50, bootstrap=10, physics="ode", threads=1)
    ex = curio.Explorer("MGE-EFR", seed=4, episodes=50, bootstrap=10)
    ex.run(curio.World("ode", seed=4))
    np.testing.assert_array_equal(
        c.ratio[0, 0, 0], curio.exploration_ratio(ex.scenes[:, :2], c.checkpoints))
    v = ex.verdicts()
    np.testing.assert_array_equal(c.controllable[(0.05, "MGE-EFR", 4)], v["controllable"])


def test_exploration_ratio_and_controllability():
    assert curio.exploration_ratio(np.zeros((0, 2))) == 0.0
    pts = np.array([[-1, -1], [1, 1], [0.999, 0.999], [2, 0], [0, 0]])
    assert curio.exploration_ratio(pts) == 3 / 900  # (1,1) and (.999,.999) share a cell
    np.testing.assert_array_equal(curio.exploration_ratio(pts, [0, 2, 5]), [0, 2 / 900, 3 / 900])
    cps = curio.checkpoints(10100)
    assert cps[0] == 0 and cps[-1] == 10100 and 333 in cps and 10000 in cps
    # a module whose progress is always positive is controllable, one with noise is not
    rng = np.random.default_rng(0)
    n = 400
    eps = np.arange(1, n + 1) * 5
    mods = np.arange(n) % 2
    prog = np.where(mods == 0, rng.uniform(0.01, 0.02, n), rng.normal(0, 0.01, n))
    inter = np.tile([0.02, 0.015], (41, 1))
    v = curio.controllability(eps, mods, prog, inter, np.arange(41) * 50, 0, 2000)
    assert list(v["controllable"]) == [True, False]
    assert v["t"][0] > 3 and abs(v["t"][1]) < 3
