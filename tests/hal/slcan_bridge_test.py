#!/usr/bin/env python3
"""curio-can slcan-bridge end to end on the host, without QEMU: this script plays QEMU's side
(a unix socket server, as `-serial unix:PATH,server=on`), the bridge joins it to a UDP bus,
and `curio-can dump` / `curio-can send` are the bus side. Checks both directions frame for
frame, classic and FD lines, and that a malformed line is counted, not forwarded.
  slcan_bridge_test.py CURIO_CAN WORKDIR"""
import os, socket, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from free_udp_ports import free_port_base  # noqa: E402

can, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)


port = free_port_base(3, os.getpid())
if port is None:
    sys.exit("no free UDP ports")
bus = f"udp:127.0.0.1:{port}?ports=3"
path = os.path.join(work, "uart.sock")
if os.path.exists(path):
    os.unlink(path)
server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
server.bind(path)
server.listen(1)

dump = subprocess.Popen([can, "dump", "--bus", bus, "-n", "3", "-t", "5000"], stdout=subprocess.PIPE, text=True)
time.sleep(0.2)
bridge = subprocess.Popen([can, "slcan-bridge", "--serial", "unix:" + path, "--bus", bus, "--fd"],
                          stderr=subprocess.PIPE, text=True)
server.settimeout(5)
conn, _ = server.accept()
time.sleep(0.2)
# QEMU's side → bus: two frames (classic, FD with BRS) and a malformed line between them.
conn.sendall(b"t1232AABB\rtZZZ\rB18DAF1209" + bytes("00" * 12, "ascii") + b"\rt0800\r")
out, _ = dump.communicate(timeout=10)
got = [l.split()[-1] for l in out.splitlines()]
want = ["123#AABB", "18DAF120##1" + "00" * 12, "080#"]
if got != want:
    sys.exit(f"serial → bus: got {got}, want {want}")

# Bus → QEMU's side.
subprocess.run([can, "send", "--bus", bus, "321#DEADBEEF", "2A0##0" + "11" * 48], check=True, timeout=10)
conn.settimeout(5)
data = b""
want_bytes = b"t3214DEADBEEF\rd2A0E" + b"11" * 48 + b"\r"
while len(data) < len(want_bytes):
    chunk = conn.recv(4096)
    if not chunk:
        break
    data += chunk
if data != want_bytes:
    sys.exit(f"bus → serial: got {data!r}, want {want_bytes!r}")

conn.close()  # QEMU exits: the bridge must end and report
_, err = bridge.communicate(timeout=10)
if bridge.returncode != 0:
    sys.exit(f"bridge exit {bridge.returncode}: {err}")
if "1 malformed" not in err or "serial→bus 3 frames" not in err or "bus→serial 2 frames" not in err:
    sys.exit(f"bridge statistics wrong: {err}")
print(err.strip())
print("slcan-bridge: both directions frame for frame, malformed line counted")
