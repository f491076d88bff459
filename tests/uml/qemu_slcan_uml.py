#!/usr/bin/env python3
"""The launcher of tests/uml/qemu_slcan_uml.sh: the QEMU image's UART0 joined to UML's serial
line 1, like a USB-CAN adapter between a board and a Linux PC.

  qemu_slcan_uml.py IMAGE CURIO_SIM WORKDIR ALGO EPISODES SEED [EXTRA_IMAGE_ARGS]

    QEMU mps2-an500 UART0 ─chardev socket,fd=M═ socketpair ═ relay ═ socketpair ═ssl1=fd:N─
      UML /dev/ttyS1 ─slcand / N_SLCAN─► slc0 ─socketcan─► curio-sim serve (ODE arm)

1. UML starts first (tests/uml/run-in-uml.sh --serial-fd N, running qemu_slcan_uml_inside.sh)
   and writes WORKDIR/uml_ready once slc0 is up and the serve runs.
2. QEMU starts with its end of the other socketpair as UART0 (-chardev socket,id=uart,fd=M:
   QEMU 7.2 takes a connected socket there).
3. This process relays bytes between the two, and KICKS UML's line after every write of
   UML's: UML's serial line driver (arch/um/drivers/line.c, 6.1) calls tty_wakeup() only from
   its write interrupt, and that interrupt is only raised when something happens on the host
   fd (SIGIO). A write that the host socket takes at once therefore never wakes the tty, and
   the slcan line discipline, which stops its netdev queue after each frame and waits for
   write_wakeup(), sends one frame and then stalls until bytes come in on the line. The kick
   is one '\\r' sent to UML (an empty SLCAN line, which slcan ignores), only where the
   QEMU → UML stream is at a line boundary (mid-line, the rest of the line is the kick).
   QEMU_SLCAN_UML_KICK=0 turns the kicks off (shows the stall).
4. When QEMU exits, WORKDIR/qemu_done tells the UML side to stop the serve (slc0 stays up: the
   relay keeps UML's line open until UML powered off); slc0's counters land in
   WORKDIR/slc0_stats.txt.
Every process it started is stopped on any exit (each child runs in a session of its own; all
processes of that session get SIGTERM, then SIGKILL; QEMU also dies with this process).

Environment: QEMU_SLCAN_UML_TIMEOUT (seconds QEMU may run, default 1800),
QEMU_SLCAN_UML_CANDUMP (1 default: candump -L slc0 > WORKDIR/candump.log inside UML; 0: none),
QEMU_SLCAN_UML_KICK (1 default), QEMU_SLCAN_UML_TRACE (1: every line with its time and
direction in WORKDIR/line.trace).
Exit: 0 when the image passed (exit 0 and an archive checksum); 1 on failure; 77 when UML
cannot boot on this host (run-in-uml.sh's 125 before the UML side was ready).
"""
import ctypes
import os
import re
import select
import signal
import socket
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
RUN_IN_UML = os.path.join(HERE, "run-in-uml.sh")
INSIDE = os.path.join(HERE, "qemu_slcan_uml_inside.sh")
UML_READY_TIMEOUT_S = 180


def session_pids(sid):
    """Pids of all live processes whose session id is `sid` (ours excluded)."""
    out = []
    for name in os.listdir("/proc"):
        if not name.isdigit() or int(name) == os.getpid():
            continue
        try:
            with open(f"/proc/{name}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        fields = stat[stat.rfind(")") + 2:].split()
        if len(fields) > 3 and int(fields[3]) == sid and fields[0] != "Z":
            out.append(int(name))
    return out


def stop_session(proc, name):
    """SIGTERM to every process of `proc`'s session, SIGKILL to what is left after 5 s."""
    if proc is None:
        return
    sid = proc.pid
    for sig, grace in ((signal.SIGTERM, 5.0), (signal.SIGKILL, 2.0)):
        pids = session_pids(sid)
        if proc.poll() is None and proc.pid not in pids:
            pids.append(proc.pid)
        if not pids:
            return
        for pid in pids:
            try:
                os.kill(pid, sig)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + grace
        while time.monotonic() < deadline:
            proc.poll()
            if not session_pids(sid):
                return
            time.sleep(0.1)
    left = session_pids(sid)
    if left:
        print(f"qemu_slcan_uml: {name}: processes {left} did not stop", file=sys.stderr)


def die_with_parent():
    """preexec_fn: SIGKILL when the launcher dies (QEMU only: it holds no state of ours)."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


TERMINATORS = b"\r\n\a"


class Relay:
    """Bytes both ways between UML's line (`uml`) and QEMU's UART (`qemu`), with kicks."""

    def __init__(self, uml, qemu, kick, trace):
        self.uml, self.qemu = uml, qemu
        uml.setblocking(False)
        qemu.setblocking(False)
        self.kick, self.trace = kick, trace
        self.to_uml, self.to_qemu = bytearray(), bytearray()
        self.q2u_boundary = True  # the last byte queued to UML ends a line
        self.uml_open = self.qemu_open = True
        self.lines = {"q2u": 0, "u2q": 0}
        self.bytes = {"q2u": 0, "u2q": 0}
        self.first = {}
        self.last = {}
        self.kicks = 0
        self.partial = {"q2u": bytearray(), "u2q": bytearray()}
        self.t0 = time.monotonic()

    def _account(self, direction, data):
        now = time.monotonic()
        self.bytes[direction] += len(data)
        n = sum(data.count(bytes([t])) for t in TERMINATORS)
        if n:
            self.lines[direction] += n
            self.first.setdefault(direction, now)
            self.last[direction] = now
        if self.trace:
            buf = self.partial[direction] + data
            start = 0
            for i, c in enumerate(buf):
                if c in TERMINATORS:
                    if i > start:
                        self.trace.write(f"{now - self.t0:.6f} {direction} "
                                         f"{buf[start:i].decode('ascii', 'replace')}\n")
                    start = i + 1
            self.partial[direction] = bytearray(buf[start:])

    def step(self, timeout):
        rl = [s for s, o in ((self.uml, self.uml_open), (self.qemu, self.qemu_open)) if o]
        wl = []
        if self.uml_open and self.to_uml:
            wl.append(self.uml)
        if self.qemu_open and self.to_qemu:
            wl.append(self.qemu)
        if not rl and not wl:
            time.sleep(timeout)
            return
        r, w, _ = select.select(rl, wl, [], timeout)
        if self.uml in r:
            data = self._recv(self.uml)
            if data is None:
                self.uml_open = False
            elif data:
                self._account("u2q", data)
                if self.qemu_open:
                    self.to_qemu += data
                if self.kick and self.q2u_boundary:
                    self.to_uml += b"\r"
                    self.kicks += 1
        if self.qemu in r:
            data = self._recv(self.qemu)
            if data is None:
                self.qemu_open = False
                self.to_qemu.clear()
            elif data:
                self._account("q2u", data)
                self.to_uml += data
                self.q2u_boundary = data[-1] in TERMINATORS
        for sock, buf, name in ((self.uml, self.to_uml, "uml"), (self.qemu, self.to_qemu, "qemu")):
            if buf:
                try:
                    n = sock.send(buf)
                    del buf[:n]
                except BlockingIOError:
                    pass
                except OSError:
                    buf.clear()
                    if name == "uml":
                        self.uml_open = False
                    else:
                        self.qemu_open = False

    @staticmethod
    def _recv(sock):
        """Bytes read; b"" when none now; None at EOF or error."""
        try:
            data = sock.recv(65536)
        except BlockingIOError:
            return b""
        except OSError:
            return None
        return data if data else None

    def run_until(self, done, deadline):
        """Relays until done() or the monotonic deadline; True when done() came first."""
        while time.monotonic() < deadline:
            if done():
                return True
            self.step(0.05)
        return done()

    def rate(self, direction):
        if direction not in self.first or self.last[direction] <= self.first[direction]:
            return 0.0
        return self.lines[direction] / (self.last[direction] - self.first[direction])


def slc0_counts(path):
    """(rx_frames, rx_bytes, tx_frames, tx_bytes, rx_dropped, tx_dropped) from `ip -s link`."""
    try:
        text = open(path).read()
    except OSError:
        return None
    m = re.search(r"RX:.*\n\s*(\d+)\s+(\d+)\s+(\d+)\s+(\d+).*\n\s*TX:.*\n\s*(\d+)\s+(\d+)\s+(\d+)\s+(\d+)",
                  text)
    if not m:
        return None
    v = [int(x) for x in m.groups()]
    return v[1], v[0], v[5], v[4], v[3], v[7]


def tail(path, n):
    try:
        lines = open(path, errors="replace").read().splitlines()
    except OSError:
        return ""
    return "\n".join(lines[-n:])


def main():
    if len(sys.argv) < 7:
        print(__doc__, file=sys.stderr)
        return 2
    image, sim, work, algo, episodes, seed = sys.argv[1:7]
    extra = sys.argv[7] if len(sys.argv) > 7 else ""
    qemu_timeout = float(os.environ.get("QEMU_SLCAN_UML_TIMEOUT", "1800"))
    candump = os.environ.get("QEMU_SLCAN_UML_CANDUMP", "1")
    kick = os.environ.get("QEMU_SLCAN_UML_KICK", "1") != "0"
    trace = open(os.path.join(work, "line.trace"), "w") \
        if os.environ.get("QEMU_SLCAN_UML_TRACE", "0") == "1" else None
    image_args = f"arg=algo={algo},arg=seed={seed},arg=episodes={episodes}"
    if extra:
        image_args += "," + extra.strip(",")

    uml = qemu = None
    ok = False

    def on_signal(signum, _frame):
        print(f"qemu_slcan_uml: signal {signum}, stopping QEMU and UML", file=sys.stderr)
        raise SystemExit(128 + signum)

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGHUP, on_signal)
    try:
        uml_line, uml_relay = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
        qemu_uart, qemu_relay = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
        relay = Relay(uml_relay, qemu_relay, kick, trace)
        t_uml = time.monotonic()
        with open(os.path.join(work, "uml.out"), "wb") as out, \
                open(os.path.join(work, "uml.err"), "wb") as err:
            uml = subprocess.Popen(
                [RUN_IN_UML, "--rw", work, "--serial-fd", str(uml_line.fileno()),
                 "--timeout", str(int(qemu_timeout + UML_READY_TIMEOUT_S + 120)), "--",
                 INSIDE, sim, work, seed, candump],
                pass_fds=[uml_line.fileno()], stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                start_new_session=True)
        uml_line.close()
        ready = os.path.join(work, "uml_ready")
        if not relay.run_until(lambda: os.path.exists(ready) or uml.poll() is not None,
                               time.monotonic() + UML_READY_TIMEOUT_S) or not os.path.exists(ready):
            rc = uml.poll()
            print(f"qemu_slcan_uml: the UML side did not come up (run-in-uml.sh exit {rc})")
            print(tail(os.path.join(work, "uml.out"), 30))
            print(tail(os.path.join(work, "uml.err"), 30))
            if rc == 125:
                print("SKIP: UML cannot run here")
                return 77
            return 1
        uml_up_s = time.monotonic() - t_uml

        t0 = time.monotonic()
        with open(os.path.join(work, "qemu.log"), "wb") as log:
            qemu = subprocess.Popen(
                ["qemu-system-arm", "-M", "mps2-an500", "-nographic", "-monitor", "none",
                 "-semihosting-config", f"enable=on,target=native,{image_args}",
                 "-chardev", f"socket,id=uart,fd={qemu_uart.fileno()}", "-serial", "chardev:uart",
                 "-kernel", image],
                pass_fds=[qemu_uart.fileno()], stdin=subprocess.DEVNULL, stdout=log,
                stderr=subprocess.STDOUT, start_new_session=True, preexec_fn=die_with_parent)
        qemu_uart.close()
        relay.run_until(lambda: qemu.poll() is not None, t0 + qemu_timeout)
        qemu_rc = qemu.poll()
        qemu_s = time.monotonic() - t0
        open(os.path.join(work, "qemu_done"), "w").close()
        relay.run_until(lambda: uml.poll() is not None, time.monotonic() + 60)
        uml_rc = uml.poll()
        if trace:
            trace.close()

        qlog = open(os.path.join(work, "qemu.log"), errors="replace").read()
        sys.stdout.write(qlog)
        print("--- UML side (curio-sim serve on slc0)")
        print(tail(os.path.join(work, "serve.log"), 20))
        print(tail(os.path.join(work, "uml.err"), 20))
        print(f"UML up in {uml_up_s:.1f} s; QEMU ran {qemu_s:.1f} s "
              f"(exit {'timeout' if qemu_rc is None else qemu_rc}); "
              f"UML side exit {'timeout' if uml_rc is None else uml_rc}")
        print(f"line: image -> UML {relay.lines['q2u']} lines ({relay.bytes['q2u']} B, "
              f"{relay.rate('q2u'):.0f} lines/s), UML -> image {relay.lines['u2q']} lines "
              f"({relay.bytes['u2q']} B, {relay.rate('u2q'):.0f} lines/s), {relay.kicks} kicks")
        counts = slc0_counts(os.path.join(work, "slc0_stats.txt"))
        if counts:
            rx, rxb, tx, txb, rxd, txd = counts
            print(f"slc0: {rx} frames from the image ({rxb} B data, {rxd} dropped), {tx} to it "
                  f"({txb} B data, {txd} dropped); {(rx + tx) / qemu_s:.0f} frames/s both ways "
                  f"over the {qemu_s:.1f} s QEMU run")
        cd = os.path.join(work, "candump.log")
        if os.path.exists(cd):
            n = sum(1 for _ in open(cd, errors="replace"))
            print(f"candump -L slc0: {n} frames in {cd}")
        if qemu_rc is None:
            print(f"FAIL: QEMU did not finish in {qemu_timeout:.0f} s")
        elif qemu_rc != 0:
            print(f"FAIL: the image exited {qemu_rc}")
        elif not re.search(r"archive checksum 0x[0-9a-f]+", qlog):
            print("FAIL: no archive checksum in the image's log")
        elif uml_rc != 0:
            print(f"FAIL: the UML side exited {uml_rc}")
            print(tail(os.path.join(work, "uml.out"), 30))
        else:
            ok = True
            print(f"PASS: {algo} seed {seed} over QEMU UART <-> UML slcan (slc0)")
        return 0 if ok else 1
    finally:
        stop_session(qemu, "QEMU")
        stop_session(uml, "UML")


if __name__ == "__main__":
    sys.exit(main())
