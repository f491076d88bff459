#!/usr/bin/env bash
# `curio-lab run --out D` into a D already used. A finished campaign with the
# same configuration is not run again (records untouched, report rewritten, equal); an
# unfinished one is resumed (only the missing run runs); another configuration is refused,
# naming the difference, and D is left as it was; --replace removes the old campaign's files
# (no seed-2 file is left beside a 2-seed campaign) and nothing else (the user's files stay);
# a folder of other files is refused even with --replace; an older curio-lab's results
# (summary.json, no manifest) count as another campaign.
#   tests/lab/out_dir_policy.sh CURIO_LAB WORK_DIR
set -euo pipefail
lab=$1 work=$2
. "$(dirname "$0")/report_compare.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; for f in err*.txt; do echo "== $f"; cat "$f"; done; exit 1; }
camp=(--algos RPE,MGE-EFR --episodes 500 --threads 2 --quiet)
stamps() { stat -c '%n %i %Y' camp/records/*.cbor; }
listing() { (cd "$1" && find . -type f | sort | xargs cksum); }

# 1. A fresh folder.
"$lab" run "${camp[@]}" --seeds 0-2 --out camp > /dev/null 2> err1.txt || fail "first run failed"
[[ $(ls camp/records/*.cbor | wc -l) == 6 && -f camp/manifest.json ]] || fail "no 6 records + manifest"
cp -a camp first
before=$(stamps)

# 2. The same campaign, finished: nothing runs; the report is written again, equal.
old_summary=$(stat -c %i camp/summary.json)
"$lab" run "${camp[@]}" --seeds 0-2 --out camp > /dev/null 2> err2.txt || fail "rerun failed"
grep -q "all 6 runs are recorded .*nothing to run, the report is written again" err2.txt ||
  fail "no 'nothing to run' notice"
[[ $(stamps) == "$before" ]] || fail "records were written again"
[[ $(stat -c %i camp/summary.json) != "$old_summary" ]] || fail "the report was not rewritten"
same_report first camp

# 3. Unfinished (one record and the run CSVs gone): resumed, only that run runs.
rm camp/records/run-4.cbor camp/runs/*.csv
"$lab" run "${camp[@]}" --seeds 0-2 --out camp > /dev/null 2> err3.txt || fail "resume failed"
grep -q "resuming camp: 5 of 6 runs recorded (skipped), 1 to run" err3.txt || fail "no resume notice"
[[ $(stamps | grep -v run-4) == "$(echo "$before" | grep -v run-4)" ]] ||
  fail "recorded runs were run again"
same_report first camp

# 4. Another configuration (fewer seeds): refused, naming the difference; D unchanged.
echo "my notes" > camp/notes.txt && echo "mine" > camp/runs/mine.txt
snapshot=$(listing camp)
rc=0
"$lab" run "${camp[@]}" --seeds 0-1 --out camp > /dev/null 2> err4.txt || rc=$?
[[ $rc == 2 ]] || fail "another campaign into camp: exit $rc, not 2"
grep -q 'seeds: \[0,1,2\] vs \[0,1\]' err4.txt || fail "the difference is not named"
grep -q -- "--replace" err4.txt || fail "--replace is not suggested"
[[ $(listing camp) == "$snapshot" ]] || fail "a refused run changed camp"

# 5. --replace: the old campaign's files go (no seed-2 file is left), the user's stay, and the
#    result equals a 2-seed campaign in a fresh folder.
"$lab" run "${camp[@]}" --seeds 0-1 --out camp --replace > /dev/null 2> err5.txt || fail "--replace failed"
grep -q -- "--replace: removed [0-9]* files" err5.txt || fail "no removal notice"
[[ -z $(find camp -name '*seed2*') ]] || fail "stale seed-2 files: $(find camp -name '*seed2*')"
[[ $(cat camp/notes.txt) == "my notes" && $(cat camp/runs/mine.txt) == mine ]] || fail "user files removed"
rm camp/notes.txt camp/runs/mine.txt
"$lab" run "${camp[@]}" --seeds 0-1 --out fresh > /dev/null 2> err6.txt || fail "fresh 2-seed run failed"
same_report fresh camp

# 6. A folder of other files: refused, --replace or not, and left alone.
mkdir other && echo keep > other/data.csv
rc=0
"$lab" run "${camp[@]}" --seeds 0-1 --out other --replace > /dev/null 2> err7.txt || rc=$?
[[ $rc == 2 ]] || fail "a foreign folder: exit $rc, not 2"
grep -q "holds no curio-lab campaign" err7.txt || fail "no message for a foreign folder"
[[ $(ls other) == data.csv ]] || fail "the foreign folder was changed: $(ls other)"

# 7. An older curio-lab's results (no manifest, no records): another campaign.
cp -a first legacy && rm -r legacy/manifest.json legacy/records
rc=0
"$lab" run "${camp[@]}" --seeds 0-1 --out legacy > /dev/null 2> err8.txt || rc=$?
[[ $rc == 2 ]] && grep -q "earlier curio-lab" err8.txt || fail "legacy folder: exit $rc"
"$lab" run "${camp[@]}" --seeds 0-1 --out legacy --replace > /dev/null 2> err9.txt ||
  fail "legacy --replace failed"
[[ -z $(find legacy -name '*seed2*') ]] || fail "stale seed-2 files in legacy/"
same_report fresh legacy
no_temp_files "$work"
echo "out-dir policy: finished → not rerun, unfinished → resumed, other → refused / --replace, foreign → refused"
