"""Shared by the tests of docs/online/*.py: where the repository is, how to run a script and read
the markdown table it prints, and named checks that print ok/FAIL and set the exit status."""
import os, subprocess, sys

root = sys.argv[1] if len(sys.argv) > 1 else os.getcwd()
results = os.path.join(root, "docs/online/results")
failures = []


def script(name):
    return os.path.join(root, "docs/online", name)


def table(name, *args):
    """(stdout, the table's body rows as lists of cells) of docs/online/<name> run with args."""
    out = subprocess.run([sys.executable, script(name), *args], capture_output=True, text=True, check=True).stdout
    lines = [l for l in out.splitlines() if l.startswith("| ")]
    return out, [[c.strip() for c in l.strip("|").split("|")] for l in lines[1:] if not l.startswith("|---")]


def check(what, cond):
    if not cond:
        failures.append(what)
    print(("ok   " if cond else "FAIL ") + what)


def finish():
    sys.exit(1 if failures else 0)
