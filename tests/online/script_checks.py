"""Shared by the tests of the online analysis scripts (host_tools/online/analysis/*.py): where the
repository, the scripts, the committed compact tables and the test fixtures are, how to run a
script and read the markdown table it prints, and named checks that print ok/FAIL and set the
exit status.

The fixtures (tests/online/fixtures/) are two finished runs of the campaign, gs seed 3 (final
model round 6) and r500 seed 0 (round 12), reduced to the files the scripts read: summary.json,
curves.csv, the final model's codes table (codes.py's output) and the retrain reports trimmed to
the fields read (round, episode, training seconds, own-image ball latents, loaded_from_checkpoint).
"""
import os, subprocess, sys

root = sys.argv[1] if len(sys.argv) > 1 else os.getcwd()
results = os.path.join(root, "docs/online/results")
fixtures = os.path.join(root, "tests/online/fixtures")
failures = []


def script(name):
    return os.path.join(root, "host_tools/online/analysis", name)


def run(name, *args):
    """The finished process of host_tools/online/analysis/<name> run with args (not checked)."""
    return subprocess.run([sys.executable, script(name), *args], capture_output=True, text=True)


def table(name, *args):
    """(stdout, the table's body rows as lists of cells) of host_tools/online/analysis/<name> run with args."""
    p = run(name, *args)
    if p.returncode != 0:
        raise SystemExit("%s %s failed (%d): %s" % (name, " ".join(args), p.returncode, p.stderr))
    lines = [l for l in p.stdout.splitlines() if l.startswith("| ")]
    return p.stdout, [[c.strip() for c in l.strip("|").split("|")] for l in lines[1:] if not l.startswith("|---")]


def check(what, cond):
    if not cond:
        failures.append(what)
    print(("ok   " if cond else "FAIL ") + what)


def finish():
    sys.exit(1 if failures else 0)
