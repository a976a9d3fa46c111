#!/usr/bin/env bash
# Checkpoint/restart bit-identity. A run that is killed (kill -9 of a rank) and restarted
# from its last checkpoint on another number of ranks, and a run stopped by SIGTERM
# (exit 3) and restarted, must both give tallies bit-identical to an uninterrupted run.
#
# Driven by events, never by the clock: the interrupted runs get a budget no machine can
# finish (1e12 photons), the interruption comes when a checkpoint file appears or the
# first progress line is printed, and the restart then sets the budget to a little more
# than the checkpoint holds (`--photons` on a restart), which the uninterrupted reference
# run gets too.
# Usage: restart_test.sh LUXTRACE H5_TALLY_COMPARE MPIEXEC WORKDIR [SAMPLER [SCENE]]
# (SAMPLER: random, the default, or sobol; a restart takes the checkpoint's sampler.
# SCENE: tests/data/run/room.toml by default.)
set -uo pipefail
lux=$1 cmp=$2 mpiexec=$3 work=$4 sampler=${5:-random}
here=$(cd "$(dirname "$0")" && pwd)
scene=${6:-$here/data/run/room.toml}
rm -rf "$work"; mkdir -p "$work"
mpi=("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader --mca oob_tcp_if_include lo)
endless=1000000000000
fail() { echo "FAIL: $*"; exit 1; }
# An endless run must not outlive the test (a failure or ctest's timeout would leave it
# tracing): on exit, kill the background job still running and its ranks.
job=
cleanup() { [ -n "$job" ] && kill -0 "$job" 2>/dev/null && { pkill -9 -P "$job"; kill -9 "$job"; } 2>/dev/null; true; }
trap cleanup EXIT
trap 'exit 143' TERM

# Waits (without a deadline of its own: ctest's timeout is the bound) until the command
# "$@" succeeds or the job ends; returns 1 if the job ended first.
wait_for() {
    local job=$1; shift
    until "$@"; do kill -0 "$job" 2>/dev/null || { "$@"; return $?; }; sleep 0.02; done
}
reported() { grep -q '/s  global' "$1" 2>/dev/null; }
# The checkpoint's highest done photon index + 1, from `luxtrace info`.
covered() { "$lux" info "$1" | sed -n 's/^checkpoint .* below index \([0-9]*\),.*/\1/p'; }

# 1. Two ranks with a checkpoint at every reduction; kill -9 one rank as soon as a
#    checkpoint exists. Restart on 3 ranks up to 200k photons beyond what it covers
#    (so the restart fills the holes the other rank left and goes on past them).
"${mpi[@]}" -n 2 "$lux" run "$scene" --photons $endless --seed 11 --sampler "$sampler" --quiet --threads 1 \
    --report-every-photons 100k --checkpoint-every 0.001 --output "$work/a.h5" --checkpoint "$work/a.ck.h5" &
job=$!
wait_for $job test -f "$work/a.ck.h5" || fail "the run ended before writing a checkpoint"
# A rank of this run only: the ranks are mpiexec's children. (A pattern over command lines
# also matched the other sampler's copy of this test, run at the same time by ctest -j2,
# and killed a rank of its restart.)
victim=$(pgrep -P "$job" | tail -1)
[ -n "$victim" ] || fail "no rank to kill"
kill -9 "$victim"
wait $job; echo "killed run exited with $?"
[ -f "$work/a.h5" ] && fail "the killed run must not have written a result"
"$lux" info "$work/a.ck.h5" | grep '^checkpoint' || fail "luxtrace info does not describe the checkpoint"
budget_a=$(( $(covered "$work/a.ck.h5") + 200000 ))
# Too small a budget for what the checkpoint holds is refused, and nothing is written.
"$lux" run "$scene" --quiet --restart "$work/a.ck.h5" --photons 1000 --output "$work/a.h5" 2>"$work/small.err"
code=$?
[ $code -eq 2 ] && grep -q "already holds photons" "$work/small.err" || fail "a too small restart budget: exit $code, $(cat "$work/small.err")"
[ -f "$work/a.h5" ] && fail "a refused restart wrote a result"
if [ "$sampler" = sobol ]; then
    # The replicates are part of the photon sequence: a restart with another R is refused.
    "$lux" run "$scene" --quiet --restart "$work/a.ck.h5" --replicates 4 --photons $budget_a --output "$work/a.h5" \
        2>"$work/reps.err"
    code=$?
    [ $code -eq 2 ] && grep -q "made with 8" "$work/reps.err" || fail "a restart with other replicates: exit $code, $(cat "$work/reps.err")"
    [ -f "$work/a.h5" ] && fail "a refused restart wrote a result"
fi
"${mpi[@]}" -n 3 "$lux" run "$scene" --quiet --threads 1 --restart "$work/a.ck.h5" --photons $budget_a \
    --output "$work/a.h5" || fail "restart on 3 ranks"
"$lux" run "$scene" --photons $budget_a --seed 11 --sampler "$sampler" --quiet --threads 2 --output "$work/ref_a.h5" || fail "reference run"
"$cmp" "$work/ref_a.h5" "$work/a.h5" || fail "kill -9 + restart on 3 ranks differs from the uninterrupted run"
echo "kill -9 at the first checkpoint, restart on 3 ranks to $budget_a photons: identical"

# 2. SIGTERM once the run prints its first progress line: checkpoint and exit code 3.
#    Restart on 2 ranks.
"$lux" run "$scene" --photons $endless --seed 11 --sampler "$sampler" --threads 2 --report-every-photons 100k \
    --output "$work/b.h5" --checkpoint "$work/b.ck.h5" >"$work/b.log" 2>&1 &
job=$!
wait_for $job reported "$work/b.log" || fail "the run ended before reporting: $(cat "$work/b.log")"
kill -TERM $job
wait $job; code=$?
[ $code -eq 3 ] || fail "SIGTERM should give exit code 3, got $code: $(cat "$work/b.log")"
[ -f "$work/b.ck.h5" ] || fail "SIGTERM left no checkpoint"
budget_b=$(( $(covered "$work/b.ck.h5") + 200000 ))
"${mpi[@]}" -n 2 "$lux" run "$scene" --quiet --threads 1 --restart "$work/b.ck.h5" --photons $budget_b \
    --output "$work/b.h5" || fail "restart after SIGTERM"
"$lux" run "$scene" --photons $budget_b --seed 11 --sampler "$sampler" --quiet --threads 2 --output "$work/ref_b.h5" || fail "reference run"
"$cmp" "$work/ref_b.h5" "$work/b.h5" || fail "SIGTERM + restart differs from the uninterrupted run"
echo "SIGTERM at the first progress line, restart on 2 ranks to $budget_b photons: identical"

# 3. Litter of a writer killed during its write (.NAME.tmp.PID beside the checkpoint) is
#    removed by the next run writing that checkpoint, when its PID is dead; a live
#    writer's temporary and every other file stay.
sh -c 'exit 0' & dead=$!; wait $dead
for f in ".b.ck.h5.tmp.$dead" ".b.ck.h5.tmp.$$" ".b.ck.h5.tmp.x$dead" ".other.h5.tmp.$dead" "b.ck.h5.tmp.$dead"; do
    echo litter >"$work/$f"
done
"$lux" run "$scene" --quiet --threads 1 --restart "$work/b.ck.h5" --photons $budget_b --output "$work/b2.h5" \
    --checkpoint "$work/b.ck.h5" || fail "second restart"
[ -e "$work/.b.ck.h5.tmp.$dead" ] && fail "a dead writer's temporary was left"
for f in ".b.ck.h5.tmp.$$" ".b.ck.h5.tmp.x$dead" ".other.h5.tmp.$dead" "b.ck.h5.tmp.$dead"; do
    [ -e "$work/$f" ] || fail "$f is not a stale temporary of this checkpoint, yet it was removed"
done
echo "stale temporaries: removed exactly the dead writer's"
echo "restart bit-identity: passed"
