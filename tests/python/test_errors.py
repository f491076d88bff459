"""Bad input raises ValueError or TypeError naming the argument, never a crash."""
import numpy as np
import pytest

import curio


def fresh(**kw):
    return curio.Explorer("MGE-EFR", episodes=10, bootstrap=5, **kw)


@pytest.mark.parametrize("kwargs, arg", [
    (dict(algorithm="MGE-XYZ"), "algorithm"),
    (dict(algorithm="MGE-EFR", explore="sideways"), "explore"),
    (dict(algorithm="MGE-EFR", tie_rule="random"), "tie_rule"),
    (dict(algorithm="MGE-EFR", competence_measure="cube"), "competence_measure"),
    (dict(algorithm="MGE-EFR", sigma=-1.0), "sigma"),
    (dict(algorithm="MGE-EFR", epsilon=2.0), "epsilon"),
    (dict(algorithm="MGE-EFR", episodes=-5), "episodes"),
    (dict(algorithm="MGE-EFR", episodes=12), "episodes: expected a multiple of 5"),
    (dict(algorithm="MGE-EFR", episodes=20000), "episodes: .* archive capacity"),
    (dict(algorithm="MGE-βVAE", episodes=10005), r"episodes: bootstrap \(400\)"),
    (dict(algorithm="MGE-EFR", modules=[[0, 1]]), "modules"),
    (dict(algorithm="MGE", modules=[[0, 0]]), "modules"),
    (dict(algorithm="MGE", modules=[[0, 11]]), "modules"),
    (dict(algorithm="MGE"), "modules"),
    (dict(algorithm="RGE", modules=[[0], [1]]), "modules"),
    (dict(algorithm="MGE", modules=[[0], [1]], goals="sphere"), "goals"),
    (dict(algorithm="MGE", modules=[[0], [1]], outcome_dim=1), "modules"),
    (dict(algorithm="MGE", modules=[[0]], outcome_dim=11), "outcome_dim"),
    (dict(algorithm="MGE", modules=[[0]], interest_every=0), "interest_every"),
])
def test_bad_configurations(kwargs, arg):
    with pytest.raises(ValueError, match=arg):
        curio.Explorer(**{"episodes": 10, **kwargs})


def test_bad_types():
    with pytest.raises(TypeError, match="modules"):
        curio.Explorer("MGE", modules="01")
    with pytest.raises(TypeError, match="modules"):
        curio.Explorer("MGE", modules=[[0.5]])
    with pytest.raises(TypeError):
        curio.Explorer("MGE-EFR", seed=-1)  # seeds are 0 .. 2^64 - 1


def test_bad_outcomes_and_order():
    ex = fresh()
    with pytest.raises(ValueError, match="propose"):
        ex.observe([0, 0, 0, 0])  # observe() without a propose()
    ex.propose()
    with pytest.raises(ValueError, match="outcome: expected a vector of 4 values"):
        ex.observe([0, 0, 0])
    with pytest.raises(ValueError, match="outcome: value 2 is not finite"):
        ex.observe([0, 0, np.nan, 0])
    with pytest.raises(ValueError, match="outcome"):
        ex.observe(np.zeros((2, 2)))
    with pytest.raises(TypeError, match="outcome"):
        ex.observe("abcd")
    with pytest.raises(ValueError, match="pending"):
        ex.run(curio.World())
    with pytest.raises(ValueError, match="episodes"):
        ex.run(curio.World(), episodes=-1)
    with pytest.raises(TypeError, match="episodes"):
        ex.run(curio.World(), episodes="all")
    ex.observe(np.float64([0.1, 0.2, 0.3, 0.4]))  # still pending after the errors: accepted
    assert ex.episode == 1 and ex.counters["non_finite_outcomes"] == 0
    ex.run(curio.World())
    with pytest.raises(ValueError, match="done"):
        ex.propose()
    with pytest.raises(ValueError, match="i: no archived episode"):
        ex.theta(15)


def test_bad_images():
    ex = curio.Explorer("MGE-βVAE", episodes=5, bootstrap=2)
    ex.propose()
    with pytest.raises(TypeError, match="outcome: expected dtype uint8"):
        ex.observe(np.zeros((64, 64, 3), np.float32))
    with pytest.raises(ValueError, match="outcome: expected shape"):
        ex.observe(np.zeros((32, 32, 3), np.uint8))
    with pytest.raises(ValueError, match="outcome"):
        ex.observe(np.zeros(4, np.float32))  # 10 latents expected
    ex.observe(np.zeros((64, 64, 3), np.uint8))
    enc = curio.Encoder()
    with pytest.raises(TypeError, match="images: expected dtype uint8"):
        enc.encode(np.zeros((2, 64, 64, 3), np.int16))
    with pytest.raises(ValueError, match="images: expected shape"):
        enc.encode(np.zeros((2, 64, 64), np.uint8))
    with pytest.raises(TypeError, match="images"):
        enc.encode([[1, 2, 3]])
    with pytest.raises(ValueError, match="name"):
        curio.Encoder("resnet")
    with pytest.raises(ValueError, match="z"):
        enc.decode(np.zeros(3))
    with pytest.raises(ValueError, match="group_size"):
        enc.modules(3)


def test_bad_worlds():
    with pytest.raises(ValueError, match="physics"):
        curio.World("mujoco")
    w = curio.World()
    with pytest.raises(ValueError, match="theta: expected a vector of 49"):
        w.run(np.zeros(48))
    with pytest.raises(ValueError, match="commands"):
        w.step(np.full(7, 2.0))
    with pytest.raises(ValueError, match="theta"):
        w.run(np.full(49, np.inf))
    w.close()
    for call in (w.reset, w.render, lambda: w.run(np.zeros(49)), lambda: w.state):
        with pytest.raises(ValueError, match="world: used after close"):
            call()
    ex = fresh()
    with pytest.raises(ValueError, match="world: used after close"):
        ex.run(w)
    with pytest.raises(TypeError, match="world"):
        ex.run(42)
    custom = curio.Explorer("MGE", modules=[[0], [1]], episodes=10)
    with pytest.raises(ValueError, match="world: a curio.World gives 4"):
        custom.run(curio.World())


def test_bad_metric_and_campaign_arguments(tmp_path):
    with pytest.raises(ValueError, match="points"):
        curio.exploration_ratio(np.zeros((5, 3)))
    with pytest.raises(ValueError, match="checkpoints"):
        curio.exploration_ratio(np.zeros((5, 2)), [3, 1])
    with pytest.raises(ValueError, match="exploit_modules"):
        curio.controllability([1], [2], [0.5], np.zeros((1, 2)), [0], 0, 10)
    with pytest.raises(ValueError, match="unknown algorithm"):
        curio.campaign(["MGE-XYZ"], seeds=[0], episodes=10)
    with pytest.raises(ValueError, match="physics"):
        curio.campaign(["RPE"], seeds=[0], episodes=10, physics="mujoco")
    with pytest.raises(ValueError, match="seeds"):
        curio.campaign(["RPE"], seeds=[-1], episodes=10)
    with pytest.raises(ValueError, match="folder"):
        curio.read_campaign(tmp_path)
