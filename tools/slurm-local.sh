#!/usr/bin/env bash
# tools/slurm-local.sh: affray split and merge on a real Slurm cluster, started here for the test.
#
#   tools/slurm-local.sh [--kill-one] [--port N] [--keep] [--scene RIB --tiles N --samples N] AFFRAY
#
# Starts a one-node cluster in a temporary directory, without systemd: munged with a key and
# socket of its own, then slurmctld and slurmd from a generated slurm.conf (the user running it as
# SlurmUser, proctrack/linuxproc, task/none, select/cons_tres; ports N and N+1, by default two free ports
# picked at random from 36800-38799, so that runs on one machine do not clash). It splits a
# 64 x 48 render of scenes/wave.rib with every AOV into 4 tiles (affray split), submits the job
# array and its merge job (OUT.submit.sh), waits for the merge, and compares the merged image with
# a single-process render byte for byte.
#   --kill-one  cancels array task 3 mid-render, once its checkpoint holds a finished tile
#               (scancel: SIGTERM, so affray keeps its checkpoint), checks that the merge job is
#               then cancelled (its afterok dependency can never be met), resubmits only task 3
#               (OUT.submit.sh 3, a new merge job with it), and checks that the rerun took tiles
#               from the checkpoint, that the image is the same and that the other tiles were not
#               rendered again.
#   --keep      keeps the temporary directory (logs, scripts, images) and prints its name.
#   --scene RIB, --tiles N, --samples N  split that scene (in place, as it is) into N tiles instead: for the
#               README's figures (the times from submission to merged image and of the single
#               render with every core are printed).
# Every daemon it starts is stopped on exit (trap EXIT), whatever happens; every wait has a timeout.
# Exit status: 0 passed, 1 failed, 77 skipped (slurmctld, slurmd, munged or sbatch is missing:
# tools/setup.sh installs them); CTest counts 77 as skipped (tests/CMakeLists.txt).
set -euo pipefail

kill_one=0 port=auto keep=0 affray="" scene="" tiles=4 samples=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --kill-one) kill_one=1 ;;
        --port) port="$2"; shift ;;
        --keep) keep=1 ;;
        --scene) scene=$(realpath "$2"); shift ;;
        --tiles) tiles="$2"; shift ;;
        --samples) samples=(--samples "$2"); shift ;;
        -*) echo "slurm-local: unknown option $1" >&2; exit 2 ;;
        *) affray="$1" ;;
    esac
    shift
done
[[ -n "$affray" ]] || { echo "usage: tools/slurm-local.sh [--kill-one] [--port N] [--keep] AFFRAY" >&2; exit 2; }
affray=$(realpath "$affray")
src=$(cd "$(dirname "$0")/.." && pwd)

for program in slurmctld slurmd munged mungekey sbatch squeue scontrol scancel sinfo; do
    if ! command -v "$program" >/dev/null && [[ ! -x /usr/sbin/$program ]]; then
        echo "slurm-local: SKIPPED: $program is not installed (tools/setup.sh installs slurm-wlm and munge)"
        exit 77
    fi
done
export PATH="$PATH:/usr/sbin"

tmp=$(mktemp -d /tmp/affray-slurm-XXXXXX)
chmod 755 "$tmp"
pids=()
cleanup() {
    local status=$?
    # Stop the daemons this script started, by their process ids, newest first.
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null || true; done
    for pid in "${pids[@]}"; do
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null || true
        wait "$pid" 2>/dev/null || true
    done
    if [[ $status -ne 0 && $status -ne 77 ]]; then
        for log in "$tmp"/slurmctld.log "$tmp"/slurmd.log "$tmp"/work/*.log; do
            [[ -f "$log" ]] && { echo "---- $log (last lines)"; tail -n 15 "$log"; }
        done
    fi
    if [[ $keep -eq 1 ]]; then echo "slurm-local: kept $tmp"; else rm -rf "$tmp"; fi
    exit $status
}
trap cleanup EXIT
trap 'exit 1' INT TERM

fail() { echo "slurm-local: FAILED: $*" >&2; exit 1; }
# wait_for SECONDS DESCRIPTION COMMAND...: polls COMMAND every 0.1 s until it succeeds.
wait_for() {
    local seconds=$1 what=$2
    shift 2
    local deadline=$((SECONDS + seconds))
    until "$@" >/dev/null 2>&1; do
        [[ $SECONDS -lt $deadline ]] || fail "no $what after ${seconds} s"
        sleep 0.1
    done
}

# Ports: two free ones (nothing answers on them), at random unless --port says.
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
if [[ "$port" == auto ]]; then
    for _ in $(seq 50); do
        port=$((36800 + RANDOM % 2000))
        port_free "$port" && port_free $((port + 1)) && break
    done
fi

# munge: its own key and socket.
mkdir -m 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key"
munged -F --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge.socket" \
    --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/munge/munged.log" --seed-file="$tmp/munge/munged.seed" \
    >"$tmp/munged.out" 2>&1 &
pids+=($!)
wait_for 10 "munge socket" test -S "$tmp/munge.socket"

# Slurm: one node with every core of this machine, one partition.
host=$(hostname -s)
cpus=$(nproc)
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/work"
export SLURM_CONF="$tmp/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=affraylocal
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
MinJobAge=600
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -c -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
wait_for 20 "slurmctld answering" scontrol ping
slurmd -D -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
node_idle() { sinfo -h -n "$host" -o %T | grep -qx idle; }
wait_for 30 "idle node" node_idle
echo "slurm-local: cluster up: node $host with $cpus CPUs, slurmctld on port $port"

# The scene: scenes/wave.rib at 64 x 48 with every AOV, its shader beside it.
cd "$tmp/work"
if [[ -z "$scene" ]]; then
    cp "$src/shaders/wave.sl" .
    sed -e 's/^Format .*/Format 64 48 1/' -e 's/"file" "rgba"/"file" "rgba,Z,N,P,st,cost,err"/' \
        "$src/scenes/wave.rib" >wave.rib
    scene=wave.rib
fi
# Task 3 must still be rendering when it is cancelled, after its first tile: at 64 samples each of
# its 4 tiles takes 0.5-1.5 s.
[[ $kill_one -eq 1 ]] && samples=(--samples 64)
"$affray" split "$scene" --tiles "$tiles" -o out.exr "${samples[@]}" >/dev/null

# job_state ID: the job's state (COMPLETED, FAILED, CANCELLED, RUNNING, PENDING...).
job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1; }
# wait_job ID SECONDS: waits until the job has ended; prints its state.
wait_job() {
    local deadline=$((SECONDS + $2)) state
    while :; do
        state=$(job_state "$1")
        case "$state" in
            COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | BOOT_FAIL | DEADLINE)
                echo "$state"; return ;;
        esac
        [[ $SECONDS -lt $deadline ]] || { echo "TIMEOUT_WAITING($state)"; return; }
        sleep 0.2
    done
}
submit() {
    local line
    line=$(./out.submit.sh "$@")
    echo "slurm-local: $line" >&2
    read -r render merge <<<"$(echo "$line" | sed 's/render job \([0-9]*\), merge job \([0-9]*\)/\1 \2/')"
}

now() { date +%s.%N; }
# since START: seconds elapsed since START (a now value), to 0.01 s.
since() { awk -v a="$(now)" -v b="$1" 'BEGIN { printf "%.2f", a - b }'; }
start=$(now)
submit
if [[ $kill_one -eq 1 ]]; then
    # Cancel task 3 once its checkpoint holds a finished tile (it has grown past its header, which
    # is written in one piece) and before the task finishes.
    larger_than() { [[ $(stat -c %s out.tile3.exr.checkpoint 2>/dev/null || echo 0) -gt $1 ]]; }
    wait_for 120 "checkpoint of task 3" larger_than 0
    header=$(stat -c %s out.tile3.exr.checkpoint)
    wait_for 120 "finished tile in the checkpoint of task 3" larger_than "$header"
    scancel "${render}_3"
    task=$(wait_job "${render}_3" 30)
    [[ "$task" == CANCELLED ]] || fail "task 3 ended $task, not CANCELLED"
    [[ ! -e out.tile3.exr ]] || fail "task 3 finished before it could be cancelled (make it slower)"
    [[ -f out.tile3.exr.checkpoint ]] || fail "the cancelled task left no checkpoint"
    state=$(wait_job "$merge" 60)
    [[ "$state" == CANCELLED ]] || fail "merge job $merge ended $state, not CANCELLED after task 3 was"
    [[ ! -e out.exr ]] || fail "an image was merged without tile 3"
    for t in 0 1 2; do
        [[ -f out.tile$t.exr ]] || fail "tile $t is missing after the array ran"
    done
    stamps=$(stat -c '%n %Y.%y' out.tile0.exr out.tile1.exr out.tile2.exr)
    echo "slurm-local: task 3 cancelled mid-render ($(stat -c %s out.tile3.exr.checkpoint) bytes of checkpoint);" \
        "merge job cancelled; resubmitting task 3 only"
    submit 3
fi
state=$(wait_job "$merge" 180)
elapsed=$(since "$start")
[[ "$state" == COMPLETED ]] || fail "merge job $merge ended $state"
[[ -f out.exr ]] || fail "the merge job wrote no out.exr"
if [[ $kill_one -eq 1 ]]; then
    [[ "$(stat -c '%n %Y.%y' out.tile0.exr out.tile1.exr out.tile2.exr)" == "$stamps" ]] ||
        fail "tiles other than 3 were rendered again"
    grep -h "checkpoint" out.render-"${render}"_3.log | sed 's/^/slurm-local: task 3 log: /' || true
    grep -q "resuming: [1-9][0-9]* of" out.render-"${render}"_3.log ||
        fail "the rerun of task 3 took no tile from its checkpoint"
fi

# The same render in one process, with every core.
start=$(now)
"$affray" render "$scene" -o single.exr --quiet "${samples[@]}"
single=$(since "$start")
cmp out.exr single.exr || fail "the merged image differs from the single-process render"
echo "slurm-local: PASSED: merged image = single-process render, byte for byte ($(stat -c %s out.exr) bytes);" \
    "submitted to merged: ${elapsed} s; single process on $cpus cores: ${single} s"
