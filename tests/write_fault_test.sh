#!/usr/bin/env bash
# A run that has traced never loses its work (issue 35, docs/RELIABILITY.md "Nothing traced
# is lost"). Each step of writing after tracing is made to fail on purpose (the hidden
# option --inject-fault FILE:STEP): the estimates, the annual metrics, the HDF5 image, the
# rename, the Ladybug folder; then also the whole checkpoint it falls back on, leaving
# the tallies alone; and rank 0's decision after a reduction. Each time:
#   - one message names the step and says where the tallies are and the command that
#     writes the result from them; the exit code is 4 for the file system's refusal, 1
#     for anything else; no MPI_ABORT, no temporary left, an old result file kept;
#   - the printed command, run as printed, writes a result equal to an undisturbed run's
#     (every dataset and attribute but the run's timings: result_compare.py), and the
#     same Ladybug results folder.
# Also under mpirun with 2 ranks, and with periodic checkpoints that can only keep the
# tallies (the run goes on, and a restart from one continues bit-identically). The annual
# test room takes the steps only annual runs have; a small room the others.
# Usage: write_fault_test.sh LUXTRACE H5_TALLY_COMPARE MPIEXEC WORKDIR
set -uo pipefail
lux=$(readlink -f "$1") cmp=$(readlink -f "$2") mpiexec=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
compare=("/usr/bin/python3" "$here/result_compare.py")
rm -rf "$work"; mkdir -p "$work"
work=$(cd "$work" && pwd)
cd "$work" || exit 1
status=0
fail() { echo "FAIL: $*"; status=1; }
mpi=("$mpiexec" -n 2 --oversubscribe --bind-to none --mca btl self,vader --mca oob_tcp_if_include lo)
# The annual test room (4,071 light groups, a Ladybug results folder beside the result)
# takes every step of the write; the small room (run-control tests' own) the others, fast.
annual=$here/data/run/annual_room.toml
room=$here/data/run/room.toml
common=(--photons 40000 --seed 3 --threads 2 --report-every-photons 10000 --quiet)

"$lux" run "$annual" "${common[@]}" --output ref.h5 >ref.log 2>&1 || fail "annual reference run: $(cat ref.log)"
"$lux" run "$room" "${common[@]}" --output ref_room.h5 >ref_room.log 2>&1 || fail "room reference: $(cat ref_room.log)"

# Runs the command a failed run printed after "write the result from it with: ".
recover() {
    local printed
    printed=$(sed -n 's/.*write the result from it with: luxtrace run //p' "$1")
    [ -n "$printed" ] || { fail "$1: no command to write the result"; return 1; }
    # shellcheck disable=SC2086  # the printed command's words, as a user would paste them
    "$lux" run $printed --quiet >"$1.recover" 2>&1 || { fail "$1: the printed command failed: $(cat "$1.recover")"; return 1; }
}

# check CASE EXPECTED_CODE FAULTS SCENE REFERENCE [LAUNCHER...]: a run of SCENE with FAULTS
# injected, then its recovery, compared with the undisturbed run REFERENCE.
check() {
    local name=$1 want=$2 faults=$3 scene=$4 ref=$5
    shift 5
    local out=$name.h5
    echo precious >"$out"
    "$@" "$lux" run "$scene" "${common[@]}" --output "$out" --inject-fault "$faults" >"$name.log" 2>&1
    local code=$?
    echo "--- $name ($faults): exit $code"
    cat "$name.log"
    [ "$code" -eq "$want" ] || fail "$name: exit $code, expected $want"
    grep -q "MPI_ABORT\|internal error on rank" "$name.log" && fail "$name: the run aborted"
    grep -q "HDF5-DIAG" "$name.log" && fail "$name: HDF5's error stack was printed"
    [ "$(grep -c 'luxtrace: error:' "$name.log")" -eq 1 ] || fail "$name: not one error message"
    grep -q "write the result from it with: luxtrace run $scene --restart .* --output $out" "$name.log" ||
        fail "$name: the message gives no command to write the result"
    ls -A | grep -q '\.tmp\.' && fail "$name: a temporary was left: $(ls -A | grep '\.tmp\.')"
    if ! grep -q "the result $out was written" "$name.log"; then
        [ "$(cat "$out")" = precious ] || fail "$name: the old result file was not kept"
    fi
    recover "$name.log" || return
    "${compare[@]}" "$ref.h5" "$out" >"$name.compare" || fail "$name: the recovered result differs: $(cat "$name.compare")"
    if [ -d "${ref}_ladybug" ]; then
        diff -r "${ref}_ladybug" "${name}_ladybug" >/dev/null || fail "$name: the recovered Ladybug folder differs"
    fi
}

check estimates 1 result:estimates "$room" ref_room
grep -q "internal error while computing the estimates: injected fault" estimates.log || fail "estimates: step not named"
check annual 1 result:annual "$annual" ref
grep -q "while computing the annual metrics" annual.log || fail "annual: step not named"
check image 1 result:image "$room" ref_room
grep -q "while making the HDF5 file" image.log || fail "image: step not named"
check rename 4 result:rename "$room" ref_room
grep -q "rename.h5: cannot replace the file" rename.log || fail "rename: the file system's words"
check ladybug 1 result:ladybug "$annual" ref
grep -q "the result ladybug.h5 was written, the Ladybug results folder .* was not" ladybug.log ||
    fail "ladybug: the message should say the result was written"
# The whole checkpoint fails too (its estimates): the tallies alone are kept.
check tallies 1 result:image,checkpoint:estimates "$annual" ref
grep -q "could not be made whole.*the run's tallies alone are kept in tallies.h5.checkpoint.h5" tallies.log ||
    fail "tallies: no word of the tally checkpoint"
"$lux" info tallies.h5.checkpoint.h5 >tallies.info 2>&1 && grep -q "^tallies only" tallies.info ||
    fail "tallies: info on the tally checkpoint: $(cat tallies.info)"
# Two ranks: rank 0 fails, both end with its verdict, nothing aborts. (The history of a run
# on two ranks has a reduction more than on one: its reference runs on two.)
"${mpi[@]}" "$lux" run "$room" "${common[@]}" --output ref2.h5 >ref2.log 2>&1 || fail "2-rank reference: $(cat ref2.log)"
check mpi 1 result:image "$room" ref2 "${mpi[@]}"

# Rank 0's decision after the first reduction fails (a bug between reductions): every rank
# stops, the tallies are kept, and the printed command continues the run to the same
# tallies as the undisturbed run's.
"$lux" run "$room" "${common[@]}" --output decide.h5 --inject-fault run:decide >decide.log 2>&1
code=$?
cat decide.log
[ $code -eq 1 ] || fail "decide: exit $code, expected 1"
grep -q "internal error while deciding after a reduction" decide.log || fail "decide: step not named"
grep -q "MPI_ABORT" decide.log && fail "decide: the run aborted"
printed=$(sed -n 's/.*continue with: luxtrace run //p' decide.log)
if [ -n "$printed" ]; then
    # shellcheck disable=SC2086
    "$lux" run $printed --quiet >decide.recover 2>&1 || fail "decide: the printed command failed: $(cat decide.recover)"
    "$cmp" ref_room.h5 decide.h5 >/dev/null || fail "decide: the continued run's tallies differ"
else
    fail "decide: no command to continue"
fi

# Nothing can be kept: exit 1, and the message says so.
echo precious >none.h5
"$lux" run "$room" "${common[@]}" --output none.h5 --inject-fault result:image,checkpoint:image,tallies:image \
    >none.log 2>&1
code=$?
cat none.log
[ $code -eq 1 ] || fail "none: exit $code, expected 1"
grep -q "the checkpoint was not written either: .*making the HDF5 file" none.log && grep -q "no checkpoint of this run was written before" none.log || fail "none: message"
grep -q "MPI_ABORT" none.log && fail "none: the run aborted"

# Periodic checkpoints that can keep only the tallies: a warning each, the run goes on and
# writes its result; a restart from such a checkpoint continues bit-identically.
"$lux" run "$room" --photons 40000 --seed 3 --threads 2 --report-every-photons 10000 --quiet \
    --checkpoint-every 0.000001 --checkpoint periodic.ck.h5 --output periodic.h5 --inject-fault checkpoint:image \
    >periodic.log 2>&1
code=$?
[ $code -eq 0 ] || fail "periodic: exit $code: $(cat periodic.log)"
grep -q "could not be made whole" periodic.log || fail "periodic: no warning"
"${compare[@]}" ref_room.h5 periodic.h5 >/dev/null || fail "periodic: the result differs"
"$lux" run "$room" --restart periodic.ck.h5 --photons 60000 --report-every-photons 10000 --threads 2 --quiet \
    --output continued.h5 >continued.log 2>&1 || fail "periodic: restart: $(cat continued.log)"
"$lux" run "$room" --photons 60000 --seed 3 --threads 2 --report-every-photons 10000 --quiet \
    --output ref60.h5 >/dev/null 2>&1 || fail "reference run to 60k"
"$cmp" ref60.h5 continued.h5 >/dev/null || fail "periodic: the continued run's tallies differ"

# A fault that names no step is bad input: exit 2 before tracing, nothing written.
"$lux" run "$room" "${common[@]}" --output bad.h5 --inject-fault result:nothing >bad.log 2>&1
code=$?
[ $code -eq 2 ] && grep -q "inject-fault: 'result:nothing' is not FILE:STEP" bad.log && [ ! -e bad.h5 ] ||
    fail "bad fault: exit $code, $(cat bad.log)"

[ $status -eq 0 ] && echo "write faults: passed"
exit $status
