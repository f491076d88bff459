#!/usr/bin/env bash
# curio-controller --explore: the strategy reaches the arm, and the journal names it.
#   - `--explore beyond` over the UDP bus against `curio-sim serve` gives the archive checksum
#     of `curio-lab run --explore beyond` in process (same seed, same episodes), and a different
#     one from SPEC's strategy (so the option is not ignored);
#   - its journal is format version 2 (the strategy's ingredients in the header); a SPEC run's
#     is version 1, byte for byte the format every older journal has;
#   - resuming the beyond run with another strategy is refused naming both (exit 1, as any other run's journal), nothing
#     written; resuming with the same strategy is accepted;
#   - one run takes one σ: `--noise 0.05,0.1` is a usage error naming --noise.
#   explore_strategy.sh CURIO_SIM CURIO_CONTROLLER CURIO_LAB WORKDIR [EPISODES]
set -euo pipefail
sim=$1 controller=$2 lab=$3 work=$4 episodes=${5:-100}
seed=3
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
serve_pid=
trap '[ -z "$serve_pid" ] || kill -9 $serve_pid 2>/dev/null || true' EXIT
fail() { echo "FAIL: $*"; for f in "$work"/*.err "$work"/*.log; do echo "== $f"; tail -n 5 "$f"; done; exit 1; }
checksum() { sed -n 's/.*archive checksum \(0x[0-9a-f]*\).*/\1/p' "$1" | tail -n 1; }
version() { od -An -tu2 -j8 -N2 "$1" | tr -d ' '; }

"$sim" serve --bus "$bus" --physics kinematic --seed $seed --exit-after-idle 30 --status-every 0 \
  2> "$work/serve.log" &
serve_pid=$!
run() {  # NAME [OPTIONS...]: a controller run over the bus into $work/NAME
  local name=$1
  shift
  "$controller" --bus "$bus" --seed $seed --episodes "$episodes" --out "$work/$name" --quiet \
    --print-checksum "$@" > "$work/$name.out" 2> "$work/$name.err" || fail "$name: exit $?"
}
run beyond --explore beyond
run spec

"$lab" run --algos MGE-EFR --seeds $seed --episodes "$episodes" --explore beyond --print-checksum \
  --out "$work/lab" --quiet > "$work/lab.out" 2> "$work/lab.err" || fail "curio-lab run: exit $?"
arm=$(checksum "$work/beyond.out") spec=$(checksum "$work/spec.out")
in_process=$(sed -n 's/.*archive checksum \(0x[0-9a-f]*\).*/\1/p' "$work/lab.out" "$work/lab.err" | tail -n 1)
[ -n "$arm" ] && [ "$arm" = "$in_process" ] ||
  fail "--explore beyond over the bus: checksum '$arm', curio-lab in process: '$in_process'"
[ "$arm" != "$spec" ] || fail "--explore beyond gives SPEC's checksum $spec: the strategy was not applied"
echo "--explore beyond over the bus = curio-lab in process: $arm (SPEC's strategy: $spec)"

[ "$(version "$work/beyond/journal.bin")" = 2 ] || fail "the beyond journal is not format version 2"
[ "$(version "$work/spec/journal.bin")" = 1 ] || fail "the SPEC journal is not format version 1"
echo "journal format: beyond version 2, spec version 1"

before=$(sha256sum "$work/beyond/journal.bin")
rc=0
"$controller" --bus loopback --seed $seed --episodes "$episodes" --out "$work/beyond" --resume \
  --explore spec > "$work/wrong.out" 2> "$work/wrong.err" || rc=$?
[ $rc = 1 ] || fail "resume under another strategy: exit $rc, want 1"
grep -q "journal is explore strategy beyond, this run is explore strategy spec" "$work/wrong.err" ||
  fail "the refusal does not name both strategies: $(cat "$work/wrong.err")"
[ "$before" = "$(sha256sum "$work/beyond/journal.bin")" ] || fail "the refused resume changed the journal"
echo "resume under spec refused: $(grep -o 'journal is explore strategy.*' "$work/wrong.err" | head -n 1)"
# The same strategy: accepted (the run is complete: every episode is replayed, none run again).
run beyond --resume --explore beyond
[ "$(checksum "$work/beyond.out")" = "$arm" ] || fail "the resumed run's checksum differs"
grep -q "($((episodes * 2)) replayed from the journal)" "$work/beyond.err" ||
  fail "the resume did not replay the whole journal: $(grep episodes "$work/beyond.err")"
kill -INT $serve_pid; wait $serve_pid || true; serve_pid=
echo "resume under beyond accepted: every episode replayed, the same checksum"

rc=0
"$controller" --bus loopback --noise 0.05,0.1 --out "$work/two" > "$work/two.out" 2> "$work/two.err" || rc=$?
[ $rc = 2 ] && grep -q -- "--noise" "$work/two.err" && [ ! -e "$work/two" ] ||
  fail "two σ for one run: exit $rc, $(cat "$work/two.err")"
echo "two σ for one run: $(head -n 1 "$work/two.err")"
