#!/usr/bin/env bash
# I/O faults lose nothing and say why (docs/RELIABILITY.md). On a 256 kB tmpfs that the
# result does not fit on, a read-only file system, a read-only result file and (run as an
# unprivileged user) a directory without write permission:
#   - one message naming the file and the operating system's reason, never HDF5's
#     diagnostic stack;
#   - a result that cannot be written: exit 4, the old file kept, no temporary left, and
#     the run's tallies in a checkpoint from which the result can be written later,
#     bit-identical to an uninterrupted run;
#   - a checkpoint that cannot be written: a warning, the previous checkpoint kept, the
#     run goes on and writes its result;
#   - a place that is not writable at all: refused before tracing (exit 2), nothing
#     written.
# Mounting needs root (or CAP_SYS_ADMIN): where it is not allowed the test says SKIP and
# exits 77 (ctest's SKIP_RETURN_CODE).
# Usage: io_fault_test.sh LUXTRACE H5_TALLY_COMPARE WORKDIR
set -uo pipefail
lux=$1 cmp=$2 work=$3
rm -rf "$work"; mkdir -p "$work"
work=$(cd "$work" && pwd)
fail() { echo "FAIL: $*"; status=1; }
status=0
full=$work/full ro=$work/ro
mkdir -p "$full" "$ro"
cleanup() { umount "$full" 2>/dev/null; umount "$ro" 2>/dev/null; }
trap cleanup EXIT
if ! mount -t tmpfs -o size=256k tmpfs "$full" 2>"$work/mount.err"; then
    echo "SKIP: cannot mount a tmpfs here ($(cat "$work/mount.err")); run as root to test full disks"
    exit 77
fi
mount -t tmpfs -o ro,size=1m tmpfs "$ro" || { echo "SKIP: cannot mount a read-only tmpfs"; exit 77; }

# 307,200 triangles: the result (mesh and maps) is a few MB and its tallies alone about
# 460 kB, more than the tmpfs holds.
cat >"$work/big.toml" <<'EOF'
[[material]]
name = "grey"
reflectance = 0.5
[[shape]]
type = "box"
center = [2, 2, 1.5]
size = [4, 4, 3]
inward = true
subdivisions = 160
material = "grey"
[[light]]
type = "point"
position = [2, 2, 2.5]
flux_lm = 1000
EOF
scene=$work/big.toml
common=(--photons 200000 --seed 5 --threads 2 --report-every-photons 50000)
no_diag() { ! grep -q "HDF5-DIAG" "$1" || fail "$2: HDF5's error stack was printed"; }

# A. The result does not fit: exit 4, the reason, the old file kept, the tallies in the
#    checkpoint (written elsewhere), and the result made from it later is the right one.
echo precious >"$full/out.h5"
"$lux" run "$scene" "${common[@]}" --quiet --output "$full/out.h5" --checkpoint "$work/a.ck.h5" >"$work/a.log" 2>&1
code=$?
cat "$work/a.log"
[ $code -eq 4 ] || fail "A: a result that does not fit should give exit 4, got $code"
grep -q "$full/out.h5.*No space left on device" "$work/a.log" || fail "A: the message names the file and the reason"
grep -q -- "--restart $work/a.ck.h5" "$work/a.log" || fail "A: the message says where the tallies are kept"
no_diag "$work/a.log" A
[ "$(cat "$full/out.h5")" = precious ] || fail "A: the old result file was not kept"
[ -z "$(ls -A "$full" | grep -v '^out.h5$')" ] || fail "A: litter left on the full disk: $(ls -A "$full")"
"$lux" run "$scene" --quiet --restart "$work/a.ck.h5" --output "$work/a.h5" >"$work/a2.log" 2>&1 ||
    fail "A: the result could not be made from the checkpoint: $(cat "$work/a2.log")"
"$lux" run "$scene" "${common[@]}" --quiet --output "$work/ref.h5" >/dev/null || fail "reference run"
"$cmp" "$work/ref.h5" "$work/a.h5" >/dev/null || fail "A: the result made from the checkpoint differs from an uninterrupted run"

# B. Checkpoints do not fit: a warning each time, the run goes on, its result is written.
"$lux" run "$scene" "${common[@]}" --quiet --checkpoint-every 0.001 --output "$work/b.h5" \
    --checkpoint "$full/b.ck.h5" >"$work/b.log" 2>&1
code=$?
head -3 "$work/b.log"
[ $code -eq 0 ] || fail "B: a run whose checkpoints fail should still finish (exit 0), got $code"
grep -q "warning: checkpoint not written: $full/b.ck.h5.*No space left on device.*the run goes on" "$work/b.log" ||
    fail "B: no warning naming the checkpoint and the reason"
no_diag "$work/b.log" B
"$cmp" "$work/ref.h5" "$work/b.h5" >/dev/null || fail "B: the result differs from the uninterrupted run"
[ -z "$(ls -A "$full" | grep -v '^out.h5$')" ] || fail "B: litter left on the full disk: $(ls -A "$full")"

# C. Neither fits: exit 4 and the message says that no checkpoint holds the tallies.
"$lux" run "$scene" "${common[@]}" --quiet --output "$full/c.h5" --checkpoint "$full/c.ck.h5" >"$work/c.log" 2>&1
code=$?
[ $code -eq 4 ] || fail "C: exit 4 expected, got $code"
grep -q "checkpoint was not written either.*No space left on device" "$work/c.log" ||
    fail "C: the message should say that the checkpoint failed too: $(cat "$work/c.log")"
no_diag "$work/c.log" C

# G. The result cannot be made (an internal fault injected in its HDF5 image) and the
#    checkpoint's disk is full: the tallies alone are kept beside the result (issue 35).
"$lux" run "$scene" "${common[@]}" --quiet --output "$work/g.h5" --checkpoint "$full/g.ck.h5" \
    --inject-fault result:image >"$work/g.log" 2>&1
code=$?
cat "$work/g.log"
[ $code -eq 1 ] || fail "G: exit 1 expected, got $code"
grep -q "are kept in the checkpoint $work/g.h5.checkpoint.h5" "$work/g.log" ||
    fail "G: the tallies should be kept beside the result"
no_diag "$work/g.log" G
[ -z "$(ls -A "$full" | grep -v '^out.h5$')" ] || fail "G: litter left on the full disk: $(ls -A "$full")"
"$lux" run "$scene" --quiet --restart "$work/g.h5.checkpoint.h5" --output "$work/g.h5" >"$work/g2.log" 2>&1 ||
    fail "G: the result could not be made from the tallies: $(cat "$work/g2.log")"
"$cmp" "$work/ref.h5" "$work/g.h5" >/dev/null || fail "G: the result made from the tallies differs"

# D. A read-only file system, E. a read-only result file: refused before tracing, exit 2.
"$lux" run "$scene" "${common[@]}" --quiet --output "$ro/d.h5" >"$work/d.log" 2>&1
code=$?
[ $code -eq 2 ] && grep -q "$ro/d.h5.*Read-only file system" "$work/d.log" ||
    fail "D: read-only file system: exit $code, $(cat "$work/d.log")"
echo keep >"$work/e.h5"; chmod 444 "$work/e.h5"
"$lux" run "$scene" "${common[@]}" --quiet --output "$work/e.h5" >"$work/e.log" 2>&1
code=$?
[ $code -eq 2 ] && grep -q "$work/e.h5.*read-only" "$work/e.log" || fail "E: read-only file: exit $code, $(cat "$work/e.log")"
[ "$(cat "$work/e.h5")" = keep ] || fail "E: the read-only file was changed"

# F. A directory without write permission (root ignores permissions: run as nobody).
mkdir -p "$work/locked"; chmod 555 "$work/locked"
as_user=()
if [ "$(id -u)" -eq 0 ]; then
    if command -v setpriv >/dev/null && setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null; then
        as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
        chmod o+rx "$work"
    else
        echo "SKIP part F: cannot run as an unprivileged user"
    fi
fi
if [ "$(id -u)" -ne 0 ] || [ ${#as_user[@]} -gt 0 ]; then
    "${as_user[@]}" "$lux" run "$scene" "${common[@]}" --quiet --output "$work/locked/f.h5" >"$work/f.log" 2>&1
    code=$?
    [ $code -eq 2 ] && grep -q "$work/locked/f.h5.*Permission denied" "$work/f.log" ||
        fail "F: unwritable directory: exit $code, $(cat "$work/f.log")"
    [ -z "$(ls -A "$work/locked")" ] || fail "F: something was written in the locked directory"
fi

[ $status -eq 0 ] && echo "io faults: passed"
exit $status
