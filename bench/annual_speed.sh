#!/usr/bin/env bash
# Speed of annual daylight runs (issue 24 §5; docs/PERFORMANCE.md "Annual daylight").
# Scenes are derived from examples/annual/annual_office.toml in a temporary directory by
# changing only the work plane's cells and [annual] sky_mf (and making its two file paths
# absolute), without the example's `direct` and `indirect` keys: the all-photon runs this
# bench has measured since issue 24. Prints three tables:
#   1. wall time to a 1 %-point error of ASE and of mean DA (a budget the run cannot
#      finish, reductions every REPORT_EVERY photons, stopped at TARGET_TIME_LIMIT s);
#   2. fixed PHOTONS: tracing time (the result's elapsed_s) and post-processing (the
#      command's wall time minus elapsed_s: the annual estimate and the writing) against
#      sensors and sky patches, and the result's size;
#   3. the same fixed-photon run on 1, 2 and 4 ranks of 1 thread: photons/s.
# Usage: bench/annual_speed.sh   (from the repository root, after building build/src/luxtrace)
# Environment: PHOTONS (10M), REPORT_EVERY (5M), TARGET_TIME_LIMIT (300), PARTS
# ("target scale ranks": which tables to measure), KEEP=1 keeps the temporary directory.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
luxtrace="$repo/build/src/luxtrace"
python=/usr/bin/python3
photons=${PHOTONS:-10M}
report_every=${REPORT_EVERY:-5M}
target_time_limit=${TARGET_TIME_LIMIT:-300}
parts=${PARTS:-"target scale ranks"}

[[ -x $luxtrace ]] || { echo "annual_speed.sh: build $luxtrace first" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d /tmp/annual_speed.XXXXXX)
[[ ${KEEP:-0} == 1 ]] || trap 'rm -rf "$work"' EXIT

# scene NX NY MF [extra TOML appended to [run]] -> path of the derived scene
scene() {
    local nx=$1 ny=$2 mf=$3 extra=${4:-}
    local file="$work/office_${nx}x${ny}_mf${mf}${extra:+_target}.toml"
    "$repo/bench/annual_example_scene.sh" --all-photons |
        sed -e "s|^cells = \[16, 20\]|cells = [$nx, $ny]|" -e "s|^sky_mf = 1 |sky_mf = $mf |" >"$file"
    if ! grep -q "^cells = \[$nx, $ny\]" "$file" || ! grep -q "^sky_mf = $mf " "$file"; then
        echo "annual_speed.sh: the example's cells or sky_mf line changed" >&2
        exit 2
    fi
    [[ -n $extra ]] && printf '\n%s\n' "$extra" >>"$file"
    echo "$file"
}

# run RANKS SCENE OUTPUT [luxtrace options] -> "wall_s" on stdout, the log in OUTPUT.log
run() {
    local ranks=$1 file=$2 out=$3
    shift 3
    local t0 t1
    t0=$(date +%s.%N)
    mpirun -n "$ranks" --bind-to none --oversubscribe \
        "$luxtrace" run "$file" --threads 1 --output "$out" "$@" >"$out.log" 2>&1
    t1=$(date +%s.%N)
    echo "$t1 - $t0" | bc -l
}

# attrs OUTPUT -> "elapsed_s photons reductions stop_reason"
attrs() {
    "$python" - "$1" <<'EOF'
import sys, h5py
a = h5py.File(sys.argv[1], "r").attrs
print(f"{a['elapsed_s']:.2f} {int(a['photons'])} {int(a['reductions'])} {a['stop_reason']}".replace("target ", "target:"))
EOF
}

echo "# annual_speed.sh $(date -u +%Y-%m-%dT%H:%MZ), $(git -C "$repo" rev-parse --short HEAD)"
echo "# $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"

if [[ $parts == *target* ]]; then
    echo
    echo "## 1. Time to a 1 %-point error (25 x 40 work plane + 120 points, MF 1, 2 ranks, photons = 1e12, a reduction every $report_every photons, stopped at ${target_time_limit} s)"
    echo "| target | stop | wall s | elapsed_s | photons | reductions | final annual line |"
    echo "|---|---|---|---|---|---|---|"
    for metric in mean_da ase; do
        file=$(scene 25 40 1 "[[run.target]]
on = \"annual:work_plane:$metric\"
absolute_error = 0.01")
        out="$work/target_$metric.h5"
        wall=$(run 2 "$file" "$out" --photons 1e12 --report-every-photons "$report_every" \
            --time-limit "$target_time_limit")
        read -r elapsed n reductions stop <<<"$(attrs "$out")"
        line=$(sed -n "/^detector work_plane/,\$p" "$out.log" | grep -A2 "^  annual" | head -3 | tr -s ' ' | tr '\n' ' ')
        printf '| %s | %s | %.1f | %s | %s | %s | %s |\n' "$metric" "$stop" "$wall" "$elapsed" \
            "$n" "$reductions" "$line"
    done
    echo "(load average now: $(cut -d' ' -f1-3 /proc/loadavg))"
fi

if [[ $parts == *scale* ]]; then
    echo
    echo "## 2. Fixed $photons photons on 2 ranks: sensors (work plane + the 120 points) and patches"
    echo "| work plane | MF | groups | wall s | tracing (elapsed_s) | post-processing s | photons/s tracing | result MB | ladybug MB |"
    echo "|---|---|---|---|---|---|---|---|---|"
    for case in "10 25 1" "25 40 1" "50 80 1" "25 40 2" "25 40 4"; do
        read -r nx ny mf <<<"$case"
        file=$(scene "$nx" "$ny" "$mf")
        out="$work/scale_${nx}x${ny}_mf$mf.h5"
        wall=$(run 2 "$file" "$out" --photons "$photons")
        read -r elapsed n _ _ <<<"$(attrs "$out")"
        groups=$("$python" -c "import h5py,sys; print(len(h5py.File(sys.argv[1],'r').attrs['light_groups']))" "$out")
        printf '| %d x %d | %d | %d | %.1f | %.2f | %.1f | %.2e | %.1f | %.1f |\n' "$nx" "$ny" "$mf" \
            "$groups" "$wall" "$elapsed" "$(echo "$wall - $elapsed" | bc -l)" \
            "$(echo "$n / $elapsed" | bc -l)" "$(echo "$(stat -c %s "$out") / 1000000" | bc -l)" \
            "$(echo "$(du -sb "${out%.h5}_ladybug" | cut -f1) / 1000000" | bc -l)"
    done
    echo "(load average now: $(cut -d' ' -f1-3 /proc/loadavg))"
fi

if [[ $parts == *ranks* ]]; then
    echo
    echo "## 3. Fixed $photons photons, 25 x 40 work plane, MF 1, ranks of 1 thread (4 oversubscribed on $(nproc) cores)"
    echo "| ranks | wall s | tracing (elapsed_s) | photons/s tracing | photons/s wall |"
    echo "|---|---|---|---|---|"
    file=$(scene 25 40 1)
    for ranks in 1 2 4; do
        out="$work/ranks_$ranks.h5"
        wall=$(run "$ranks" "$file" "$out" --photons "$photons")
        read -r elapsed n _ _ <<<"$(attrs "$out")"
        printf '| %d | %.1f | %.2f | %.2e | %.2e |\n' "$ranks" "$wall" "$elapsed" \
            "$(echo "$n / $elapsed" | bc -l)" "$(echo "$n / $wall" | bc -l)"
    done
    echo "(load average now: $(cut -d' ' -f1-3 /proc/loadavg))"
fi
