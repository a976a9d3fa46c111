#!/usr/bin/env bash
# Strong and weak scaling of whole runs (issue 26, docs/SCALING.md): bench/scenes/million.toml
# traced on ranks x threads with the default reductions, the photon rate over the run's
# time without the BVH build (the result's elapsed_s - bvh_build_s: tracing and
# reductions; the load and the write are outside it) and the wall time of the whole
# command. Strong: a fixed budget on every layout; weak: a fixed budget per rank. Above
# 2 ranks x threads the 2-core machine is oversubscribed (--bind-to none): those rows
# measure time-sharing, not more cores.
#
#   bash bench/scaling.sh [BUILD_DIR] [PHOTONS] [LAYOUTS]
#   e.g. bash bench/scaling.sh build 8M "1x1 1x2 2x1 4x1 8x1"
set -euo pipefail
build=${1:-build}
photons=${2:-8M}
layouts=${3:-"1x1 1x2 2x1 4x1 8x1"}
here=$(cd "$(dirname "$0")" && pwd)
lux=$(cd "$build" && pwd)/src/luxtrace
scene=$here/scenes/million.toml
work=$(mktemp -d /tmp/luxtrace_scaling.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
count() { /usr/bin/python3 -c "import sys; s=sys.argv[1]; m={'k':1e3,'M':1e6}; print(int(float(s[:-1])*m[s[-1]]) if s[-1] in m else int(float(s)))" "$1"; }
base=$(count "$photons")

run() {  # $1 ranks, $2 threads, $3 photons: prints "wall_s rate"
    local out=$work/r.h5 cmd
    rm -f "$out"
    cmd=("$lux" run "$scene" --photons "$3" --threads "$2" --quiet --output "$out")
    (($1 > 1)) && cmd=(mpirun -n "$1" --oversubscribe --bind-to none --mca btl self,vader "${cmd[@]}")
    local t0 t1
    t0=$(date +%s.%N)
    "${cmd[@]}" >/dev/null
    t1=$(date +%s.%N)
    /usr/bin/python3 - "$out" "$t0" "$t1" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
a = f.attrs
rate = int(a["photons"]) / (float(a["elapsed_s"]) - float(a["bvh_build_s"]))
print(f"{float(sys.argv[3]) - float(sys.argv[2]):.2f} {rate:.4g}")
PY
}

for kind in strong weak; do
    echo "$kind scaling, bench/scenes/million.toml, $photons photons$([[ $kind == weak ]] && echo " per rank")"
    printf '%-8s %10s %12s %14s %12s %12s\n' layout photons "wall_s" "photons/s" "per thread" "per core"
    ref=""
    for layout in $layouts; do
        r=${layout%x*} t=${layout#*x}
        n=$base
        [[ $kind == weak ]] && n=$((base * r))
        read -r wall rate < <(run "$r" "$t" "$n")
        # Efficiency: the rate per tracing thread, and per core used (no more than the
        # machine has), against one rank x one thread's.
        [[ -z $ref ]] && ref=$(/usr/bin/python3 -c "print($rate / ($r * $t))")
        eff=$(/usr/bin/python3 -c "print(f'{$rate / ($r * $t) / $ref:.2f}')")
        core=$(/usr/bin/python3 -c "print(f'{$rate / min($r * $t, $(nproc)) / $ref:.2f}')")
        printf '%-8s %10d %12s %14s %12s %12s\n' "$layout" "$n" "$wall" "$rate" "$eff" "$core"
    done
done
