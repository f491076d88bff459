#!/usr/bin/env python3
"""Checks Curio's layering and include convention (docs/architecture.md, "What each layer may
include"). Exits 1 and names every offending line; 0 when the tree is clean.

usage: check_layers.py [REPO_DIR]      check a tree (default: this script's repository)
       check_layers.py --self-test     prove the checker catches each kind of violation

Rules, for every C/C++ file the repository holds:
  1. Project headers are included by their path from the repository root, in quotes
     ("firmware/explore/archive.hpp", "hal/can_bus.hpp"); the one other root is the build's
     generated/ folder, which mirrors the tree (so the path still names a source folder).
  2. firmware/, hal/*.{hpp,cpp} (the firmware-clean interfaces and SLCAN bus) and hal/mps2/
     (the QEMU board's drivers) include only firmware/ and hal/*.hpp (hal/mps2/ also its own
     headers), and from the C/C++ library only freestanding-safe headers (FIRMWARE_SYSTEM):
     no OS headers, no <vector>/<string>/<iostream>, no allocation-based containers.
  3. hal/ (its host/ and linux/ backends) does not include sim/, host_tools/ or tests/.
  4. sim/ does not include host_tools/ or tests/.
  5. Nothing outside tests/ includes tests/.
"""
import os
import re
import subprocess
import sys
import tempfile

SOURCE_EXT = (".c", ".cc", ".cpp", ".h", ".hpp")
ROOTS = ("firmware/", "hal/", "sim/", "host_tools/", "tests/", "toolchain/")
# What firmware may take from the toolchain: freestanding headers and the handful of
# hosted ones that need no OS and no heap (cmath, cstring for memcpy, SIMD intrinsics on
# the host's vector path, guarded by the build).
FIRMWARE_SYSTEM = {
    "array", "bit", "cfloat", "climits", "cmath", "cstddef", "cstdint", "cstring", "limits",
    "new", "type_traits", "utility", "immintrin.h", "arm_acle.h",
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def tracked_sources(repo):
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "--cached", "--others",
                              "--exclude-standard"], check=True, capture_output=True,
                             text=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        out = []
        for d, _, files in os.walk(repo):
            for f in files:
                out.append(os.path.relpath(os.path.join(d, f), repo))
    return sorted(p for p in out if p.endswith(SOURCE_EXT) and not p.startswith("build/"))


def is_firmware_clean(path):
    return (path.startswith("firmware/") or path.startswith("hal/mps2/") or
            (path.startswith("hal/") and path.count("/") == 1))


def check_file(repo, path, generated):
    problems = []
    try:
        lines = open(os.path.join(repo, path), encoding="utf-8", errors="replace").readlines()
    except OSError as e:
        return [f"{path}: cannot read ({e})"]
    for n, line in enumerate(lines, 1):
        m = INCLUDE.match(line)
        if not m:
            continue
        kind, target = m.groups()
        where = f"{path}:{n}: #include {kind}{target}{'>' if kind == '<' else kind}"
        if kind == '"':
            if not target.startswith(ROOTS):
                problems.append(f"{where}: not a path from the repository root (rule 1)")
                continue
            if not os.path.exists(os.path.join(repo, target)) and target not in generated:
                problems.append(f"{where}: no such file from the repository root (rule 1)")
                continue
        if is_firmware_clean(path):
            if kind == "<" and target not in FIRMWARE_SYSTEM:
                problems.append(f"{where}: firmware code may not use this system header (rule 2)")
            if kind == '"' and not (target.startswith("firmware/") or
                                    (target.startswith("hal/") and target.count("/") == 1) or
                                    (path.startswith("hal/mps2/") and
                                     target.startswith("hal/mps2/"))):
                problems.append(f"{where}: firmware code includes only firmware/ and hal/*.hpp "
                                "(rule 2)")
        elif path.startswith("hal/"):
            if kind == '"' and target.startswith(("sim/", "host_tools/", "tests/")):
                problems.append(f"{where}: hal/ may not include {target.split('/')[0]}/ (rule 3)")
        elif path.startswith("sim/"):
            if kind == '"' and target.startswith(("host_tools/", "tests/")):
                problems.append(f"{where}: sim/ may not include {target.split('/')[0]}/ (rule 4)")
        if not path.startswith("tests/") and kind == '"' and target.startswith("tests/"):
            problems.append(f"{where}: only tests/ may include tests/ (rule 5)")
    return problems


# Headers made at build time (rule 1's generated/ root): the path they are included by.
GENERATED = {"tests/nn/synthetic_weights.hpp"}


def check(repo):
    problems = []
    for path in tracked_sources(repo):
        problems += check_file(repo, path, GENERATED)
    return problems


def self_test():
    cases = {
        "firmware/explore/ok.hpp": '#include <cstdint>\n#include "hal/can_bus.hpp"\n',
        "hal/can_bus.hpp": "#include <cstdint>\n",
        "firmware/explore/bad_os.cpp": "#include <unistd.h>\n",
        "firmware/explore/bad_vector.cpp": "#include <vector>\n",
        "firmware/explore/bad_host.cpp": '#include "host_tools/experiment/run.hpp"\n',
        "firmware/explore/bad_linux.cpp": '#include "hal/linux/udp_bus.hpp"\n',
        "firmware/explore/bad_sim.cpp": '#include "sim/world.hpp"\n',
        "firmware/explore/bad_relative.cpp": '#include "ok.hpp"\n',
        "sim/bad_lab.cpp": '#include "host_tools/experiment/run.hpp"\n',
        "hal/linux/bad_sim.cpp": '#include "sim/world.hpp"\n',
        "host_tools/lab/bad_test.cpp": '#include "tests/app/util.hpp"\n',
        "host_tools/experiment/run.hpp": "",
        "hal/linux/udp_bus.hpp": "",
        "sim/world.hpp": "",
        "tests/app/util.hpp": "",
    }
    with tempfile.TemporaryDirectory() as d:
        for rel, text in cases.items():
            os.makedirs(os.path.dirname(os.path.join(d, rel)), exist_ok=True)
            with open(os.path.join(d, rel), "w") as f:
                f.write(text)
        problems = check(d)
    flagged = {p.split(":")[0] for p in problems}
    expected = {rel for rel in cases if "/bad_" in rel}
    if flagged != expected:
        print("check_layers self-test FAILED")
        print("  expected to flag:", sorted(expected))
        print("  flagged:         ", sorted(flagged))
        return 1
    print(f"check_layers self-test: all {len(expected)} violations caught, clean files pass")
    return 0


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    if len(argv) > 1 and argv[1] == "--self-test":
        return self_test()
    repo = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems = check(repo)
    files = len(tracked_sources(repo))
    if problems:
        print(f"check_layers: {len(problems)} violation(s) in {files} files "
              "(docs/architecture.md states the rules):")
        for p in problems:
            print("  " + p)
        return 1
    print(f"check_layers: {files} files, layering and include convention respected")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
