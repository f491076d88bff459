"""curio.World (reset/step/run/render, both physics) and curio.Encoder (bit for bit the
encoder the explorer archives with, batch = one by one, modules in KL order, decoder)."""
import numpy as np
import pytest

import curio


@pytest.mark.parametrize("physics", ["kinematic", "ode"])
def test_world_reset_step_run_render(physics):
    with curio.World(physics, seed=4) as w:
        s = w.reset()
        assert s["ball"] == (0.6, 0.6) and s["distractor"] == (0.7, -0.45)
        assert s["grasped"] is False
        assert s["hand"] == pytest.approx((1.0, 0.0), abs=1e-6)
        img = w.render()
        assert img.shape == (64, 64, 3) and img.dtype == np.uint8
        np.testing.assert_array_equal(img, curio.render((0.6, 0.6), (0.7, -0.45)))
        s = w.step(np.full(7, 0.5))
        assert s["hand"] != (1.0, 0.0)
        theta = np.random.default_rng(1).uniform(-1, 1, 49).astype(np.float32)
        out = w.run(theta)
        st = w.state
        assert out.dtype == np.float32 and out.shape == (4,)
        np.testing.assert_array_equal(out, np.float32([*st["distractor"], *st["ball"]]))
        # the same episode again gives the same arm (the distractor walks on)
        w2 = curio.World(physics, seed=4)
        w2.step(np.full(7, 0.5))
        np.testing.assert_array_equal(w2.run(theta)[2:], out[2:])
    assert w.closed
    with pytest.raises(ValueError, match="after close"):
        w.render()


def test_world_seed_is_the_run_seed():
    # two worlds with the same seed walk the distractor alike, another seed differs
    theta = np.zeros(49, np.float32)
    a, b, c = curio.World(seed=9), curio.World(seed=9), curio.World(seed=10)
    for _ in range(3):
        ra, rb, rc = a.run(theta), b.run(theta), c.run(theta)
    np.testing.assert_array_equal(ra, rb)
    assert not np.array_equal(ra[:2], rc[:2])
    a.reset_to_episode(2)
    b2 = curio.World(seed=9)
    b2.run(theta), b2.run(theta)
    b2.reset()
    assert a.state == b2.state


def test_encoder_equals_the_explorers_encoder():
    """The archive of a learned run holds the controller's encoder output for each episode's
    camera frame: curio.Encoder gives the same floats, bit for bit, in one batch."""
    ex = curio.Explorer("MGE-βVAE", seed=2, episodes=20, bootstrap=10)
    world = curio.World(seed=2)
    frames = []
    while not ex.done:
        world.run(ex.propose())
        frames.append(world.render())
        ex.observe(frames[-1])
    frames = np.stack(frames)
    enc = curio.Encoder("beta_vae", threads=2)
    mu, log_var = enc.encode(frames)
    assert mu.shape == (30, 10) and mu.dtype == np.float32 and log_var.shape == (30, 10)
    np.testing.assert_array_equal(mu, ex.outcomes)
    one_mu, one_lv = curio.Encoder("beta_vae").encode(frames[7])
    np.testing.assert_array_equal(one_mu, mu[7])
    np.testing.assert_array_equal(one_lv, log_var[7])
    assert not np.array_equal(mu[0], mu[-1])
    # the explorer's modules are the encoder's KL-ordered pairs
    assert ex.module_dims == enc.modules(2)
    assert sorted(enc.kl_order) == list(range(10))
    assert enc.modules(10) == [list(enc.kl_order)]
    kl = enc.kl_per_latent[enc.kl_order]
    assert np.all(np.diff(kl) <= 0)


def test_vae_differs_and_decoder_reconstructs():
    img = curio.render((0.3, -0.2), (-0.5, 0.5))
    bv, _ = curio.Encoder("beta_vae").encode(img)
    v, _ = curio.Encoder("vae").encode(img)
    assert not np.array_equal(bv, v)
    enc = curio.Encoder("beta_vae")
    rec = enc.decode(bv)
    assert rec.shape == (64, 64, 3) and rec.dtype == np.float32
    assert 0 <= rec.min() and rec.max() <= 1
    # the reconstruction is closer to its image than to another scene's
    other = curio.render((-0.6, 0.6), (0.5, -0.5)) / 255.0
    err = np.abs(rec - img / 255.0).mean()
    assert err < np.abs(rec - other).mean()
    batch = enc.decode(np.stack([bv, bv]))
    assert batch.shape == (2, 64, 64, 3)
    np.testing.assert_array_equal(batch[0], rec)


def test_ode_worlds_in_threads_equal_one_thread():
    """Explorers on ODE worlds in Python threads (the GIL released in run) give the archives
    they give one after another."""
    from concurrent.futures import ThreadPoolExecutor

    def one(seed):
        ex = curio.Explorer("MGE-EFR", seed=seed, episodes=20, bootstrap=10)
        ex.run(curio.World("ode", seed=seed))
        return ex.checksum()

    alone = [one(s) for s in (1, 2)]
    with ThreadPoolExecutor(2) as pool:
        assert list(pool.map(one, (1, 2))) == alone
    assert alone[0] != alone[1]
