#!/usr/bin/env python3
"""The command-line convention of Curio's programs (README, "Command-line convention"), checked
on every program that was built: for each program, and each subcommand listed below, an unknown
option, a number option without its value, a malformed number and a number out of range must
  - exit with 2,
  - print exactly one line on stderr that names the option and points to --help,
  - print nothing on stdout and write nothing: each case runs in an empty folder (its cwd, and
    the --out of the programs that take one) that must still be empty afterwards.
The same for a malformed value that is not a number (a bus URL that does not parse, an empty
--out, an output file that names a folder).
`--help` must exit 0 with the usage on stdout.

  cli_convention.py NAME=PATH...    e.g. curio-sim=build/default/sim/curio-sim
Programs not given (not built: curio-train and curio-online need LibTorch) are skipped."""
import concurrent.futures
import os
import subprocess
import sys
import tempfile

OUT = "{out}"  # replaced by a path inside the case's empty folder
MODEL = os.path.abspath(__file__)  # any existing file, for options that must name one

# program -> list of (command words, output option words, number option, out-of-range value).
# The number option is given with no value, with "abc" and with the out-of-range value.
CASES = {
    "curio-sim": [
        (["rollout"], [], "--seed", "-1"),
        (["render"], ["--out", OUT + ".png"], "--scale", "0"),
        (["serve", "--bus", "loopback"], [], "--exit-after-idle", "-1"),
        (["serve", "--bus", "loopback"], [], "--seed", "18446744073709551616"),
        (["serve", "--bus", "loopback"], [], "--camera-fps", "0"),
    ],
    "curio-can": [
        (["episodes", "loopback"], [], "--episodes", "0"),
        (["dump", "loopback"], [], "--timeout-ms", "-5"),
        (["bench", "loopback"], [], "--frames", "0"),
        (["slcan-bridge", "--serial", "pty", "--bus", "loopback"], [], "--max-fps", "-1"),
    ],
    "curio-quantize": [
        (["quantize", "--model", MODEL, "--name", "m"], ["--out", OUT + ".hpp"], "--images", "0"),
        (["evaluate", "--model", MODEL], [], "--test-images", "-1"),
        (["evaluate", "--model", MODEL], [], "--test-seed", "18446744073709551616"),
    ],
    "curio-train": [
        (["train", "--model", "vae"], ["--out", OUT], "--iterations", "0"),
        (["train", "--model", "vae"], ["--out", OUT], "--seed", "-1"),
        (["report", "--model-dir", "."], [], "--images", "1"),
        (["unmix", "--from", MODEL], ["--out", OUT], "--threads", "0"),
    ],
    "curio-lab": [
        (["run"], ["--out", OUT], "--episodes", "-1"),
        (["paper", "--efr-only"], ["--out", OUT], "--threads", "-1"),
        (["run"], ["--out", OUT], "--bootstrap", "-1"),
        (["run"], ["--out", OUT], "--competence-clip", "-1"),
        (["run"], ["--out", OUT], "--seeds", "18446744073709551616"),
    ],
    "curio-controller": [
        ([], ["--out", OUT], "--episodes", "-1"),
        ([], ["--out", OUT], "--bootstrap", "-1"),
        ([], ["--out", OUT], "--competence-clip", "0"),
        ([], ["--out", OUT], "--seed", "18446744073709551616"),
        ([], ["--out", OUT], "--grasp-radius", "-0.1"),
        ([], ["--out", OUT], "--period-us", "-1"),
        ([], ["--out", OUT], "--realtime", "0"),
        ([], ["--out", OUT], "--settle-ms", "-1"),
        ([], ["--out", OUT], "--camera-stall", "0"),
    ],
    "curio-online": [
        ([], ["--out", OUT], "--episodes", "-1"),
        ([], ["--out", OUT], "--seed", "-1"),
    ],
    "curio-encode": [
        ([MODEL], ["--out", OUT], "--figure-images", "0"),
    ],
}

# program -> list of (arguments with a malformed value that is not a number, the option named).
# An empty --out once meant "the current folder" (and printed "results in /"); an output file
# named by a folder would leave "<folder>.tmp.*" litter beside it.
MALFORMED = {
    "curio-sim": [(["serve", "--bus", "udp:notaport"], "--bus"),
                  (["render", "--out", ""], "--out")],
    "curio-can": [(["dump", "udp:notaport"], "url")],
    "curio-controller": [(["--bus", "udp:notaport", "--out", OUT], "--bus"),
                         (["--out", ""], "--out"),
                         (["--explore", "frontier-ish", "--out", OUT], "--explore"),
                         (["--noise", "0.05,0.1", "--out", OUT], "--noise"),
                         (["--tie-rule", "middle", "--out", OUT], "--tie-rule")],
    "curio-lab": [(["run", "--out", ""], "--out"),
                  (["run", "--explore", "frontier-ish", "--out", OUT], "--explore"),
                  (["merge", "--out", "", OUT], "--out")],
    "curio-online": [(["--out", ""], "--out"),
                     (["--explore", "frontier-ish", "--out", OUT], "--explore")],
    "curio-encode": [([MODEL, "--out", ""], "--out"), ([MODEL, "--model", "gan", "--out", OUT], "--model")],
    "curio-train": [(["train", "--model", "vae", "--out", ""], "--out")],
    "curio-quantize": [(["quantize", "--model", MODEL, "--name", "m", "--out", ""], "--out"),
                       (["quantize", "--model", MODEL, "--name", "m", "--out", "."], "--out")],
}


def run(path, args, cwd):
    try:
        p = subprocess.run([path] + args, cwd=cwd, stdin=subprocess.DEVNULL,
                           capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return None, "", "(no exit within 60 s)"
    return p.returncode, p.stdout, p.stderr


def usage_error_problems(name, path, args, option):
    """Runs `path args` (OUT replaced) in an empty folder; returns what is wrong, "" if nothing."""
    with tempfile.TemporaryDirectory(prefix="curio_cli_") as work:
        words = [a.replace(OUT, os.path.join(work, "out")) for a in args]
        code, out, err = run(path, words, work)
        left = sorted(os.listdir(work))
    shown = " ".join([name] + args).replace(MODEL, "FILE")
    problems = []
    if code != 2:
        problems.append(f"exit {code}, not 2")
    if len(err.splitlines()) != 1:
        problems.append(f"{len(err.splitlines())} lines on stderr, not 1")
    if option not in err:
        problems.append(f"stderr does not name {option}")
    if "--help" not in err:
        problems.append("stderr has no --help hint")
    if out:
        problems.append("wrote on stdout")
    if left:
        problems.append(f"wrote {left}")
    return f"{shown}: {'; '.join(problems)}\n    stderr: {err.strip()[:300]!r}" if problems else ""


def help_problems(name, path, command):
    code, out, _ = run(path, command + ["--help"], tempfile.gettempdir())
    if code != 0 or "Usage" not in out:
        return f"{' '.join([name] + command)} --help: exit {code}, usage {'shown' if 'Usage' in out else 'missing'}"
    return ""


def main():
    paths = {n: os.path.abspath(p) for n, p in (a.split("=", 1) for a in sys.argv[1:])}
    jobs = []  # (function, arguments)
    for name, cases in CASES.items():
        path = paths.get(name)
        if path is None or not os.access(path, os.X_OK):
            print(f"{name}: not built, skipped")
            continue
        jobs.append((help_problems, (name, path, [])))
        for command, outputs, option, out_of_range in cases:
            base = command + outputs
            if command:
                jobs.append((help_problems, (name, path, command[:1])))
            for args, named in ((base + ["--no-such-option"], "--no-such-option"),
                                (base + [option], option),
                                (base + [option, "abc"], option),
                                (base + [option, out_of_range], option)):
                jobs.append((usage_error_problems, (name, path, args, named)))
        for args, named in MALFORMED.get(name, []):
            jobs.append((usage_error_problems, (name, path, args, named)))
    # In parallel: the LibTorch programs take seconds to start.
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        failures = [f for f in pool.map(lambda job: job[0](*job[1]), jobs) if f]
    for f in failures:
        print("FAIL", f)
    print(f"{len(jobs)} invocations checked, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
