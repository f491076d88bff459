#!/usr/bin/python3
"""The drives watch the controller: `curio-controller` is SIGKILLed at KILLS random moments of a
run against `curio-sim serve` (ODE), and after each kill every one of the 7 joints must send EMCY
0x8130 (it missed the controller's heartbeat), stop on its quick-stop ramp and stand still
within the consumer time plus the heartbeat period plus the ramp (plus a scheduling margin).
The time from the kill to the last joint's standstill is taken from the serve's own log lines
as they arrive; p50 and max are printed.
  drive_watchdog.py CURIO_SIM CURIO_CONTROLLER WORKDIR KILLS [BUS_URL]
BUS_URL defaults to a free UDP bus on 127.0.0.1 (socketcan:vcan0 inside User-mode Linux).
The controller keeps its defaults: heartbeat 100 ms, consumer time 500 ms, quick-stop
deceleration 1000 rad/s², maximum joint speed π rad per 10 ms period."""
import os
import random
import shutil
import signal
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from free_udp_ports import free_port_base  # noqa: E402

CONSUMER_S = 0.500
HEARTBEAT_S = 0.100
MAX_RAMP_S = 3.141593 / 0.010 / 1000.0  # the fastest joint (π per period) at 1000 rad/s²
MARGIN_S = 0.300  # log pipes and the scheduling of three processes on a loaded machine
JOINTS = 7


class ServeLog:
    """curio-sim serve's stderr, each line stamped with its arrival time."""

    def __init__(self, proc, path):
        self.lines = []
        self.cond = threading.Condition()
        self.file = open(path, "w")
        threading.Thread(target=self._read, args=(proc,), daemon=True).start()

    def _read(self, proc):
        for line in proc.stderr:
            now = time.monotonic()
            self.file.write(line)
            self.file.flush()
            with self.cond:
                self.lines.append((now, line))
                self.cond.notify_all()

    def wait_for(self, pred, count, since, timeout):
        """Until `count` lines after index `since` satisfy pred: their arrival times, or None."""
        deadline = time.monotonic() + timeout
        with self.cond:
            while True:
                hits = [t for t, l in self.lines[since:] if pred(l)]
                if len(hits) >= count:
                    return hits[:count]
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)


def main():
    if len(sys.argv) not in (5, 6):
        print(__doc__, file=sys.stderr)
        return 2
    sim, controller, work, kills = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    if len(sys.argv) == 6:
        bus = sys.argv[5]
    else:
        base = free_port_base(3, os.getpid())
        if base is None:
            print("no 3 free UDP ports on 127.0.0.1")
            return 1
        bus = f"udp:127.0.0.1:{base}?ports=3"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    rng = random.Random(os.getpid())
    serve = subprocess.Popen([sim, "serve", "--bus", bus, "--physics", "ode", "--seed", "0",
                              "--exit-after-idle", "60", "--status-every", "0"],
                             stderr=subprocess.PIPE, text=True)
    log = ServeLog(serve, os.path.join(work, "serve.log"))
    bound = CONSUMER_S + HEARTBEAT_S + MAX_RAMP_S + MARGIN_S
    times = []
    try:
        if log.wait_for(lambda l: " physics, seed " in l, 1, 0, 30) is None:
            print("FAIL: curio-sim serve did not start")
            return 1
        for k in range(kills):
            err = open(os.path.join(work, f"ctl{k}.err"), "w")
            ctl = subprocess.Popen([controller, "--bus", bus, "--seed", "0", "--episodes", "10000",
                                    "--out", os.path.join(work, f"run{k}"), "--no-journal",
                                    "--progress-every", "0.05"],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            # Under way: the first progress line (the joints enabled and moving).
            for line in ctl.stderr:
                err.write(line)
                if " episodes, ratio" in line:
                    break
            else:
                print(f"FAIL: kill {k}: the controller ended before its first episode:")
                print(open(os.path.join(work, f"ctl{k}.err")).read())
                return 1
            time.sleep(rng.uniform(0.0, 0.6))
            mark = len(log.lines)
            t_kill = time.monotonic()
            ctl.send_signal(signal.SIGKILL)
            ctl.wait()
            err.close()
            emcy = log.wait_for(lambda l: "missed" in l and "EMCY 0x8130" in l, JOINTS, mark, 5)
            still = log.wait_for(lambda l: "stood still" in l and "missed heartbeat" in l, JOINTS,
                                 mark, 5)
            if emcy is None or still is None:
                print(f"FAIL: kill {k}: not every joint sent EMCY 0x8130 and stood still; "
                      f"serve log since the kill:")
                print("".join(l for _, l in log.lines[mark:]))
                return 1
            dt = max(still) - t_kill
            times.append(dt)
            print(f"kill {k + 1}/{kills}: 7 × EMCY 0x8130, last joint still "
                  f"{dt * 1000:.0f} ms after the kill")
            if dt > bound:
                print(f"FAIL: {dt * 1000:.0f} ms is above the consumer time + period + ramp + "
                      f"margin = {bound * 1000:.0f} ms")
                return 1
    finally:
        serve.send_signal(signal.SIGINT)
        try:
            serve.wait(timeout=10)
        except subprocess.TimeoutExpired:
            serve.kill()
    times.sort()
    p50 = times[len(times) // 2]
    print(f"drive watchdog over {bus}: {kills} kills of curio-controller; from the kill to the "
          f"last joint's standstill p50 {p50 * 1000:.0f} ms, max {times[-1] * 1000:.0f} ms "
          f"(consumer time 500 ms + heartbeat period 100 ms + ramp; bound {bound * 1000:.0f} ms)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
