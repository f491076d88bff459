#!/usr/bin/env python3
"""Checks Curio's layering and include convention (docs/architecture.md, "What each layer may
include"). Exits 1 and names every offending line; 0 when the tree is clean.

usage: check_layers.py [REPO_DIR]      check a tree (default: this script's repository)
       check_layers.py --self-test     prove the checker catches each kind of violation

Rules, for every C/C++ file the repository holds:
  1. Project headers are included by their path from the repository root, in quotes
     ("firmware/explore/archive.hpp", "hal/can_bus.hpp"); the one other root is the build's
     generated/ folder, which mirrors the tree (so the path still names a source folder).
  2. firmware/, hal/*.{hpp,cpp} (the firmware-clean interfaces), hal/slcan/ (the SLCAN bus)
     and hal/mps2/ (the QEMU board's drivers) include only firmware/ and hal/*.hpp (hal/slcan/
     and hal/mps2/ also their own headers), and from the C/C++ library only freestanding-safe headers (FIRMWARE_SYSTEM):
     no OS headers, no <vector>/<string>/<iostream>, no allocation-based containers.
  3. hal/ (its host/ and linux/ backends) does not include sim/, host_tools/ or tests/.
  4. sim/'s library (every file under sim/ outside curio-sim's program folders, today the files
     directly in sim/) includes neither host_tools/ nor tests/. curio-sim's program folders
     (SIM_PROGRAM_FOLDERS: sim/cli/, sim/serve/) include no tests/ and, from host_tools/, only
     the shared layers (HOST_SHARED), never a host program's folder.
  5. Nothing outside tests/ includes tests/.
  The host wing (host_tools/<folder>/, the folder being the first one under host_tools/):
  6. A program's folder (HOST_PROGRAMS) includes, from host_tools/, only itself and the
     shared layers (HOST_SHARED): no program includes another program's folder.
  7. A shared layer includes no program's folder.
  8. Every folder under host_tools/ is either a program or a shared layer (a new folder is
     named in one list or the other here, and in docs/architecture.md).
  9. No include cycle between folders anywhere in the tree: a folder that includes another is
     above it, and the two never include each other, directly or through a third. A folder is
     the file's own folder (hal/ and hal/linux/ are two), except in the host wing, where it is
     the first folder under host_tools/. So sim/ (the library) and sim/cli/ are two folders:
     host_tools/cli/ may include sim/ while sim/cli/ includes host_tools/cli/.
  10. No file outside a program's folder includes that program's folder: a program's folder is
     host_tools/<program>/ (HOST_PROGRAMS) or, for curio-sim, sim/cli/ and sim/serve/ together
     (sim/cli/ may include sim/serve/; sim/'s library and host_tools/ include neither). tests/
     may include anything. (Lines that rules 4, 6 or 7 already name are not named again.)
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
# The host wing's folders (docs/architecture.md, "Host layers"). Programs build one executable
# each; shared layers are what several programs build on.
HOST_PROGRAMS = {"can_tools", "controller", "encode", "lab", "online", "python", "quantize", "train"}
HOST_SHARED = {"cli", "common", "experiment", "journal", "model_io", "vae"}
# curio-sim's program folders: its commands (cli/) and the arm as CAN nodes behind
# `curio-sim serve` (serve/). The rest of sim/ is the library every program may include.
SIM_PROGRAM_FOLDERS = ("sim/cli/", "sim/serve/")
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
    # A tracked file deleted in the work tree is not part of the tree being checked.
    return sorted(p for p in out if p.endswith(SOURCE_EXT) and not p.startswith("build/") and
                  os.path.exists(os.path.join(repo, p)))


def is_firmware_clean(path):
    return (path.startswith("firmware/") or path.startswith("hal/mps2/") or
            path.startswith("hal/slcan/") or (path.startswith("hal/") and path.count("/") == 1))


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
        already = len(problems)
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
                                     target.startswith("hal/mps2/")) or
                                    (path.startswith("hal/slcan/") and
                                     target.startswith("hal/slcan/"))):
                problems.append(f"{where}: firmware code includes only firmware/ and hal/*.hpp "
                                "(rule 2)")
        elif path.startswith("hal/"):
            if kind == '"' and target.startswith(("sim/", "host_tools/", "tests/")):
                problems.append(f"{where}: hal/ may not include {target.split('/')[0]}/ (rule 3)")
        elif path.startswith("sim/"):
            if kind == '"':
                problems += check_sim_include(path, target, where)
        if not path.startswith("tests/") and kind == '"' and target.startswith("tests/"):
            problems.append(f"{where}: only tests/ may include tests/ (rule 5)")
        if kind == '"':
            problems += check_host_include(path, target, where)
        if kind == '"' and len(problems) == already and not path.startswith("tests/"):
            problems += check_program_include(path, target, where)
    return problems


def check_sim_include(path, target, where):
    """Rule 4: sim/'s library includes no host_tools/ or tests/; curio-sim's program folders
    include no tests/ and only the shared layers of host_tools/."""
    if target.startswith("tests/"):
        return [f"{where}: sim/ may not include tests/ (rule 4)"]
    if not target.startswith("host_tools/"):
        return []
    if not path.startswith(SIM_PROGRAM_FOLDERS):
        return [f"{where}: sim/'s library may not include host_tools/ (only curio-sim's program "
                f"folders {', '.join(SIM_PROGRAM_FOLDERS)} include its shared layers) (rule 4)"]
    included = host_folder(target)
    if included not in HOST_SHARED:
        return [f"{where}: {path.split('/')[0]}/{path.split('/')[1]}/ is curio-sim's program "
                f"folder; from host_tools/ it includes only the shared layers "
                f"({', '.join(sorted(HOST_SHARED))}), not host_tools/{included}/ (rule 4)"]
    return []


def program_of(path):
    """The program whose folder a path is in ("host_tools/lab", or "curio-sim" for sim/cli/ and
    sim/serve/), or None outside every program's folder."""
    if path.startswith(SIM_PROGRAM_FOLDERS):
        return "curio-sim"
    folder = host_folder(path)
    return f"host_tools/{folder}" if folder in HOST_PROGRAMS else None


def check_program_include(path, target, where):
    """Rule 10: only a program's own folder (and tests/) includes that program's folder."""
    owner = program_of(target)
    if owner is None or owner == program_of(path):
        return []
    folder = "/".join(target.split("/")[:2]) + "/"
    what = "curio-sim's program folder" if owner == "curio-sim" else "a program's folder"
    return [f"{where}: {folder} is {what}; nothing outside it (but tests/) includes it "
            "(rule 10)"]


def host_folder(path):
    """The host_tools folder a path is in ("lab" for host_tools/lab/run.cpp), or None."""
    parts = path.split("/")
    return parts[1] if len(parts) > 2 and parts[0] == "host_tools" else None


def check_host_include(path, target, where):
    source, included = host_folder(path), host_folder(target)
    if source is None or included is None or source == included:
        return []
    if source in HOST_PROGRAMS and included not in HOST_SHARED:
        return [f"{where}: host_tools/{source}/ is a program; it includes only itself and the "
                f"shared layers ({', '.join(sorted(HOST_SHARED))}), not host_tools/{included}/ "
                "(rule 6)"]
    if source in HOST_SHARED and included in HOST_PROGRAMS:
        return [f"{where}: host_tools/{source}/ is a shared layer; it may not include the "
                f"program folder host_tools/{included}/ (rule 7)"]
    return []


def check_host_folders(paths):
    """Rule 8: every host_tools folder holding sources is classified."""
    problems = []
    for folder in sorted({host_folder(p) for p in paths} - {None}):
        if folder not in HOST_PROGRAMS | HOST_SHARED:
            first = min(p for p in paths if host_folder(p) == folder)
            problems.append(f"{first}: host_tools/{folder}/ is neither a program (HOST_PROGRAMS) "
                            "nor a shared layer (HOST_SHARED) (rule 8)")
    return problems


def folder_cycles(edges):
    """The strongly connected components of more than one folder (Tarjan, iterative)."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []
    counter = 0
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.add(member)
                    if member == node:
                        break
                if len(component) > 1:
                    components.append(component)
    return components


def include_unit(path):
    """The folder rule 9 sees a file in: host_tools/<first folder> in the host wing, else the
    file's own folder (a generated/ header counts as the source folder it mirrors)."""
    if path.startswith("generated/"):
        path = path[len("generated/"):]
    host = host_folder(path)
    return f"host_tools/{host}" if host else os.path.dirname(path)


def check_cycles(repo, paths):
    """Rule 9: the first include of each folder-to-folder edge inside a cycle."""
    edges, first_line = {}, {}
    for path in paths:
        source = include_unit(path)
        try:
            lines = open(os.path.join(repo, path), encoding="utf-8", errors="replace").readlines()
        except OSError:
            continue
        for n, line in enumerate(lines, 1):
            m = INCLUDE.match(line)
            if not m or m.group(1) != '"':
                continue
            included = include_unit(m.group(2))
            if included == source:
                continue
            edges.setdefault(source, set()).add(included)
            first_line.setdefault((source, included), f"{path}:{n}: #include \"{m.group(2)}\"")
    problems = []
    for component in folder_cycles(edges):
        names = ", ".join(f"{f}/" for f in sorted(component))
        for (source, included), where in sorted(first_line.items()):
            if source in component and included in component:
                problems.append(f"{where}: include cycle between the folders {names} (rule 9)")
    return problems


# Headers made at build time (rule 1's generated/ root): the path they are included by.
GENERATED = {"tests/nn/synthetic_weights.hpp"}


def check(repo):
    problems = []
    paths = tracked_sources(repo)
    for path in paths:
        problems += check_file(repo, path, GENERATED)
    problems += check_host_folders(paths)
    problems += check_cycles(repo, paths)
    return problems


def self_test():
    # (file, text, the rule its violation breaks; None: a clean file).
    cases = [
        ("firmware/explore/ok.hpp", '#include <cstdint>\n#include "hal/can_bus.hpp"\n', None),
        ("hal/can_bus.hpp", "#include <cstdint>\n", None),
        ("firmware/explore/bad_os.cpp", "#include <unistd.h>\n", 2),
        ("firmware/explore/bad_vector.cpp", "#include <vector>\n", 2),
        ("firmware/explore/bad_host.cpp", '#include "host_tools/lab/run.hpp"\n', 2),
        ("firmware/explore/bad_linux.cpp", '#include "hal/linux/udp_bus.hpp"\n', 2),
        ("firmware/explore/bad_sim.cpp", '#include "sim/world.hpp"\n', 2),
        ("firmware/explore/bad_relative.cpp", '#include "ok.hpp"\n', 1),
        ("sim/bad_lab.cpp", '#include "host_tools/lab/run.hpp"\n', 4),
        ("hal/linux/bad_sim.cpp", '#include "sim/world.hpp"\n', 3),
        ("host_tools/lab/bad_test.cpp", '#include "tests/app/util.hpp"\n', 5),
        ("host_tools/lab/run.hpp", '#include "host_tools/experiment/spec.hpp"\n', None),
        ("host_tools/lab/main.cpp",
         '#include "host_tools/lab/run.hpp"\n#include "host_tools/common/gnuplot.hpp"\n', None),
        ("host_tools/experiment/spec.hpp", '#include "host_tools/common/gnuplot.hpp"\n', None),
        ("host_tools/common/gnuplot.hpp", "", None),
        # A program includes another program's folder (the controller the lab's).
        ("host_tools/controller/bad_sideways.cpp", '#include "host_tools/lab/run.hpp"\n', 6),
        # A program includes a folder that is no shared layer.
        ("host_tools/controller/bad_unlisted.cpp", '#include "host_tools/gadgets/g.hpp"\n', 6),
        # A shared layer includes a program's folder.
        ("host_tools/experiment/bad_upward.cpp", '#include "host_tools/train/trainer.hpp"\n', 7),
        ("host_tools/train/trainer.hpp", "", None),
        # A folder that is neither a program nor a shared layer.
        ("host_tools/gadgets/bad_unclassified.hpp", "", 8),
        ("host_tools/gadgets/g.hpp", "", None),
        # Two shared layers that include each other: a cycle.
        ("host_tools/journal/bad_cycle.hpp", '#include "host_tools/model_io/bad_cycle.hpp"\n', 9),
        ("host_tools/model_io/bad_cycle.hpp", '#include "host_tools/journal/bad_cycle.hpp"\n', 9),
        # Two folders outside the host wing that include each other: a cycle.
        ("sim/cli/bad_cycle.cpp", '#include "sim/serve/bad_cycle.hpp"\n', 9),
        ("sim/serve/bad_cycle.hpp", '#include "sim/cli/options.hpp"\n', 9),
        ("sim/cli/options.hpp", "", None),
        ("hal/linux/udp_bus.hpp", "", None),
        ("sim/world.hpp", "", None),
        ("tests/app/util.hpp", "", None),
        # sim/'s library includes not even a shared layer; curio-sim's program folders include
        # the shared layers (cli/) but no host program's folder and no unclassified folder.
        ("sim/bad_cli.cpp", '#include "host_tools/cli/command_line.hpp"\n', 4),
        ("sim/serve/bad_program.cpp", '#include "host_tools/train/trainer.hpp"\n', 4),
        ("sim/cli/bad_unlisted.cpp", '#include "host_tools/gadgets/g.hpp"\n', 4),
        ("sim/cli/ok_shared.cpp", '#include "host_tools/cli/command_line.hpp"\n', None),
        ("host_tools/cli/command_line.hpp", "", None),
        # curio-sim's program folders are included by nothing outside them but tests/: not by
        # a host program, a shared layer, sim/'s library or any other folder.
        ("host_tools/controller/bad_sim_program.cpp", '#include "sim/serve/arm_nodes.hpp"\n', 10),
        ("host_tools/experiment/bad_sim_program.hpp", '#include "sim/cli/options.hpp"\n', 10),
        ("sim/bad_program.cpp", '#include "sim/serve/arm_nodes.hpp"\n', 10),
        ("toolchain/bad_program.cpp", '#include "host_tools/lab/run.hpp"\n', 10),
        ("tests/app/ok_serve.cpp", '#include "sim/serve/arm_nodes.hpp"\n', None),
        ("sim/serve/arm_nodes.hpp", "", None),
    ]
    # The shape of the command-line layer, in a tree of its own (the cases above would close
    # cycles through it): host_tools/cli/ includes sim/'s library, curio-sim's folders include
    # host_tools/cli/ and each other's serve/, the controller the library's world identity, and
    # no rule flags any of it: sim/ and sim/cli/ are two folders, so rule 9 sees no cycle.
    cli_layer = [
        ("sim/world.hpp", "", None),
        ("sim/world_identity.hpp", '#include "sim/world.hpp"\n', None),
        ("host_tools/cli/world_options.hpp", '#include "sim/world.hpp"\n', None),
        ("host_tools/cli/command_line.hpp", '#include "host_tools/cli/world_options.hpp"\n', None),
        ("sim/serve/arm_nodes.hpp",
         '#include "host_tools/cli/command_line.hpp"\n#include "sim/world_identity.hpp"\n', None),
        ("sim/cli/main.cpp", '#include "host_tools/cli/command_line.hpp"\n'
         '#include "sim/serve/arm_nodes.hpp"\n#include "sim/world.hpp"\n', None),
        ("host_tools/controller/arm_world.cpp",
         '#include "host_tools/cli/world_options.hpp"\n#include "sim/world_identity.hpp"\n', None),
        ("host_tools/lab/main.cpp", '#include "host_tools/cli/command_line.hpp"\n', None),
        ("tests/app/world_identity_test.cpp", '#include "host_tools/controller/arm_world.cpp"\n'
         '#include "sim/serve/arm_nodes.hpp"\n', None),
    ]
    failures = []
    for tree in (cases, cli_layer):
        with tempfile.TemporaryDirectory() as d:
            for rel, text, _ in tree:
                os.makedirs(os.path.dirname(os.path.join(d, rel)), exist_ok=True)
                with open(os.path.join(d, rel), "w") as f:
                    f.write(text)
            problems = check(d)
        for rel, _, rule in tree:
            mine = [p for p in problems if p.split(":")[0] == rel]
            if rule is None and mine:
                failures.append(f"{rel}: clean, but flagged: {mine}")
            elif rule is not None and not any(f"(rule {rule})" in p for p in mine):
                failures.append(f"{rel}: breaks rule {rule}, flagged: {mine or 'not at all'}")
    if failures:
        print("check_layers self-test FAILED")
        for f in failures:
            print("  " + f)
        return 1
    rules = sorted({rule for _, _, rule in cases if rule is not None})
    bad = sum(1 for _, _, rule in cases if rule is not None)
    print(f"check_layers self-test: all {bad} violations caught, each by its rule "
          f"({', '.join(map(str, rules))}); clean files pass")
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
