"""Shared fixtures: the built curio package (PYTHONPATH set by CTest) and the curio-lab binary."""
import os
import shutil
import subprocess

import pytest


@pytest.fixture(scope="session")
def curio_lab():
    path = os.environ.get("CURIO_LAB") or shutil.which("curio-lab")
    if not path or not os.path.exists(path):
        pytest.fail("CURIO_LAB must name the curio-lab binary (ctest sets it)")
    return path


@pytest.fixture(scope="session")
def source_dir():
    return os.environ.get("CURIO_SOURCE_DIR") or os.path.abspath(
        os.path.join(os.path.dirname(__file__), "..", ".."))


def run_lab(curio_lab, args):
    p = subprocess.run([curio_lab, "run", *args], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    return p
