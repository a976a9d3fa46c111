#!/usr/bin/env bash
# Checkpoint/restart bit-identity. A fixed-budget run that is killed (kill -9 of a rank)
# and restarted from its last checkpoint on another number of ranks, and a run stopped
# by SIGTERM (exit 3) and restarted, must both give tallies bit-identical to an
# uninterrupted run.
# Usage: restart_test.sh LUXTRACE H5_TALLY_COMPARE MPIEXEC WORKDIR
set -uo pipefail
lux=$1 cmp=$2 mpiexec=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
scene=$here/data/run/room.toml
rm -rf "$work"; mkdir -p "$work"
mpi=("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader --mca oob_tcp_if_include lo)
budget=6000000
common=(--photons $budget --seed 11 --quiet)
fail() { echo "FAIL: $*"; exit 1; }

"$lux" run "$scene" "${common[@]}" --threads 2 --output "$work/ref.h5" || fail "reference run"

# 1. Two ranks with frequent checkpoints; kill -9 one rank once a checkpoint exists.
"${mpi[@]}" -n 2 "$lux" run "$scene" "${common[@]}" --threads 1 --report-every 0.2 \
    --checkpoint-every 0.2 --output "$work/a.h5" --checkpoint "$work/a.ck.h5" &
job=$!
for _ in $(seq 1200); do [ -f "$work/a.ck.h5" ] && break; sleep 0.05; done
[ -f "$work/a.ck.h5" ] || fail "no checkpoint appeared"
sleep 0.5
victim=$(pgrep -f "luxtrace run .*a.ck.h5" | grep -v "^$job$" | tail -1)
[ -n "$victim" ] && kill -9 "$victim"
wait $job; echo "killed run exited with $?"
[ -f "$work/a.h5" ] && fail "the killed run must not have written a result"
done_photons=$(h5dump -a /photons "$work/a.ck.h5" 2>/dev/null | grep -o '([0-9]*): [0-9]*' | awk '{print $2}')
echo "checkpoint holds $done_photons of $budget photons"
[ -n "$done_photons" ] && [ "$done_photons" -gt 0 ] && [ "$done_photons" -lt $budget ] || fail "checkpoint should be partial"
"${mpi[@]}" -n 3 "$lux" run "$scene" --quiet --threads 1 --restart "$work/a.ck.h5" --output "$work/a.h5" \
    || fail "restart on 3 ranks"
"$cmp" "$work/ref.h5" "$work/a.h5" || fail "kill -9 + restart on 3 ranks differs from the uninterrupted run"

# 2. SIGTERM: checkpoint, exit code 3, restart on 2 ranks.
"$lux" run "$scene" "${common[@]}" --threads 2 --report-every 0.2 --output "$work/b.h5" --checkpoint "$work/b.ck.h5" &
job=$!
sleep 2
kill -TERM $job
wait $job; code=$?
[ $code -eq 3 ] || fail "SIGTERM should give exit code 3, got $code"
[ -f "$work/b.ck.h5" ] || fail "SIGTERM left no checkpoint"
"${mpi[@]}" -n 2 "$lux" run "$scene" --quiet --threads 1 --restart "$work/b.ck.h5" --output "$work/b.h5" \
    || fail "restart after SIGTERM"
"$cmp" "$work/ref.h5" "$work/b.h5" || fail "SIGTERM + restart differs from the uninterrupted run"
echo "restart bit-identity: passed"
