#!/usr/bin/env bash
# The cluster path tried on a real Slurm (Debian's slurm-wlm + munge), single node, as root:
# starts munged, slurmctld and slurmd of its own (temporary folder, free ports, own munge
# socket and key), then
#   1. submits a 15-seed × 3-algorithm campaign with `curio-lab slurm --submit`, waits, and
#      checks the merged results equal a local `curio-lab run` of the same campaign file by
#      file (summary.json less its wall-time fields, summary.md less its wall-time line,
#      plot scripts with the output folder's name replaced; everything else byte for byte);
#   2. kills one task of an ODE campaign mid-way, resubmits, checks that only that task's
#      missing runs ran again, that the merge then succeeds and equals the local run;
#   3. submits `curio-lab slurm-train` for two seeds, one already finished, with a stand-in
#      training script, and checks only the other one trained.
# Stops the daemons it started, by PID. Exit 77 (skipped) when not root or Slurm is missing.
#
#   tests/lab/slurm_campaign.sh CURIO_LAB [KEEP_DIR]     (KEEP_DIR: keep the folder there)
set -euo pipefail

lab=$(realpath "$1")
keep=${2:-}
skip() { echo "SKIP: $*"; exit 77; }
[[ $(id -u) == 0 ]] || skip "needs root (it starts munged, slurmctld and slurmd on localhost)"
for b in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel sinfo jq; do
  command -v "$b" > /dev/null ||
    skip "$b missing (toolchain/setup-debian.sh installs slurm-wlm, munge and jq)"
done

start=$(date +%s)
tmp=$(mktemp -d /tmp/curio_slurm.XXXXXX)
pids=()
cleanup() {
  set +e
  [[ -n ${SLURM_CONF:-} ]] && scancel --quiet --user=root > /dev/null 2>&1 && sleep 1
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2> /dev/null; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2> /dev/null || break; sleep 0.1; done
    kill -9 "$p" 2> /dev/null
  done
  if [[ -n $keep ]]; then rm -rf "$keep" && mv "$tmp" "$keep" && echo "kept in $keep"
  else rm -rf "$tmp"; fi
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  for f in "$tmp"/log/*.log; do echo "== $f"; tail -n 20 "$f"; done
  exit 1
}

free_port() {
  local p
  while :; do
    p=$((20000 + RANDOM % 20000))
    ss -Htln "sport = :$p" 2> /dev/null | grep -q . || { echo "$p"; return; }
  done
}

# --- munge: our own key and socket, so a system munged (if any) is left alone ---
mkdir -p "$tmp"/{munge,state,spool,log}
chmod 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key"
chmod 400 "$tmp/munge/munge.key"
munged --foreground --force --socket="$tmp/munge/munge.socket" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/log/munged.log" \
  --seed-file="$tmp/munge/munged.seed" 2> "$tmp/log/munged.stderr.log" &
pids+=($!)
for _ in $(seq 50); do [[ -S $tmp/munge/munge.socket ]] && break; sleep 0.1; done
[[ -S $tmp/munge/munge.socket ]] || fail "munged did not start"

# --- slurm.conf (what works in a container as root: no cgroups, no accounting) ---
host=$(hostname -s)
export SLURM_CONF=$tmp/slurm.conf
cat > "$SLURM_CONF" << EOF
ClusterName=curio-test
SlurmctldHost=$host
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/munge.socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmUser=root
SlurmdUser=root
ReturnToService=2
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
MinJobAge=600
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -f "$SLURM_CONF" > "$tmp/log/slurmctld.stdout.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" > "$tmp/log/slurmd.stdout.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  state=$(sinfo -h -o %T 2> /dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.2
done
[[ $state == idle ]] || fail "the node did not come up (sinfo: '$state')"
echo "slurm up in $(($(date +%s) - start)) s ($host, $(nproc) CPUs)"

# Waits until none of the given jobs is queued or running (at most $2 seconds).
wait_jobs() {
  local ids=$1 limit=$2 t0
  t0=$(date +%s)
  while [[ -n $(squeue -h -t PD,R,CF,CG,S -j "$ids" 2> /dev/null) ]]; do
    (($(date +%s) - t0 < limit)) || fail "jobs $ids still queued after $limit s: $(squeue -j "$ids")"
    sleep 0.5
  done
}
job_state() { scontrol show job "$1" | grep -o 'JobState=[A-Z_]*' | head -n 1 | cut -d= -f2; }
job_id() { sed -n "s/^submitted $1 job \([0-9]*\).*/\1/p" "$2"; }

# Local results vs merged: every file of the local run, byte for byte, except the wall times.
compare() {
  local a=$1 b=$2 f
  # The local run's manifest.json and records/ (what makes it resumable) have no merged twin.
  local_files() { (cd "$a" && find . -path ./records -prune -o -type f ! -path ./manifest.json -print); }
  for f in $(local_files | sort); do
    case $f in
      ./summary.json)
        cmp <(jq 'del(.wall_seconds) | del(.results[].seconds_per_run)' "$a/$f") \
            <(jq 'del(.wall_seconds) | del(.results[].seconds_per_run)' "$b/$f") ||
          fail "$f differs beyond its wall times" ;;
      ./summary.md) cmp <(sed 3d "$a/$f") <(sed 3d "$b/$f") || fail "$f differs beyond line 3" ;;
      *.gp) cmp <(sed "s|$a|OUT|g" "$a/$f") <(sed "s|$b|OUT|g" "$b/$f") || fail "$f differs" ;;
      *) cmp "$a/$f" "$b/$f" || fail "$f differs" ;;
    esac
  done
  local na nb
  na=$(local_files | wc -l)
  nb=$(cd "$b" && find . -path ./tasks -prune -o -path ./slurm -prune -o -type f -print | wc -l)
  [[ $na == "$nb" ]] || fail "$b has $nb result files, the local run $na"
  echo "  $na files equal ($(cd "$a" && find . -name '*.png' | wc -l) PNGs, $(ls "$a/runs" | wc -l) run CSVs)"
}

# --- 1. 15 seeds × 3 algorithms, one array, one merge ---
campaign=(--algos RPE,RGE-EFR,MGE-EFR --seeds 0-14 --noise 0.05 --physics kinematic --episodes 2000)
t1=$(date +%s)
"$lab" slurm "${campaign[@]}" --chunk 5 --out "$tmp/c1" --submit | tee "$tmp/submit1.txt"
array=$(job_id array "$tmp/submit1.txt")
merge=$(job_id merge "$tmp/submit1.txt")
[[ -n $array && -n $merge ]] || fail "no job ids printed"
grep -q "#SBATCH --array=0-8" "$tmp/c1/slurm/array.sbatch" || fail "array.sbatch: not 9 tasks"
(cd "$tmp" && "$lab" run "${campaign[@]}" --quiet --out "$tmp/local1" > /dev/null)
wait_jobs "$array,$merge" 300
[[ $(job_state "$merge") == COMPLETED ]] || fail "merge job $merge: $(job_state "$merge")"
echo "campaign 1: 45 runs in 9 array tasks + merge, $(($(date +%s) - t1)) s from submission"
compare "$tmp/local1" "$tmp/c1"

# --- 2. a task killed mid-way, then resubmitted ---
ode=(--algos RGE-EFR,MGE-EFR --seeds 0-2 --physics ode --episodes 1000)
t2=$(date +%s)
"$lab" slurm "${ode[@]}" --chunk 3 --time 10 --out "$tmp/c2" --submit | tee "$tmp/submit2.txt"
array=$(job_id array "$tmp/submit2.txt")
merge=$(job_id merge "$tmp/submit2.txt")
records=$tmp/c2/tasks/task-0/records
for _ in $(seq 600); do
  [[ $(ls "$records"/run-*.cbor 2> /dev/null | wc -l) -ge 1 ]] && break
  sleep 0.05
done
scancel "${array}_0"
sleep 1
done_before=$(ls "$records"/run-*.cbor 2> /dev/null | wc -l)
((done_before >= 1 && done_before < 3)) || fail "task 0 had $done_before of 3 runs when killed"
stamp_before=$(stat -c '%n %i %Y' "$records"/run-*.cbor)
wait_jobs "$array,$merge" 120
[[ $(job_state "$merge") != COMPLETED ]] || fail "the merge ran after a killed task"
echo "campaign 2: task 0 killed with $done_before of 3 runs recorded; merge job $(job_state "$merge")"
"$lab" merge "$tmp/c2/tasks" --out "$tmp/c2_partial" > "$tmp/partial.txt" 2>&1 &&
  fail "merge of a partial campaign succeeded"
grep -q "missing run" "$tmp/partial.txt" || fail "the merge does not list the missing runs"
"$lab" slurm "${ode[@]}" --chunk 3 --time 10 --out "$tmp/c2" --submit | tee "$tmp/submit3.txt"
grep -q "indices 0)" "$tmp/submit3.txt" || fail "the resubmission is not task 0 alone"
array=$(job_id array "$tmp/submit3.txt")
merge=$(job_id merge "$tmp/submit3.txt")
(cd "$tmp" && "$lab" run "${ode[@]}" --quiet --out "$tmp/local2" > /dev/null)
wait_jobs "$array,$merge" 120
[[ $(job_state "$merge") == COMPLETED ]] || fail "merge job $merge after resubmission: $(job_state "$merge")"
grep -q "$done_before already recorded, skipped" "$tmp/c2/slurm/logs/task-0.out" ||
  fail "task 0 did not skip its recorded runs: $(cat "$tmp/c2/slurm/logs/task-0.out")"
[[ $(stat -c '%n %i %Y' $(echo "$stamp_before" | cut -d' ' -f1)) == "$stamp_before" ]] ||
  fail "recorded runs were written again"
echo "campaign 2: resubmitted task 0 ran $((3 - done_before)) run(s), merged, $(($(date +%s) - t2)) s in all"
compare "$tmp/local2" "$tmp/c2"

# --- 3. training seeds: one finished, one to train ---
cat > "$tmp/train.sh" << 'EOF'
#!/usr/bin/env bash
# Stand-in for train_beta_vae.sh: OUT_DIR SEED, a done marker at the end.
mkdir -p "$1/4_tuned" && echo "seed $2 threads $THREADS" > "$1/4_tuned/log" && touch "$1/4_tuned/done"
EOF
mkdir -p "$tmp/train/seed-3/4_tuned" && touch "$tmp/train/seed-3/4_tuned/done"
"$lab" slurm-train --script "$tmp/train.sh" --seeds 2,3 --out "$tmp/train" --time 5 --submit |
  tee "$tmp/submit4.txt"
array=$(job_id array "$tmp/submit4.txt")
grep -q "indices 2)" "$tmp/submit4.txt" || fail "slurm-train did not leave out the finished seed"
wait_jobs "$array" 60
[[ $(cat "$tmp/train/seed-2/4_tuned/log") == "seed 2 threads 2" ]] || fail "seed 2 did not train"
[[ ! -e $tmp/train/seed-3/4_tuned/log ]] || fail "the finished seed 3 trained again"
echo "slurm-train: seed 2 trained, finished seed 3 left out"

echo "PASS in $(($(date +%s) - start)) s"
