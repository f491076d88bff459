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
An old spelling of a renamed option (RETIRED) must be a usage error like any unknown option,
its one line naming the new spelling.

One meaning per option name (README, the "Option | Meaning | Programs" table): the options each
program and subcommand offers in its --help are read, and every name of MEANINGS must be offered
exactly where the table says (no program may give `--out` to a file, `--model` to a model kind,
`--window` to frames in flight, ...), with the kind of value the table says (`--out` a FOLDER,
`--png` and `--header` a FILE, `--bus` a URL, `--seed` a SEED); no name of RETIRED_NAMES may be
offered anywhere.

  cli_convention.py NAME=PATH...    e.g. curio-sim=build/default/sim/curio-sim
Programs not given (not built: curio-train and curio-online need LibTorch) are skipped."""
import concurrent.futures
import os
import re
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
        (["render"], ["--png", OUT + ".png"], "--scale", "0"),
        (["serve", "--bus", "loopback"], [], "--exit-after-idle", "-1"),
        (["serve", "--bus", "loopback"], [], "--seed", "18446744073709551616"),
        (["serve", "--bus", "loopback"], [], "--camera-fps", "0"),
    ],
    "curio-can": [
        (["episodes", "--bus", "loopback"], [], "--episodes", "0"),
        (["dump", "--bus", "loopback"], [], "--timeout-ms", "-5"),
        (["echo", "--bus", "loopback"], [], "--count", "-1"),
        (["mock-arm", "--bus", "loopback"], [], "--timeout-ms", "0"),
        (["bench", "--bus", "loopback"], [], "--frames", "0"),
        (["bench", "--bus", "loopback"], [], "--in-flight", "0"),
        (["slcan-bridge", "--serial", "pty", "--bus", "loopback"], [], "--max-fps", "-1"),
        (["slcan-bridge", "--serial", "pty", "--bus", "loopback"], [], "--burst", "0"),
    ],
    "curio-quantize": [
        (["quantize", "--model", MODEL, "--name", "m"], ["--header", OUT + ".hpp"], "--images", "0"),
        (["evaluate", "--model", MODEL], [], "--test-images", "-1"),
        (["evaluate", "--model", MODEL], [], "--test-seed", "18446744073709551616"),
    ],
    "curio-train": [
        (["train", "--kind", "vae"], ["--out", OUT], "--iterations", "0"),
        (["train", "--kind", "vae"], ["--out", OUT], "--seed", "-1"),
        (["report", "--checkpoint", "."], [], "--images", "1"),
        (["export", "--checkpoint", ".", "--name", "m"], ["--out", OUT], "--kl-images", "0"),
        (["unmix", "--checkpoint", MODEL], ["--out", OUT], "--threads", "0"),
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
                  (["render", "--png", ""], "--png"),
                  (["render", "--png", "."], "--png")],
    "curio-can": [(["dump", "--bus", "udp:notaport"], "--bus"),
                  (["send", "--bus", "udp:notaport", "123#00"], "--bus"),
                  (["dump"], "--bus")],
    "curio-controller": [(["--bus", "udp:notaport", "--out", OUT], "--bus"),
                         (["--out", ""], "--out"),
                         (["--explore", "frontier-ish", "--out", OUT], "--explore"),
                         (["--noise", "0.05,0.1", "--out", OUT], "--noise"),
                         (["--tie-rule", "middle", "--out", OUT], "--tie-rule")],
    "curio-lab": [(["run", "--out", ""], "--out"),
                  (["run", "--explore", "frontier-ish", "--out", OUT], "--explore"),
                  (["merge", "--out", "", OUT], "--out"),
                  (["score", "--run", OUT, "--positions", MODEL, "--out", ""], "--out")],
    "curio-online": [(["--out", ""], "--out"),
                     (["--explore", "frontier-ish", "--out", OUT], "--explore")],
    "curio-encode": [([MODEL, "--out", ""], "--out"),
                     ([MODEL, "--weights", "gan", "--out", OUT], "--weights")],
    "curio-train": [(["train", "--kind", "vae", "--out", ""], "--out"),
                    (["train", "--kind", "gan", "--out", OUT], "--kind"),
                    (["report", "--checkpoint", "no/such/run"], "--checkpoint")],
    "curio-quantize": [(["quantize", "--model", MODEL, "--name", "m", "--header", ""], "--header"),
                       (["quantize", "--model", MODEL, "--name", "m", "--header", "."], "--header")],
}

# program -> the old spellings of renamed options, each refused as a usage error naming it.
RETIRED = {  # (arguments, (the old spelling, the new one: the one line names both))
    "curio-sim": [(["render", "--out", OUT + ".png"], ("--out", "--png")),
                  (["render", "-o", OUT + ".png"], ("-o", "--png"))],
    "curio-can": [(["dump", "loopback"], ("loopback", "--bus loopback")),
                  (["bench", "--bus", "loopback", "--window", "4"], ("--window", "--in-flight")),
                  (["bench", "--bus", "loopback", "-w", "4"], ("-w", "--in-flight")),
                  (["slcan-bridge", "--serial", "pty", "--bus", "loopback", "--window", "4"],
                   ("--window", "--burst"))],
    "curio-quantize": [(["quantize", "--model", MODEL, "--name", "m", "--out", OUT + ".hpp"],
                        ("--out", "--header"))],
    "curio-encode": [([MODEL, "--model", "vae", "--out", OUT], ("--model", "--weights"))],
    "curio-train": [(["train", "--model", "vae", "--out", OUT], ("--model", "--kind")),
                    (["report", "--model-dir", "."], ("--model-dir", "--checkpoint")),
                    (["export", "--model-dir", ".", "--name", "m", "--out", OUT],
                     ("--model-dir", "--checkpoint")),
                    (["unmix", "--from", MODEL, "--out", OUT], ("--from", "--checkpoint"))],
}

# One meaning per option name: the README's table. option -> (the kind of value its --help must
# show, "" for any; where it is offered: "program" or "program subcommand"). A name of this table
# offered anywhere else, or missing from a place listed here, fails: a new use of one of these
# names joins the table (and the README's) only if it means the same thing.
LAB_CAMPAIGN = {"curio-lab run", "curio-lab bench", "curio-lab paper", "curio-lab slurm"}
CAN_BUS = {"curio-can " + c for c in ("send", "dump", "echo", "bench", "mock-arm", "episodes",
                                        "slcan-bridge")}
MEANINGS = {
    # where a program writes: always a folder
    "--out": ("FOLDER", {"curio-controller", "curio-encode", "curio-online", "curio-lab run",
                         "curio-lab paper", "curio-lab merge", "curio-lab score", "curio-lab slurm",
                         "curio-lab slurm-train", "curio-train train", "curio-train export",
                         "curio-train unmix"}),
    # a single file written (or, for check, read): named for what it is
    "--png": ("FILE", {"curio-sim render"}),
    "--header": ("FILE", {"curio-quantize quantize", "curio-quantize check"}),
    # a float model file (.cfm)
    "--model": ("FILE", {"curio-quantize quantize", "curio-quantize check",
                         "curio-quantize evaluate"}),
    # the int8 weights compiled into the build (beta_vae, vae)
    "--weights": ("", {"curio-encode"}),
    # the kind of model to train (beta-vae, vae)
    "--kind": ("", {"curio-train train"}),
    # a checkpoint to read: a training's folder or its checkpoint.pt
    "--checkpoint": ("", {"curio-train report", "curio-train export", "curio-train unmix"}),
    # the checkpoint a new training starts from (its weights, a fresh optimizer)
    "--init-from": ("", {"curio-train train"}),
    # the CAN bus URL
    "--bus": ("URL", CAN_BUS | {"curio-sim serve", "curio-controller"}),
    # one seed, 0 to 2^64 - 1
    "--seed": ("SEED", {"curio-sim rollout", "curio-sim serve", "curio-quantize quantize",
                        "curio-quantize evaluate", "curio-controller", "curio-online",
                        "curio-train train"}),
    # a list or range of seeds
    "--seeds": ("", LAB_CAMPAIGN | {"curio-lab slurm-train"}),
    # exploration episodes (curio-can episodes: episodes timed)
    "--episodes": ("", LAB_CAMPAIGN | {"curio-controller", "curio-online", "curio-can episodes"}),
    "--threads": ("", LAB_CAMPAIGN | {"curio-encode", "curio-online", "curio-train train",
                                      "curio-train report", "curio-train unmix"}),
    "--quiet": ("", {"curio-encode", "curio-controller", "curio-online", "curio-lab run",
                     "curio-lab paper", "curio-lab score"}),
    # kinematic or ode
    "--physics": ("", LAB_CAMPAIGN | {"curio-sim rollout", "curio-sim serve", "curio-online"}),
    # the exploration options (host_tools/experiment/exploration_options.hpp), defined once
    "--noise": ("", LAB_CAMPAIGN | {"curio-controller"}),
    "--bootstrap": ("", LAB_CAMPAIGN | {"curio-controller"}),
    "--competence-clip": ("", LAB_CAMPAIGN | {"curio-controller"}),
    "--competence": ("", LAB_CAMPAIGN | {"curio-controller"}),
    # W, the interest smoothing of SPEC §2.5
    "--window": ("", LAB_CAMPAIGN | {"curio-controller"}),
    "--epsilon": ("", LAB_CAMPAIGN | {"curio-controller"}),
    "--tie-rule": ("", LAB_CAMPAIGN | {"curio-controller"}),
    "--explore": ("", LAB_CAMPAIGN | {"curio-controller", "curio-online"}),
    # frames in flight in a throughput run
    "--in-flight": ("", {"curio-can bench"}),
    # the burst of a pacing token bucket, lines
    "--burst": ("", {"curio-can slcan-bridge"}),
    # continue the run in --out
    "--resume": ("", {"curio-controller", "curio-online", "curio-train train"}),
    # start afresh over what --out holds
    "--replace": ("", {"curio-controller", "curio-lab run", "curio-lab paper"}),
    # the CSV of every episode's final positions (serve writes it, score reads it)
    "--positions": ("", {"curio-sim serve", "curio-lab score"}),
}
# Old spellings: offered nowhere.
RETIRED_NAMES = {"-o", "-w", "--model-dir", "--from"}


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
    for o in option if isinstance(option, tuple) else (option,):
        if o not in err:
            problems.append(f"stderr does not name {o}")
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


# An option line of CLI11's --help: two spaces, its names ("-n,--frames"), then the kind of its
# value ("UINT:UINT in [1 - 512]=32", "TEXT:FOLDER REQUIRED"); descriptions are indented further.
OPTION_LINE = re.compile(r"^  (-{1,2}[A-Za-z0-9][^\s,]*(?:,-{1,2}[^\s,]+)*)(?: (\S+))?")


def offered(path, command):
    """The options `path command --help` lists ({name: kind of value}) and its subcommands;
    None if --help fails."""
    code, out, _ = run(path, command + ["--help"], tempfile.gettempdir())
    if code != 0:
        return None
    options, subcommands, section = {}, [], ""
    for line in out.splitlines():
        if re.match(r"^\S.*:$", line):
            section = line[:-1]
        elif section == "Subcommands":
            m = re.match(r"^  (\S+)", line)
            if m:
                subcommands.append(m.group(1))
        elif m := OPTION_LINE.match(line):
            for name in m.group(1).split(","):
                options[name] = m.group(2) or ""
    return options, subcommands


def meaning_problems(name, path):
    """Every --help of the program (and of each subcommand) against MEANINGS and RETIRED_NAMES."""
    top = offered(path, [])
    if top is None:
        return [f"{name} --help failed"]
    places = {name: top[0]}
    for sub in top[1]:
        got = offered(path, [sub])
        if got is None:
            return [f"{name} {sub} --help failed"]
        places[f"{name} {sub}"] = got[0]
    problems = []
    for place, options in places.items():
        for option, kind in options.items():
            if option in RETIRED_NAMES:
                problems.append(f"{place} offers {option}, an old spelling")
            if option not in MEANINGS:
                continue
            want, where = MEANINGS[option]
            if place not in where:
                problems.append(f"{place} offers {option}, which the table gives only to "
                                f"{', '.join(sorted(where))}")
            elif want and want not in kind.split(":", 1)[-1]:
                problems.append(f"{place} {option} takes {kind or 'no value'}, not a {want}")
    for option, (_, where) in MEANINGS.items():
        for place in sorted(where):
            if place.split()[0] == name and option not in places.get(place, {}):
                problems.append(f"{place} does not offer {option}, which the table lists there")
    return problems


def readme_problems():
    """The README's "Option | Meaning | Programs" table must be MEANINGS: the same names, offered
    in the same places ("`curio-lab run`/`paper`" is curio-lab run and curio-lab paper)."""
    readme = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")
    table = {}
    with open(readme, encoding="utf-8") as f:
        for line in f:
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
            if len(cells) != 3 or not cells[0].startswith("`-"):
                continue
            option = cells[0].strip("`").split()[0]
            places, program = set(), ""
            for word in re.findall(r"`([^`]+)`", cells[2]):
                if word.startswith("curio-"):
                    program = word.split()[0]
                    places.add(word)
                elif program and not word.startswith("-"):
                    places.add(f"{program} {word}")
            table[option] = places
    problems = []
    for option in sorted(set(table) | set(MEANINGS)):
        if option not in table:
            problems.append(f"README's option table has no row for {option}")
        elif option not in MEANINGS:
            problems.append(f"README's option table lists {option}, which MEANINGS does not")
        elif table[option] != MEANINGS[option][1]:
            problems.append(f"README's option table gives {option} to {sorted(table[option])}, "
                            f"MEANINGS to {sorted(MEANINGS[option][1])}")
    return problems


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
        for args, named in MALFORMED.get(name, []) + RETIRED.get(name, []):
            jobs.append((usage_error_problems, (name, path, args, named)))
        jobs.append((lambda n, p: "\n".join(f"{n}: {x}" for x in meaning_problems(n, p)),
                     (name, path)))
    jobs.append((lambda: "\n".join(readme_problems()), ()))
    # In parallel: the LibTorch programs take seconds to start.
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        failures = [f for f in pool.map(lambda job: job[0](*job[1]), jobs) if f]
    for f in failures:
        print("FAIL", f)
    print(f"{len(jobs)} invocations checked, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
