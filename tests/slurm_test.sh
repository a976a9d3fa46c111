#!/usr/bin/env bash
# End to end on a real one-node Slurm cluster: the batch scripts in jobs/ are submitted
# with sbatch and their HDF5 results checked.
#   (a) one_node.sbatch, 2 ranks under mpirun     -> photons = budget, ranks = 2
#   (b) multi_node.sbatch, 1 rank x all CPUs, srun -> ranks = 1, threads = CPUs, and
#       tallies bit-identical to (a): same seed and budget on another split (SPEC §3)
#   (c) seed_array.sbatch, seeds 1 and 2          -> distinct tallies, means agreeing
#       within 4 sigma (independent estimates of one quantity)
#   (d) requeue.sbatch signalled with USR1 once its first checkpoint exists (and by
#       Slurm's own --signal before any 1-minute limit): checkpoint (exit 3), self-requeue,
#       restart from the checkpoint, finish; tallies bit-identical to an uninterrupted run.
# The cluster (munged, slurmctld, slurmd) is private to this test: its own key, socket,
# ports, state and log directories; root is not needed. It is always torn down.
# Usage: slurm_test.sh LUXTRACE WORKDIR
set -uo pipefail
[ $# -eq 2 ] || { echo "usage: $0 LUXTRACE WORKDIR"; exit 2; }
lux=$(readlink -f "$1") work=$2
here=$(cd "$(dirname "$0")" && pwd)
jobs=$here/../jobs
scene=$here/data/run/room.toml
py=/usr/bin/python3
t0=$SECONDS
status=0
pass() { echo "PASS: $*"; }
fail() { echo "FAIL: $*"; status=1; }
elapsed() { echo "[$((SECONDS - t0)) s]"; }

for tool in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel sinfo mpirun; do
    command -v $tool >/dev/null || { echo "FAIL: $tool not found (scripts/install_deps.sh installs slurm-wlm and munge)"; exit 1; }
done
"$py" -c "import h5py, numpy" 2>/dev/null || { echo "FAIL: $py cannot import h5py and numpy"; exit 1; }

# Daemons left by an earlier run of this test that was killed (kill -9 cannot be trapped).
for f in "$work"/run/*.pid; do
    [ -f "$f" ] || continue
    pid=$(cat "$f")
    case $(cat "/proc/$pid/comm" 2>/dev/null) in slurmctld | slurmd | munged) kill -KILL "$pid" ;; esac
done
[ -f "$work/run/rt" ] && [[ $(cat "$work/run/rt") == /tmp/luxslurm.* ]] && rm -rf "$(cat "$work/run/rt")"
rm -rf "$work"
mkdir -p "$work"/{etc,state,log,run,results}
chmod 700 "$work"
work=$(cd "$work" && pwd)
# Sockets (munged's, slurmstepd's, PMIx's) must have paths that fit in sun_path (108
# bytes): they live in a short private directory under /tmp. PMIx's per-step directories
# are named by job id alone, so they must not be in the shared /tmp (TmpFS) either.
rt=$(mktemp -d /tmp/luxslurm.XXXXXX)
chmod 755 "$rt"  # munged wants its socket directory searchable by all
mkdir -p "$rt/spool" "$rt/tmp"
echo "$rt" >"$work/run/rt"
munged_pid='' ctld_pid='' slurmd_pid=''
user=$(id -un)
host=$(hostname -s)

# Stop the process PID (ours) with TERM, then KILL after a few seconds.
stop_pid() {
    local pid=$1
    [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null || return 0
    kill -TERM "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || return 0; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null
}
teardown() {
    set +e
    local clean=yes
    if [ -n "$ctld_pid" ] && kill -0 "$ctld_pid" 2>/dev/null; then
        # Jobs first: a slurmstepd outlives slurmd, and would keep its job running.
        local ids
        ids=$(squeue -h -o %A 2>/dev/null | sort -u)
        [ -n "$ids" ] && scancel $ids 2>/dev/null
        clean=
        for _ in $(seq 100); do
            [ -z "$(squeue -h 2>/dev/null)" ] && ! ls "$rt/spool/${host}"_* >/dev/null 2>&1 && clean=yes && break
            sleep 0.2
        done
    fi
    if [ -z "$clean" ]; then
        # Left-overs of our jobs (slurmstepd, scripts, luxtrace) carry our SLURM_CONF and
        # live in sessions of their own; the test's own children share its session.
        echo "jobs did not end on scancel; killing what is left of them"
        local d p sid me
        me=$(ps -o sid= -p $$ | tr -d ' ')
        for d in /proc/[0-9]*; do
            p=${d#/proc/}
            case " $munged_pid $ctld_pid $slurmd_pid " in *" $p "*) continue ;; esac
            { tr '\0' '\n' <"$d/environ"; } 2>/dev/null | grep -qx "SLURM_CONF=$SLURM_CONF" || continue
            sid=$(ps -o sid= -p "$p" | tr -d ' ')
            [ -n "$sid" ] && [ "$sid" != "$me" ] && kill -KILL "$p"
        done
    fi
    stop_pid "$slurmd_pid"
    stop_pid "$ctld_pid"
    stop_pid "$munged_pid"
    rm -rf "$rt"
    echo "torn down $(elapsed)"
}
trap teardown EXIT
trap 'exit 1' INT TERM HUP

# --- A private munged -------------------------------------------------------------------
mungekey -c -k "$rt/munge.key" || { echo "FAIL: mungekey"; exit 1; }
setsid munged -F --socket="$rt/munge.sock" --key-file="$rt/munge.key" --pid-file="$work/run/munged.pid" \
    --seed-file="$rt/munged.seed" --log-file="$work/log/munged.log" </dev/null >"$work/log/munged.out" 2>&1 &
munged_pid=$!

# --- slurm.conf ---------------------------------------------------------------------------
read -r port_ctld port_slurmd < <("$py" -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
node=$(slurmd -C | head -1)
ncpu=$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$node")
export SLURM_CONF=$work/etc/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=luxtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port_ctld
SlurmdPort=$port_slurmd
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
# cred_expire: a requeued job may start again only after this (default 120 s).
AuthInfo=socket=$rt/munge.sock,cred_expire=10
StateSaveLocation=$work/state
SlurmdSpoolDir=$rt/spool
TmpFS=$rt/tmp
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
PlugStackConfig=$work/etc/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=bf_interval=1,sched_interval=2
MpiDefault=pmix
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MailProg=/bin/true
ReturnToService=2
MinJobAge=600
KillWait=5
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
: >"$work/etc/plugstack.conf"

for _ in $(seq 50); do [ -S "$rt/munge.sock" ] && break; sleep 0.1; done
[ -S "$rt/munge.sock" ] || { echo "FAIL: munged did not start:"; cat "$work/log/munged".*; exit 1; }

# --- Daemons: own session, every fd redirected (ctest waits for inherited fds) ---------
setsid slurmctld -D </dev/null >"$work/log/slurmctld.out" 2>&1 &
ctld_pid=$!
setsid slurmd -D </dev/null >"$work/log/slurmd.out" 2>&1 &
slurmd_pid=$!
state=
for _ in $(seq 150); do
    state=$(sinfo -h -o %T 2>/dev/null)
    [ "$state" = idle ] && break
    sleep 0.2
done
if [ "$state" != idle ]; then
    echo "FAIL: the node did not become idle (state '$state')"
    tail -n 20 "$work"/log/slurm*.log "$work"/log/*.out
    exit 1
fi
# setsid forks when it must; the daemons' own pid files are the truth.
munged_pid=$(cat "$work/run/munged.pid" 2>/dev/null || echo "$munged_pid")
ctld_pid=$(cat "$work/run/slurmctld.pid" 2>/dev/null || echo "$ctld_pid")
slurmd_pid=$(cat "$work/run/slurmd.pid" 2>/dev/null || echo "$slurmd_pid")
echo "cluster up: node $host, $ncpu CPUs, ports $port_ctld/$port_slurmd $(elapsed)"

# --- Submit ------------------------------------------------------------------------------
export LUXTRACE=$lux SCENE=$scene OUTDIR=$work/results LUXTRACE_ARGS=--quiet
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export MPIRUN_ARGS="--oversubscribe --mca btl self,vader --mca oob_tcp_if_include lo"
budget=2000000 budget_c=4000000
sub() {
    local id
    id=$(sbatch --parsable --chdir="$work" "$@")
    [[ $id =~ ^[0-9]+$ ]] || { echo "FAIL: sbatch $* did not return a job id ('$id')" >&2; exit 1; }
    echo "$id"
}
# Waits until the jobs IDS have left the queue; gives up 330 s into the test, so that
# even a slow teardown ends before ctest's timeout (400 s) kills the test without one.
wait_jobs() {
    local ids=$1 now last=
    while [ -n "$(squeue -h -j "$ids" 2>/dev/null)" ]; do
        if ((SECONDS - t0 > 330)); then
            echo "FAIL: jobs still queued 330 s into the test:"; squeue -j "$ids"; exit 1
        fi
        now=$(squeue -h -j "$ids" -o "%i:%t" | tr '\n' ' ')
        [ "$now" != "$last" ] && echo "queue: $now $(elapsed)"
        last=$now
        sleep 1
    done
}
job_field() { scontrol show job "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }

# Submitted in this order, they run in it (FIFO): (a) and (b) take the whole node.
id_a=$(PHOTONS=$budget SEED=5 sub --output="$work/a-%j.log" --ntasks=2 --cpus-per-task=1 --time=5 \
       "$jobs/one_node.sbatch") || exit 1
id_b=$(PHOTONS=$budget SEED=5 sub --output="$work/b-%j.log" --nodes=1 --cpus-per-task="$ncpu" --time=5 \
       "$jobs/multi_node.sbatch") || exit 1
id_c=$(PHOTONS=$budget_c sub --output="$work/c-%A_%a.log" --array=1-2 --cpus-per-task=1 --time=5 \
       "$jobs/seed_array.sbatch") || exit 1
echo "submitted: (a) $id_a, (b) $id_b, (c) $id_c $(elapsed)"
wait_jobs "$id_a,$id_b,$id_c"

# --- (d): the requeue job and its reference --------------------------------------------------
# Driven by an event, not by the clock: as soon as the first start has written its first
# checkpoint (one per reduction, every 200k photons), the test sends USR1 to the batch
# shell (scancel --signal=USR1 --batch: the path Slurm's --signal=B:USR1 takes). The
# start stops at once, checkpoints, exits 3 and requeues itself. The budget is 150 times
# the photons of that first checkpoint, so the start cannot finish before the signal
# lands unless the machine traces 150 x 200k photons in the time scancel takes; should
# that ever happen, the start finishing first is seen and (d) runs again with ten times
# the budget. Later starts still carry Slurm's own --signal=B:USR1@10 with --time=1, so a
# slow machine is simply requeued more often.
budget_d=30000000
submit_d() {
    id_d=$(PHOTONS=$budget_d SEED=11 CHECKPOINT_EVERY=0.001 LUXTRACE_ARGS="--quiet --report-every-photons 200k" \
           sub --output="$work/d-%j.log" --cpus-per-task=1 --time=1 --signal=B:USR1@10 "$jobs/requeue.sbatch") || exit 1
    id_ref=$(sub --output="$work/ref-%j.log" --cpus-per-task=1 --time=10 --job-name=reference --wrap="srun \
             --mpi=pmix $lux run $scene --photons $budget_d --seed 11 --threads 1 --quiet \
             --output $work/results/reference-$budget_d.h5") || exit 1
    echo "submitted: (d) $id_d, reference $id_ref $(elapsed)"
    local ck=$work/results/room-$id_d.ck.h5
    while [ ! -f "$ck" ] && [ -n "$(squeue -h -j "$id_d" 2>/dev/null)" ]; do sleep 0.1; done
    if [ -f "$ck" ]; then
        scancel --signal=USR1 --batch "$id_d" && echo "(d) first checkpoint written: USR1 sent $(elapsed)"
    fi
}
submit_d
wait_jobs "$id_d,$id_ref"
if [ "$(job_field "$id_d" Restarts)" = 0 ] && grep -q "^luxtrace-requeue: finished" "$work/d-$id_d.log"; then
    budget_d=$((10 * budget_d))
    echo "NOTE: (d) finished before the signal landed; again with $budget_d photons"
    submit_d
    wait_jobs "$id_d,$id_ref"
fi
echo "all jobs left the queue $(elapsed)"

for j in "$id_a" "$id_b" "${id_c}_1" "${id_c}_2" "$id_d" "$id_ref"; do
    st=$(job_field "$j" JobState) ec=$(job_field "$j" ExitCode)
    if [ "$st" = COMPLETED ] && [ "$ec" = 0:0 ]; then pass "job $j completed"
    else fail "job $j: state $st, exit code $ec"; fi
done

# --- (d): the job's own account of its starts -----------------------------------------------
log_d=$work/d-$id_d.log
restarts=$(job_field "$id_d" Restarts)
starts=$(grep -c "^luxtrace-requeue: job $id_d start" "$log_d")
if [ "${restarts:-0}" -ge 1 ] && [ "$starts" -eq $((restarts + 1)) ]; then
    pass "(d) ran $starts times (Restarts=$restarts)"
else fail "(d) should have been requeued: Restarts=$restarts, $starts starts in the log"; fi
grep -q "^luxtrace-requeue: restarting from" "$log_d" && pass "(d) restarted from its checkpoint" ||
    fail "(d) never restarted from a checkpoint"
grep -q "^checkpoint: $work/results/" "$log_d" && pass "(d) luxtrace reported writing a checkpoint" ||
    fail "(d) luxtrace did not report a checkpoint"
grep -q "^luxtrace-requeue: finished" "$log_d" && pass "(d) the last start finished" ||
    fail "(d) no start finished"
# Every USR1 must come before the 60 s limit of the start it interrupted.
signals=$("$py" - "$log_d" <<'EOF'
import re, sys
from datetime import datetime
start, late, n = None, 0, 0
for line in open(sys.argv[1]):
    m = re.match(r"luxtrace-requeue: (?:job \d+ start \d+ on \S+ at|USR1 at) (\S+)", line)
    if not m: continue
    t = datetime.fromisoformat(m.group(1).rstrip(","))
    if "USR1" in line:
        n += 1
        dt = (t - start).total_seconds()
        print(f"USR1 {dt:.0f} s after its start", file=sys.stderr)
        late += dt >= 60
    else:
        start = t
print(n, late)
EOF
)
read -r n_usr1 n_late <<<"$signals"
if [ "${n_usr1:-0}" -ge 1 ] && [ "$n_late" -eq 0 ] && [ "$n_usr1" -eq "${restarts:-0}" ]; then
    pass "(d) $n_usr1 USR1 signal(s), each before the time limit"
else fail "(d) USR1 signals: $n_usr1, $n_late of them late, Restarts=$restarts"; fi

# --- HDF5 results ---------------------------------------------------------------------------
"$py" - "$work/results" "$id_a" "$id_b" "$id_d" "$budget" "$budget_c" "$budget_d" "$ncpu" <<'EOF' || status=1
import sys, h5py, numpy as np
res, id_a, id_b, id_d = sys.argv[1:5]
budget, budget_c, budget_d, ncpu = map(int, sys.argv[5:9])
ok = True
def check(cond, what):
    global ok
    print(("PASS: " if cond else "FAIL: ") + what)
    ok = ok and bool(cond)
def tallies(f):
    names = [f"/global/{n}" for n in ("count_odd", "count_even", "direct_odd", "direct_even")]
    names += [f"/detectors/{d}/{n}" for d in f["detectors"] for n in ("count", "sumsq")]
    return {n: f[n][()] for n in names}
def identical(f, g):
    a, b = tallies(f), tallies(g)
    return a.keys() == b.keys() and all(a[n].dtype == np.uint64 and np.array_equal(a[n], b[n]) for n in a)
def result(path, photons, ranks=None, threads=None):
    f = h5py.File(path, "r")
    at = f.attrs
    check(at["format"] == "luxtrace-result" and at["format_version"] == 2,
          f"{path.split('/')[-1]}: format {at['format']} v{at['format_version']}")
    check(at["photons"] == photons and at["stop_reason"] == "photons",
          f"{path.split('/')[-1]}: {at['photons']} photons (budget {photons}), stopped by {at['stop_reason']}")
    if ranks is not None:
        check(at["ranks"] == ranks and at["threads_per_rank"] == threads,
              f"{path.split('/')[-1]}: {at['ranks']} rank(s) x {at['threads_per_rank']} thread(s), want {ranks} x {threads}")
    return f

a = result(f"{res}/room-{id_a}.h5", budget, 2, 1)
b = result(f"{res}/room-{id_b}.h5", budget, 1, ncpu)
check(identical(a, b), "(a) 2 ranks and (b) 1 rank: bit-identical tallies for the same seed and budget")

s1 = result(f"{res}/room-seed1.h5", budget_c)
s2 = result(f"{res}/room-seed2.h5", budget_c)
check((s1.attrs["seed"], s2.attrs["seed"]) == (1, 2), f"(c) seeds {s1.attrs['seed']} and {s2.attrs['seed']}")
check(not np.array_equal(s1["/global/count_odd"][()], s2["/global/count_odd"][()]), "(c) distinct seeds, distinct tallies")
# Independent estimates of the table's mean illuminance: |difference| within 4 sigma.
t1, t2 = s1["/detectors/table"].attrs, s2["/detectors/table"].attrs
m1, m2 = t1["mean_value"], t2["mean_value"]
z = abs(m1 - m2) / np.hypot(m1 * t1["mean_sigma_rel"], m2 * t2["mean_sigma_rel"])
check(z < 4, f"(c) table mean {m1:.3f} vs {m2:.3f} lx, z = {z:.2f} (< 4)")

d = result(f"{res}/room-{id_d}.h5", budget_d)
ck = h5py.File(f"{res}/room-{id_d}.ck.h5", "r")
check(ck.attrs["format"] == "luxtrace-checkpoint" and ck["/checkpoint"].attrs["budget"] == budget_d
      and 0 < ck.attrs["photons"] < budget_d,
      f"(d) checkpoint: {ck.attrs['format']}, {ck.attrs['photons']} of {ck['/checkpoint'].attrs['budget']} photons")
# A restart carries the checkpoint's history forward; a fresh run would have its own.
n = len(ck["/history/time_s"])
check(n > 0 and all(np.array_equal(ck[f"/history/{c}"][()], d[f"/history/{c}"][:n]) for c in ("time_s", "photons")),
      f"(d) the final result continues the checkpoint's history ({n} of {len(d['/history/time_s'])} rows)")
ref = result(f"{res}/reference-{budget_d}.h5", budget_d, 1, 1)
print(f"INFO: (d) traced {d.attrs['photons'] / d.attrs['elapsed_s']:.3g} photons/s over its starts, "
      f"its reference {ref.attrs['photons'] / ref.attrs['elapsed_s']:.3g}")
check(identical(d, ref), "(d) signalled + requeued + restarted: tallies bit-identical to the uninterrupted run")
sys.exit(0 if ok else 1)
EOF

echo "slurm end to end: $([ $status -eq 0 ] && echo passed || echo FAILED) in $((SECONDS - t0)) s"
exit $status
