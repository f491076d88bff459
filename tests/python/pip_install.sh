#!/usr/bin/env bash
# The documented offline install (docs/python.md): a venv over Debian's numpy, then
# `pip install --no-build-isolation host_tools/python` (setup.py builds _curio with this
# repository's CMake into build/python-<version>), then an exploration from the installed
# package, outside the source tree, equal to curio-lab's checksum. Label long: it builds.
#   pip_install.sh REPO_DIR WORKDIR CURIO_LAB
set -euo pipefail
repo=$1 work=$2 lab=$3
rm -rf "$work" && mkdir -p "$work"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
"$work/venv/bin/pip" install --no-build-isolation --no-index "$repo/host_tools/python"
rm -rf "$repo/host_tools/python/build" "$repo/host_tools/python/curio.egg-info"
cd "$work"
got=$("$work/venv/bin/python" -c 'import curio
ex = curio.Explorer("MGE-EFR", seed=2, episodes=50, bootstrap=20)
ex.run(curio.World(seed=2))
assert curio.Encoder().decode([0.0] * 10).shape == (64, 64, 3)
print("0x%08x" % ex.checksum())')
want=$("$lab" run --algos MGE-EFR --seeds 2 --episodes 50 --bootstrap 20 --quiet --print-checksum \
  --out "$work/lab" 2>&1 | sed -n 's/.*archive checksum \(0x[0-9a-f]*\).*/\1/p')
[ "$got" = "$want" ] || { echo "installed package: $got, curio-lab: $want"; exit 1; }
echo "pip-installed curio: archive checksum $got equal to curio-lab's"
