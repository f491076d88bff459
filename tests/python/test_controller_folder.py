"""A finished curio-controller output folder (the firmware controller over the UDP bus against
curio-sim serve's ODE arm) reads into a Campaign, and curio.Explorer on curio.World("ode")
builds the controller's very archive (its --print-checksum)."""
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import curio

SEED, BOOTSTRAP, EPISODES = 4, 20, 40


def test_controller_folder_and_checksum(source_dir, tmp_path):
    sim, controller = os.environ.get("CURIO_SIM"), os.environ.get("CURIO_CONTROLLER")
    if not (sim and controller and os.path.exists(sim) and os.path.exists(controller)):
        pytest.fail("CURIO_SIM and CURIO_CONTROLLER must name the binaries (ctest sets them)")
    sys.path.insert(0, os.path.join(source_dir, "tests", "common"))
    from free_udp_ports import free_port_base
    bus = f"udp:127.0.0.1:{free_port_base(2, os.getpid())}?ports=2"
    serve = subprocess.Popen([sim, "serve", "--bus", bus, "--physics", "ode", "--seed", str(SEED),
                              "--exit-after-idle", "20", "--status-every", "0"],
                             stderr=subprocess.DEVNULL)
    try:
        p = subprocess.run([controller, "--bus", bus, "--algo", "MGE-EFR", "--seed", str(SEED),
                            "--episodes", str(EPISODES), "--bootstrap", str(BOOTSTRAP),
                            "--out", str(tmp_path / "controller"), "--quiet", "--print-checksum"],
                           capture_output=True, text=True, timeout=120)
    finally:
        serve.terminate()
        serve.wait(timeout=30)
    assert p.returncode == 0, p.stderr
    checksum = int(re.search(r"archive checksum (0x[0-9a-f]{8})", p.stdout)[1], 16)

    ex = curio.Explorer("MGE-EFR", seed=SEED, episodes=EPISODES, bootstrap=BOOTSTRAP)
    ex.run(curio.World("ode", seed=SEED))
    assert ex.checksum() == checksum

    c = curio.read_campaign(tmp_path / "controller")
    assert c.algorithms == ["MGE-EFR"] and list(c.seeds) == [SEED]
    ours = curio.exploration_ratio(ex.scenes[:, :2], c.checkpoints)
    np.testing.assert_allclose(c.ratio[0, 0, 0], ours, atol=1e-6)
    np.testing.assert_array_equal(c.controllable[(0.05, "MGE-EFR", SEED)],
                                  ex.verdicts()["controllable"])
    e, interest = c.interest[(0.05, "MGE-EFR", SEED)]
    np.testing.assert_array_equal(e, ex.interest_episodes)
    np.testing.assert_allclose(interest, ex.interest, rtol=1e-5)
