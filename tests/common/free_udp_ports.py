#!/usr/bin/env python3
"""Finds COUNT consecutive free UDP ports on 127.0.0.1 for a test's own bus (udp:127.0.0.1:BASE),
starting from a place derived from a seed (the caller's PID) so that parallel tests rarely
collide, and skipping ranges something is bound to. Prints BASE, or exits 1.
  free_udp_ports.py COUNT SEED       (shell)
  free_port_base(count, seed)        (python, import from tests/common)"""
import socket
import sys


def free_port_base(count, seed, first=33000, slots=2000):
    for attempt in range(200):
        base = first + ((seed * 7919 + attempt * 131) % slots) * count
        socks = []
        try:
            for p in range(base, base + count):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                socks.append(s)
                s.bind(("127.0.0.1", p))
            return base
        except OSError:
            pass
        finally:
            for s in socks:
                s.close()
    return None


if __name__ == "__main__":
    base = free_port_base(int(sys.argv[1]), int(sys.argv[2]))
    if base is None:
        sys.exit("no free UDP port range on 127.0.0.1")
    print(base)
