#!/usr/bin/python3
"""Runs every ctest test carrying LABEL in BUILD_DIR, one by one, without ctest's own log files
(an outer ctest may be writing them). Meant to run inside User-mode Linux:
    tests/uml/run-in-uml.sh -- /usr/bin/python3 tests/uml/run_labelled.py BUILD_DIR vcan
Exit status 0 only if every test passed; prints one line per test and a summary."""
import json
import os
import subprocess
import sys
import time


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    build, label = sys.argv[1], sys.argv[2]
    listing = subprocess.run(["ctest", "--test-dir", build, "-N", "-L", f"^{label}$",
                              "--show-only=json-v1"], capture_output=True, text=True)
    if listing.returncode != 0:
        print(listing.stderr, file=sys.stderr)
        return 2
    tests = json.loads(listing.stdout).get("tests", [])
    if not tests:
        print(f"run_labelled: no tests labelled '{label}' in {build}", file=sys.stderr)
        return 2
    failed, skipped = [], []
    t0 = time.monotonic()
    for t in tests:
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        env = dict(os.environ)
        for kv in props.get("ENVIRONMENT", []):
            k, _, v = kv.partition("=")
            env[k] = v
        start = time.monotonic()
        r = subprocess.run(t["command"], cwd=props.get("WORKING_DIRECTORY", build), env=env,
                           capture_output=True, text=True, timeout=props.get("TIMEOUT", 300))
        dt = time.monotonic() - start
        out = r.stdout + r.stderr
        status = "PASS"
        if r.returncode != 0:
            status = "FAIL"
            failed.append(t["name"])
        elif "[  SKIPPED ]" in out:
            status = "SKIP"
            skipped.append(t["name"])
        print(f"{status} {t['name']} ({dt:.2f} s)", flush=True)
        if status == "FAIL":
            print(out)
    print(f"run_labelled {label}: {len(tests) - len(failed) - len(skipped)} passed, "
          f"{len(skipped)} skipped, {len(failed)} failed in {time.monotonic() - t0:.1f} s")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
