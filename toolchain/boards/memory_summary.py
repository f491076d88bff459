#!/usr/bin/env python3
"""RAM and flash of a board-profile image, per component, against the board's budget.

Reads the image's section sizes (`size -A`), its symbols (`nm -S -C`: the encoder weights)
and the component sizes of tests/board/memory_components.cpp (`nm -S` on that object: one
curio_component_<id> array per component, sized by sizeof on the target). Prints a Markdown
table (and writes it with --markdown). --check fails when a total exceeds the budget (the
linker already refuses that) or the table misses a component it must show.

  memory_summary.py --elf IMAGE.elf --components memory_components.o --nm arm-none-eabi-nm
                    --size arm-none-eabi-size [--ram-kib 1024] [--flash-kib 2048]
                    [--markdown OUT.md] [--check]
"""
import argparse
import subprocess
import sys

LABELS = {
    "explorer": "Explorer (firmware/explore)",
    "explorer__archive": "archive",
    "explorer__archive__recipes": "θ recipes, 4 B per episode",
    "explorer__archive__outcomes": "outcomes, 10 float columns",
    "explorer__archive__pool": "θ pool (float θ of deep chains)",
    "explorer__goal_history": "goal history (one entry per exploit)",
    "explorer__frontier": "frontier grids (strategy beyond SPEC; unused by SPEC's)",
    "controller": "Controller (firmware/app)",
    "controller__capture": "capture: ISO-TP receiver + 12 KiB camera frame buffer",
    "controller__master": "CANopen master: SDO client, RX frame batch",
    "controller__cycle": "control cycle: targets, TPDO1 feedback",
    "encoder": "β-VAE encoder: activation arena (firmware/nn)",
    "bus": "CAN queues: in-image bus (stands in for the CAN driver's queues)",
    "fake_arm": "fake arm (QEMU test harness, not firmware)",
}
RAM_SECTIONS = (".data", ".bss", ".stack")
FLASH_SECTIONS = (".vectors", ".text", ".ARM.extab", ".ARM.exidx", ".init_array", ".data")
WEIGHT_NAMESPACES = ("curio::nn::beta_vae::", "curio::nn::vae::")


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def sections(size_tool, elf):
    out = {}
    for line in run([size_tool, "-A", elf]).splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[0].startswith(".") and parts[1].isdigit():
            out[parts[0]] = int(parts[1])
    return out


def symbols(nm, path, demangle):
    """(name, size, address) of every symbol nm reports with a size."""
    cmd = [nm, "-S"] + (["-C"] if demangle else []) + [path]
    rows = []
    for line in run(cmd).splitlines():
        parts = line.split(maxsplit=3)
        if len(parts) == 4:
            rows.append((parts[3], int(parts[1], 16), int(parts[0], 16)))
    return rows


def kib(n):
    return f"{n / 1024:.1f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elf", required=True)
    ap.add_argument("--components", required=True)
    ap.add_argument("--nm", required=True)
    ap.add_argument("--size", required=True)
    ap.add_argument("--ram-kib", type=int, default=1024)
    ap.add_argument("--flash-kib", type=int, default=2048)
    ap.add_argument("--ram-origin", type=lambda v: int(v, 0), default=0x20000000)
    ap.add_argument("--markdown")
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()

    sec = sections(args.size, args.elf)
    ram_total = sum(sec.get(s, 0) for s in RAM_SECTIONS)
    flash_total = sum(sec.get(s, 0) for s in FLASH_SECTIONS)
    comps = {name[len("curio_component_"):]: size
             for name, size, _ in symbols(args.nm, args.components, False)
             if name.startswith("curio_component_")}
    # The weight arrays are inline constexpr (weak 'V' symbols): count those in flash.
    weights = sum(size for name, size, address in symbols(args.nm, args.elf, True)
                  if address < args.ram_origin and name.startswith(WEIGHT_NAMESPACES))

    order = [c for c in LABELS if c in comps] + sorted(c for c in comps if c not in LABELS)
    rows = []  # (depth, label, region, bytes)

    def emit(cid, depth):
        rows.append((depth, LABELS.get(cid, cid), "RAM", comps[cid]))
        children = [c for c in order if c.startswith(cid + "__") and "__" not in c[len(cid) + 2:]]
        for c in children:
            emit(c, depth + 1)
        rest = comps[cid] - sum(comps[c] for c in children)
        if children and rest > 0:
            rows.append((depth + 1, "rest (state, counters, small tables)", "RAM", rest))

    top = [c for c in ("explorer", "controller", "encoder", "bus", "fake_arm") if c in comps]
    for c in top:
        emit(c, 0)
    stack = sec.get(".stack", 0)
    rows.append((0, "main stack (curio_sections.ld)", "RAM", stack))
    other_ram = ram_total - stack - sum(comps[c] for c in top)
    rows.append((0, "other .data/.bss (libc, test frame, scenario bookkeeping)", "RAM", other_ram))
    rows.append((0, "β-VAE encoder weights, int8 (firmware/nn/models)", "flash", weights))
    rows.append((0, "code and other constants", "flash", flash_total - weights))

    lines = ["| component | region | bytes | KiB |", "|---|---|---:|---:|"]
    for depth, label, region, n in rows:
        indent = "· " * depth
        lines.append(f"| {indent}{label} | {region} | {n:,} | {kib(n)} |")
    ram_budget, flash_budget = args.ram_kib * 1024, args.flash_kib * 1024
    lines.append(f"| **RAM total** (.data + .bss + stack) | RAM | **{ram_total:,}** | "
                 f"**{kib(ram_total)}** of {args.ram_kib} ({100 * ram_total / ram_budget:.0f} %) |")
    lines.append(f"| **flash total** (code, constants, .data image) | flash | **{flash_total:,}** | "
                 f"**{kib(flash_total)}** of {args.flash_kib} ({100 * flash_total / flash_budget:.0f} %) |")
    table = "\n".join(lines)
    print(f"memory budget of {args.elf}:")
    print(table)
    if args.markdown:
        with open(args.markdown, "w", encoding="utf-8") as f:
            f.write(table + "\n")

    if args.check:
        problems = []
        if ram_total > ram_budget:
            problems.append(f"RAM {ram_total} > {ram_budget}")
        if flash_total > flash_budget:
            problems.append(f"flash {flash_total} > {flash_budget}")
        for c in ("explorer", "explorer__archive", "controller", "encoder"):
            if comps.get(c, 0) == 0:
                problems.append(f"component {c} missing")
        if weights == 0:
            problems.append("no encoder weights in the image")
        if other_ram < 0:
            problems.append("components exceed the image's RAM (stale components object?)")
        for p in problems:
            print(f"memory_summary: {p}", file=sys.stderr)
        return 1 if problems else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
