#!/usr/bin/python3
"""Checks firmware/protocol/curio.dbc against Curio's C++ encoders.

Runs DUMP (tests/hal/dbc_dump), which prints frames made by the encoders and the signal values
they must carry, decodes each frame with canmatrix (Debian python3-canmatrix) and the DBC, and
fails on any difference: unknown id, wrong length, FD flag, signal value. Also fails if the DBC
describes a message that no encoder produced (the DBC documents exactly what we send).

usage: check_dbc.py DBC DUMP"""
import decimal
import json
import subprocess
import sys

try:
    import canmatrix.formats
    from canmatrix import ArbitrationId
except ImportError:
    print("check_dbc: needs the Debian package python3-canmatrix", file=sys.stderr)
    sys.exit(2)

# Variable-length transport frames (last CF padded shorter), FD in the FD profile and classic
# (8 bytes) in the classic profile: the DBC gives the FD size and format.
ISOTP_IDS = {0x18DAF120, 0x18DA20F1}


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    db = canmatrix.formats.loadp_flat(sys.argv[1])
    dump = json.loads(subprocess.run([sys.argv[2]], check=True, capture_output=True, text=True).stdout)
    errors = []
    seen = set()
    checked = 0
    for f in dump["frames"]:
        fid = ArbitrationId(f["id"], extended=f["extended"])
        msg = db.frame_by_id(fid)
        where = f"0x{f['id']:X} ({f['data']})"
        if msg is None:
            errors.append(f"{where}: id not in the DBC")
            continue
        seen.add(msg.name)
        if f["id"] in ISOTP_IDS:
            if f["len"] > msg.size:
                errors.append(f"{msg.name}: frame length {f['len']} > DBC size {msg.size}")
        elif f["len"] != msg.size:
            errors.append(f"{msg.name}: frame length {f['len']} != DBC size {msg.size}")
        if f["id"] in ISOTP_IDS and not f["fd"]:
            if f["len"] != 8:
                errors.append(f"{msg.name}: a classic ISO-TP frame of {f['len']} bytes, not 8")
        elif bool(msg.is_fd) != f["fd"]:
            errors.append(f"{msg.name}: FD flag {f['fd']} but DBC says {msg.is_fd}")
        data = bytes.fromhex(f["data"])
        data = data + bytes(max(0, msg.size - len(data)))
        decoded = msg.decode(data)
        for name, expect in f["signals"].items():
            if name not in decoded:
                errors.append(f"{msg.name}: DBC has no signal {name}")
                continue
            got = decoded[name]
            if isinstance(expect, dict):  # scaled: raw counts and physical value
                if got.raw_value != expect["raw"]:
                    errors.append(f"{msg.name}.{name}: raw {got.raw_value} != {expect['raw']}")
                if float(got.phys_value) != expect["phys"]:
                    errors.append(f"{msg.name}.{name}: phys {got.phys_value} != {expect['phys']!r}")
            elif isinstance(expect, float):
                if float(got.raw_value) != expect:
                    errors.append(f"{msg.name}.{name}: {got.raw_value!r} != {expect!r}")
            elif got.raw_value != expect:
                errors.append(f"{msg.name}.{name}: {got.raw_value} != {expect}")
            checked += 1
    unused = sorted(m.name for m in db.frames if m.name not in seen)
    if unused:
        errors.append("DBC messages no encoder produced: " + ", ".join(unused))
    for e in errors:
        print("check_dbc:", e)
    print(f"check_dbc: {len(dump['frames'])} frames, {checked} signals, {len(db.frames)} DBC "
          f"messages, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    decimal.getcontext().prec = 40
    sys.exit(main())
