#!/usr/bin/env python3
"""Checks that the repository stands alone and describes the product, not the history of its
making. Exits 1 and names every offending line; 0 when the tree is clean.

usage: check_stands_alone.py [REPO_DIR]    check a tree (default: this script's repository)
       check_stands_alone.py --self-test   prove the checker catches each kind of offence

Rules, for every text file git tracks (plus new files it does not ignore), except *.csv and
*.json (run data, which may record where and when it was made):
  1. No numbered step of the work: the words for a work session, a stop or an issue followed
     by a number ("<word> 12", "<word>s 3", "<word>-4", case-insensitive). A reader cannot
     see those; git log is where history lives. Say what the thing is or does instead.
  2. No path outside the repository: the shared folder beside the checkout, the engineering
     note in capitals, or this machine's work folder. A clone has none of them: state the
     fact in the project's own words, or point to docs/spec.md.
  3. No dated narrative: the phrase "at the time" "of writing" (joined). A reference states
     what holds.
"""
import os
import re
import subprocess
import sys
import tempfile

SKIPPED_EXT = (".csv", ".json")

# The patterns are assembled from pieces so that this file does not match itself.
_WORDS = "|".join(("sess" + "ion", "st" + "op", "iss" + "ue"))
RULES = (
    (re.compile(r"\b(" + _WORDS + r")s?[ -][0-9]+", re.IGNORECASE),
     "names a numbered session, stop or issue (rule 1)"),
    (re.compile(r"\.\./" + "shared"), "points outside the repository (rule 2)"),
    (re.compile("ENGIN" + "EERING"), "points to a note outside the repository (rule 2)"),
    (re.compile(r"(?<![\w.])/" + "work" + r"/"), "names a folder of the build machine (rule 2)"),
    (re.compile(r"\bat the time " + r"of writing\b", re.IGNORECASE),
     "dated narrative (rule 3)"),
)


def tracked_files(repo):
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "--cached", "--others",
                              "--exclude-standard", "-z"], check=True, capture_output=True,
                             text=True).stdout.split("\0")
    except (OSError, subprocess.CalledProcessError):
        out = []
        for d, dirs, files in os.walk(repo):
            dirs[:] = [x for x in dirs if not x.startswith(".") and x not in ("build", "out", "runs")]
            for f in files:
                out.append(os.path.relpath(os.path.join(d, f), repo))
    return sorted(p for p in out if p and not p.lower().endswith(SKIPPED_EXT))


def check_file(repo, path):
    try:
        with open(os.path.join(repo, path), "rb") as f:
            data = f.read()
    except OSError:
        return []  # listed by git but deleted in the working tree
    if b"\0" in data[:8192]:
        return []  # binary (figures, models)
    problems = []
    for n, line in enumerate(data.decode("utf-8", errors="replace").splitlines(), 1):
        for pattern, why in RULES:
            m = pattern.search(line)
            if m:
                start = max(0, m.start() - 30)
                problems.append(f"{path}:{n}: {why}: …{line[start:m.end() + 30].strip()}…")
    return problems


def check(repo):
    problems = []
    for path in tracked_files(repo):
        problems += check_file(repo, path)
    return problems


def self_test():
    w = {"s": "Sess" + "ion", "t": "st" + "op", "i": "iss" + "ue"}
    cases = {
        "README.md": "Stop the run with Ctrl-C; two sessions of the demo; open issues; "
                     "docs/spec.md; engineering notes; ../docs/spec.md; build/work/x\n",
        "firmware/ok.hpp": "// the stop condition (5 periods), an issue with 3 frames\n",
        "docs/bad_session.md": f"Measured in {w['s']} 22.\n",
        "docs/bad_sessions.md": f"({w['s'].lower()}s 11–12)\n",
        "firmware/bad_stop.hpp": f"// found at {w['t']} 3\n",
        "tests/bad_issue.sh": f"# {w['i'].upper()} 17 item 6\n",
        "host_tools/bad_issue_hyphen.hpp": f"// the {w['i']}-3 criteria\n",
        "docs/bad_shared.md": "see ../" + "shared/SPEC.md\n",
        "sim/bad_engineering.hpp": "// (" + "ENGIN" + "EERING §6)\n",
        "docs/bad_work_folder.md": "cd /" + "work/main\n",
        "docs/bad_writing.md": "launched, not finished at the time " + "of writing\n",
        "docs/results.csv": f"{w['s']} 4,0.5\n",
        "docs/results.json": f'{{"note": "{w["i"]} 2"}}\n',
    }
    with tempfile.TemporaryDirectory() as d:
        for rel, text in cases.items():
            os.makedirs(os.path.dirname(os.path.join(d, rel)) or d, exist_ok=True)
            with open(os.path.join(d, rel), "w") as f:
                f.write(text)
        with open(os.path.join(d, "docs", "figure.png"), "wb") as f:
            f.write(b"\x89PNG\0\0" + f"{w['i']} 5".encode())
        problems = check(d)
    flagged = {p.split(":")[0] for p in problems}
    expected = {rel for rel in cases if "/bad_" in rel}
    if flagged != expected:
        print("check_stands_alone self-test FAILED")
        print("  expected to flag:", sorted(expected))
        print("  flagged:         ", sorted(flagged))
        return 1
    print(f"check_stands_alone self-test: all {len(expected)} offences caught, clean files, "
          "run data and binaries pass")
    return 0


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    if len(argv) > 1 and argv[1] == "--self-test":
        return self_test()
    repo = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    files = tracked_files(repo)
    problems = check(repo)
    if problems:
        by_file = {}
        for p in problems:
            by_file.setdefault(p.split(":")[0], 0)
            by_file[p.split(":")[0]] += 1
        print(f"check_stands_alone: {len(problems)} line(s) in {len(by_file)} of {len(files)} "
              "files (the rules: toolchain/check_stands_alone.py --help):")
        for p in problems:
            print("  " + p)
        return 1
    print(f"check_stands_alone: {len(files)} files name no session, stop or issue number and "
          "no path outside the repository")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
