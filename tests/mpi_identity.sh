#!/usr/bin/env bash
# Bit-identical tallies whatever the split: the same seed and photon budget must give the
# same uint64 counts on 1 rank x 1 thread, 1 rank x 2 threads, 2 ranks x 1 thread and
# 3 ranks x 2 threads; a different seed must not (so the comparison can fail).
# Usage: mpi_identity.sh LUXTRACE H5_TALLY_COMPARE MPIEXEC WORKDIR [SAMPLER [SCENE]]
# (SAMPLER: random, the default, or sobol, whose per-replicate grids are compared too;
# SCENE: tests/data/run/room.toml by default; with light groups their own counts are
# compared as well, with [annual] every detector's coefficients.)
set -euo pipefail
lux=$1 cmp=$2 mpiexec=$3 work=$4 sampler=${5:-random}
here=$(cd "$(dirname "$0")" && pwd)
scene=${6:-$here/data/run/room.toml}
mkdir -p "$work"
mpi=("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader --mca oob_tcp_if_include lo)
common=(--photons 300000 --seed 7 --quiet --sampler "$sampler")
"$lux" run "$scene" "${common[@]}" --threads 1 --output "$work/r1t1.h5"
"$lux" run "$scene" "${common[@]}" --threads 2 --output "$work/r1t2.h5"
# 2 ranks share an annual scene's post-processing, one part each, as the ranks of two nodes
# would (the hidden --annual-parts ranks); 3 ranks on one node leave it to rank 0.
"${mpi[@]}" -n 2 "$lux" run "$scene" "${common[@]}" --threads 1 --annual-parts ranks --output "$work/r2t1.h5"
"${mpi[@]}" -n 3 "$lux" run "$scene" "${common[@]}" --threads 2 --output "$work/r3t2.h5"
"$lux" run "$scene" --photons 300000 --seed 8 --quiet --sampler "$sampler" --threads 2 --output "$work/seed8.h5"
# A run stopped by a target at a reduction at photon counts holds exactly that
# reduction's photons, whatever the threads and their timing at the end. (Not across rank
# counts: each rank traces its own share of the photon indices between reductions.)
target=(--photons 1e9 --target 0.03 --report-every-photons 20000 --seed 7 --quiet --sampler "$sampler")
"$lux" run "$scene" "${target[@]}" --threads 1 --output "$work/t1.h5"
"$lux" run "$scene" "${target[@]}" --threads 2 --output "$work/t2.h5"
"${mpi[@]}" -n 2 "$lux" run "$scene" "${target[@]}" --threads 1 --output "$work/t3.h5"
"${mpi[@]}" -n 2 "$lux" run "$scene" "${target[@]}" --threads 2 --output "$work/t4.h5"
status=0
for other in r1t2 r2t1 r3t2; do
    if "$cmp" "$work/r1t1.h5" "$work/$other.h5"; then echo "identical: r1t1 vs $other"
    else echo "FAIL: r1t1 and $other differ"; status=1; fi
done
# The reductions of the 2-rank run left out the sides no rank had hit (a closed room's
# outer faces): at most the tally words minus (5 + R) slots per band and map group for each
# unlit side (R the sobol replicates, whose arrivals each side keeps too), and less by the
# detector blocks no rank wrote in. An annual scene's sun groups reach few cells: most of
# its detector words are left out. The map's counts since the previous reduction travel as
# 32-bit words: fewer bytes than 8 per word.
if /usr/bin/python3 - "$work/r2t1.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
a, g = f.attrs, f["global"]
T, B = g["count_odd"].shape[0], g["count_odd"].shape[2]
R = int(a["replicates"]) if "replicates" in a else 0
G = len(a["light_groups"]) if int(a.get("group_maps", 1)) else 1
unlit = 2 * T - int(g.attrs["lit_sides"])
words, tally = int(a["reduction_message_words"]), int(a["tally_words"])
nbytes = int(a["reduction_message_bytes"])
most = tally - unlit * (5 + R) * B * G
annual = "annual" in f
print(f"reduction message: {words} words ({nbytes} bytes), tallies {tally}, {unlit} of {2 * T} sides unlit, at most {most}")
ok = unlit > 0 and 0 < words <= most and nbytes < 8 * words and (not annual or words < tally // 2)
sys.exit(0 if ok else 1)
PY
then echo "the reduction message leaves out the unlit sides and unwritten blocks"
else echo "FAIL: the reduction message is not the lit sides' and written blocks' tallies"; status=1; fi
for pair in "t1 t2" "t3 t4"; do
    set -- $pair
    if "$cmp" "$work/$1.h5" "$work/$2.h5" >/dev/null; then echo "identical: a target met at photon counts, $1 vs $2"
    else echo "FAIL: the target-stopped runs $1 and $2 differ"; status=1; fi
done
if "$cmp" "$work/r1t1.h5" "$work/seed8.h5" >/dev/null; then
    echo "FAIL: seeds 7 and 8 gave identical tallies"; status=1
else echo "different seeds differ, as they must"; fi
exit $status
