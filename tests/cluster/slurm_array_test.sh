#!/usr/bin/env bash
# ctest `cluster`: a real single-node Slurm (munge + slurmctld + slurmd, started and stopped here,
# bound to 127.0.0.1, state in a temporary folder) runs tools/grader/slurm/grade-array.sh as an
# array of 3 shards over a batch of 31 corpus submissions, one of them in a dot folder; the shards'
# CSVs merged as docs/grading-reference.md says must equal a one-machine batch's CSV row for row (the seconds
# column left out). Exit 77 (skipped) only when Slurm or munge is not installed, without root (slurmd
# starts jobs as their user), or inside a chroot when the node does not come up or the array fails.
# Usage: slurm_array_test.sh CLOTHREF SOURCE_DIR CACHE_DIR
set -euo pipefail
clothref=$1 source=$2 cache=$3

for tool in munged slurmctld slurmd sbatch sinfo; do
  command -v "$tool" >/dev/null || PATH=$PATH:/usr/sbin
  command -v "$tool" >/dev/null ||
    { echo "SKIP: $tool not installed (tools/setup.sh installs slurm-wlm and munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "SKIP: slurmd needs root to start jobs"; exit 77; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/clothref-slurm-XXXXXX")
pids=()
cleanup() {
  # jobs first (a timed-out array must not keep grading), then the daemons, by their PIDs
  [ -z "${SLURM_CONF:-}" ] || timeout 10 scancel --quiet --partition=test 2>/dev/null || true
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  for log in "$tmp"/*.log "$tmp"/out/*.out; do [ -f "$log" ] && { echo "== $log"; tail -n 20 "$log"; }; done >&2
  exit 1
}
ready_within() {  # seconds command...: whether the command succeeds within that time
  local limit=$1
  shift
  for _ in $(seq $((limit * 5))); do "$@" >/dev/null 2>&1 && return 0; sleep 0.2; done
  return 1
}
wait_for() {  # seconds description command...
  local limit=$1 what=$2
  shift 2
  ready_within "$limit" "$@" || fail "$what not ready after ${limit}s"
}
# In a chroot (tools/check_fresh_debian.sh: a fresh Debian root, host /proc bound) munged refuses
# Slurm's credentials ("Unauthorized credential for client UID=0"): the node may never register,
# or Slurm 22.05 requeues each task after it exits 0. A skip there, a failure elsewhere.
in_chroot() { [ "$(stat -c %d:%i /)" != "$(stat -c %d:%i /proc/1/root/. 2>/dev/null)" ]; }
start=$(date +%s)

# munge: its own key, socket and files in the temporary folder.
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/out"
chmod 700 "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge/munge.key"
socket=$tmp/munge/munge.socket
munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$socket" \
  --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" \
  --log-file="$tmp/munged.log" >> "$tmp/munged.log" 2>&1 &
pids+=($!)
wait_for 10 munged test -S "$socket"

# Slurm on the loopback address, ports picked free.
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
host=$(hostname -s)
cat > "$tmp/slurm.conf" <<CONF
ClusterName=clothref-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
CommunicationParameters=NoInAddrAny
AuthType=auth/munge
AuthInfo=socket=$socket
CryptoType=crypto/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
MailProg=/bin/true
NodeName=clothref-node NodeAddr=127.0.0.1 NodeHostname=$host CPUs=2 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >> "$tmp/slurmctld.log" 2>&1 &
pids+=($!)
wait_for 20 slurmctld sinfo
slurmd -D -N clothref-node -f "$SLURM_CONF" >> "$tmp/slurmd.log" 2>&1 &
pids+=($!)
idle() { sinfo -h -n clothref-node -o %T | grep -q '^idle'; }
if ! ready_within 30 idle; then
  if in_chroot; then
    echo "SKIP: in a chroot the node never comes up (munged: Unauthorized credential for client UID=0)"
    exit 77
  fi
  fail "the node (idle) not ready after 30s"
fi
echo "slurm up after $(($(date +%s) - start)) s"

# The batch: 30 corpus submissions and one in a folder whose name starts with a dot (a glob without
# dotglob skips it); three shards through the checked-in array script.
"$source/tests/bench/make_corpus_batch.sh" "$tmp/subs"
cp -r "$tmp/subs/01-"* "$tmp/subs/.hidden"
export CLOTHREF=$clothref SUBMISSIONS=$tmp/subs BATCHDIR=$tmp/batch
export GRADE_OPTIONS="--cache-dir $cache"
if ! timeout 200 sbatch --quiet --wait --array=0-2 --output="$tmp/out/task-%a.out" \
  "$source/tools/grader/slurm/grade-array.sh"; then
  if in_chroot; then
    echo "SKIP: in a chroot Slurm requeues the array's tasks instead of finishing them"
    exit 77
  fi
  fail "the array did not finish (sbatch --wait)"
fi
echo "array done after $(($(date +%s) - start)) s"
# merged as docs/grading-reference.md says (shards 2 and 3 wrote no header), word for word
# shellcheck disable=SC2046  # the folder has no spaces; the docs command is copied as it is
cat $(for k in $(seq 1 3); do echo "$BATCHDIR/grades-$k-of-3.csv"; done) > "$tmp/merged.csv"

# the one-machine batch of every folder, dot folders included (docs/grading-reference.md)
shopt -s dotglob
"$clothref" grade "$tmp"/subs/*/ --out "$tmp/one" --jobs 2 --cache-dir "$cache" --quiet
shopt -u dotglob
python3 - "$tmp/merged.csv" "$tmp/one/grades.csv" <<'PY' || fail "the merged CSV differs"
import csv, sys
def rows(path):
    table = list(csv.reader(open(path, newline="")))
    drop = table[0].index("seconds")
    return [row[:drop] + row[drop + 1:] for row in table]
merged, one = rows(sys.argv[1]), rows(sys.argv[2])
assert len(one) == 32, f"{len(one)} lines in the one-machine CSV, expected 32 (31 rows)"
assert any(row[0] == "_.hidden" for row in one), "no row for the dot folder"
for k, (a, b) in enumerate(zip(merged, one)):
    assert a == b, f"line {k + 1}: shards {a} one machine {b}"
assert len(merged) == len(one), f"{len(merged)} merged lines, {len(one)} one-machine lines"
print(f"merged CSV of 3 shards equals the one-machine CSV: {len(one) - 1} rows")
PY
echo "cluster test done in $(($(date +%s) - start)) s"
