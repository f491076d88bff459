#!/usr/bin/env bash
# curio-encode on a folder of two rendered scenes and four bad files: the good images are
# encoded and written (latents.csv has 10 rows each, summary.json lists them and the refused
# files with why, figure.png exists), each bad file gets one stderr line naming it, exit 1;
# the good images alone exit 0; an empty folder exits 1 naming it; --resize takes a 2x render.
# Usage: encode_cli.sh <curio-encode> <curio-sim> <scratch dir>
set -euo pipefail
enc=$1; sim=$2; dir=$3
rm -rf "$dir"; mkdir -p "$dir/mixed" "$dir/empty"
"$sim" render --ball 0.3 -0.2 --distractor -0.5 0.4 --png "$dir/mixed/a.png"
"$sim" render --ball -0.6 0.5 --distractor 0.2 0.2 --png "$dir/mixed/b.png"
"$sim" render --ball 0 0 --distractor 0.5 0.5 --scale 2 --png "$dir/big.png"
echo "not a png" > "$dir/mixed/c.png"
head -c 100 "$dir/mixed/a.png" > "$dir/mixed/d.png"
cp "$dir/big.png" "$dir/mixed/e.png"
fail() { echo "FAIL: $*"; exit 1; }

set +e
"$enc" "$dir/mixed" --out "$dir/out" > "$dir/stdout" 2> "$dir/stderr"; code=$?
set -e
[[ $code == 1 ]] || fail "mixed folder: exit $code, want 1"
for bad in c d e; do
  [[ $(grep -c "mixed/$bad.png: " "$dir/stderr") == 1 ]] || fail "no one-line error for $bad.png: $(cat "$dir/stderr")"
done
grep -q "mixed/e.png: 128×128 pixels; the encoder takes 64×64 (add --resize" "$dir/stderr" || fail "size message"
[[ $(grep -c '^"' "$dir/out/latents.csv") == 20 ]] || fail "latents.csv rows: $(wc -l < "$dir/out/latents.csv")"
[[ -s $dir/out/figure.png ]] || fail "no figure.png"
python3 - "$dir/out/summary.json" <<'PY' || fail "summary.json"
import json, sys
s = json.load(open(sys.argv[1]))
assert [i["file"].split("/")[-1] for i in s["images"]] == ["a.png", "b.png"], s["images"]
assert sorted(r["file"].split("/")[-1] for r in s["refused"]) == ["c.png", "d.png", "e.png"], s["refused"]
assert s["goal_modules"] == [[0, 2], [1, 3], [4, 5], [6, 7], [8, 9]] or len(s["goal_modules"]) == 5
for i in s["images"]:
    assert len(i["mu_int8"]) == 10 and len(i["mu_float"]) == 10
    assert i["max_abs_mu_int8_minus_float"] < 0.05, i
PY

"$enc" "$dir/mixed/a.png" "$dir/mixed/b.png" --out "$dir/out_ok" --quiet > /dev/null || fail "good images: exit $?"
"$enc" "$dir/big.png" --resize --out "$dir/out_resized" --quiet > /dev/null || fail "--resize: exit $?"
set +e
"$enc" "$dir/empty" --out "$dir/out_empty" 2> "$dir/stderr_empty" > /dev/null; code=$?
set -e
[[ $code == 1 ]] || fail "empty folder: exit $code"
grep -q "empty: folder has no .png files" "$dir/stderr_empty" || fail "empty folder message: $(cat "$dir/stderr_empty")"
echo "PASS"
