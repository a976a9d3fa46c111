#!/usr/bin/env bash
# Reductions against ranks and triangles (issue 26, docs/SCALING.md): a closed box room of
# about 10^4, 10^5 and 10^6 triangles (an inward box of n subdivisions per face: 12 n^2
# triangles) and bench/scenes/ten_million.toml, each traced with a fixed budget on 1, 2,
# 4 and 8 ranks (above 2 ranks the 2-core machine is oversubscribed: --bind-to none), one
# tracing thread per rank (two on one rank), reductions every 0.5 s at first (the period
# rule then lengthens them as their cost asks). Prints one row per run from its result
# file: reductions, the stall, the main thread's work and its wait for the other ranks per
# reduction, the longest message's bytes, the photon rate over the run's time without the
# BVH build, and the peak resident memory (one rank only: under mpirun, mpirun's own).
# (Reductions at photon counts would make the ranks wait for each other at every fence.)
#
#   bash bench/reduction_scaling.sh [BUILD_DIR] [SIZES] [RANKS]
#   e.g. bash bench/reduction_scaling.sh build "1e4 1e5 1e6 1e7" "1 2 4 8"
# Runs of ten million triangles on 8 ranks need about 30 GB and are left out.
set -euo pipefail
build=${1:-build}
sizes=${2:-"1e4 1e5 1e6 1e7"}
ranks_list=${3:-"1 2 4 8"}
here=$(cd "$(dirname "$0")" && pwd)
lux=$(cd "$build" && pwd)/src/luxtrace
work=$(mktemp -d /tmp/luxtrace_scaling.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

box_scene() {  # $1 subdivisions, $2 file
    cat >"$2" <<TOML
[scene]
name = "box_$1"
bands = ["Y"]
[[material]]
name = "wall"
type = "diffuse"
reflectance = 0.6
[[shape]]
type = "box"
center = [5, 4, 2]
size = [10, 8, 4]
inward = true
material = "wall"
subdivisions = $1
[[light]]
type = "point"
position = [3, 4, 3.5]
flux_lm = 2000
[[light]]
type = "point"
position = [7, 4, 3.5]
flux_lm = 1000
[run]
seed = 1
photons = "1M"
TOML
}

printf '%-9s %5s %7s %6s %10s %10s %10s %12s %12s %8s\n' triangles ranks threads reds "stall_ms" "work_ms" "wait_ms" "msg_bytes" "photons/s" "rss_GB"
for size in $sizes; do
    case $size in
    1e4) scene=$work/box_29.toml; box_scene 29 "$scene"; photons=4M ;;
    1e5) scene=$work/box_91.toml; box_scene 91 "$scene"; photons=4M ;;
    1e6) scene=$work/box_289.toml; box_scene 289 "$scene"; photons=4M ;;
    1e7) scene=$here/scenes/ten_million.toml; photons=4M ;;
    *) echo "reduction_scaling: unknown size $size (1e4, 1e5, 1e6 or 1e7)" >&2; exit 2 ;;
    esac
    for ranks in $ranks_list; do
        [[ $size == 1e7 && $ranks -gt 4 ]] && continue
        threads=$((ranks == 1 ? 2 : 1))
        out=$work/r.h5
        rm -f "$out"
        cmd=("$lux" run "$scene" --photons "$photons" --report-every 0.5 --threads "$threads" --quiet
             --output "$out")
        if ((ranks > 1)); then
            cmd=(mpirun -n "$ranks" --oversubscribe --bind-to none --mca btl self,vader "${cmd[@]}")
        fi
        /usr/bin/time -f '%M' -o "$work/rss" "${cmd[@]}" >/dev/null
        rss_kb=$(tail -1 "$work/rss")
        ((ranks > 1)) && rss_kb=0
        /usr/bin/python3 - "$out" "$ranks" "$threads" "$rss_kb" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
a = f.attrs
n = int(a["reductions"])
T = f["mesh"]["triangles"].shape[0] if "triangles" in f["mesh"] else 0
rate = int(a["photons"]) / (float(a["elapsed_s"]) - float(a["bvh_build_s"]))
per = lambda k: 1e3 * float(a[k]) / n
print(f'{T:<9d} {sys.argv[2]:>5} {sys.argv[3]:>7} {n:>6d} {per("reduction_stall_s"):>10.2f} '
      f'{per("reduction_work_s"):>10.2f} {per("reduction_wait_s"):>10.2f} {int(a["reduction_message_bytes"]):>12d} '
      f'{rate:>12.4g} {int(sys.argv[4]) / 1048576:>8.2f}')
PY
    done
done
