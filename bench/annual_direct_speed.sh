#!/usr/bin/env bash
# Error against CPU time of the annual example's sky and ground, with the direct light by
# photons and by shadow rays (issue 37 §2; docs/PERFORMANCE.md "Annual daylight with the
# direct light by shadow rays"). The example (examples/annual/annual_office.toml) is copied
# to a temporary directory twice, without its `direct` and `indirect` keys (all photons) and
# with [annual] direct = "shadow_rays" alone (its two file paths made absolute), and run on
# 1 rank x 2 threads:
#   - once long (REFERENCE photons, seed 99) each way: the reference;
#   - at each of BUDGETS photons with SEEDS seeds each way, timed by /usr/bin/time (user +
#     system CPU seconds of the whole command: loading, the shadow rays, tracing and the
#     post-processing with its replicate years and the Ladybug folder).
# Measured: per sensor of the 120-point grid, the year's exposure from the sky patches and
# the ground (the sum of their coefficients: the year's sky as one common sky matrix), the
# photons' part from the coefficients' counts plus, with shadow rays, their direct part
# (shadow_direct_sky_lx_h). Its RMS relative error over the sensors against the same way's
# reference, averaged over the seeds (root mean square), and the CPU seconds, per budget.
# Usage: bench/annual_direct_speed.sh   (from the repository root, after building)
# Environment: BUDGETS ("2M 5M 10M 20M"), SEEDS (3), REFERENCE (160M), KEEP=1 keeps the
# temporary directory, REUSE=DIR takes the references from DIR (ref_photons.h5, ref_shadow.h5).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
luxtrace="$repo/build/src/luxtrace"
budgets=${BUDGETS:-"2M 5M 10M 20M"}
seeds=${SEEDS:-3}
reference=${REFERENCE:-160M}
[[ -x $luxtrace ]] || { echo "annual_direct_speed.sh: build $luxtrace first" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d /tmp/annual_direct_speed.XXXXXX)
[[ ${KEEP:-0} == 1 ]] || trap 'rm -rf "$work"' EXIT

"$repo/bench/annual_example_scene.sh" --all-photons > "$work/photons.toml"
sed 's|^\[annual\]|[annual]\ndirect = "shadow_rays"|' "$work/photons.toml" > "$work/shadow.toml"

run() {  # way photons seed out
    /usr/bin/time -f "%U %S" -o "$4.time" "$luxtrace" run "$work/$1.toml" --photons "$2" --seed "$3" --threads 2 \
        --quiet --output "$4.h5" > "$4.log" 2>&1
}
for way in photons shadow; do
    if [[ -n ${REUSE:-} ]]; then cp "$REUSE/ref_$way.h5" "$work/ref_$way.h5"
    else run "$way" "$reference" 99 "$work/ref_$way"; fi
    for n in $budgets; do
        for ((s = 1; s <= seeds; ++s)); do run "$way" "$n" "$s" "$work/${way}_${n}_$s"; done
    done
done

/usr/bin/python3 - "$work" "$seeds" $budgets <<'PY'
import sys, h5py, numpy as np
work, seeds, budgets = sys.argv[1], int(sys.argv[2]), sys.argv[3:]

def sky_exposure(path):
    f = h5py.File(path, "r")
    g = f["annual/detectors/sensors"]
    c = g["coefficients"]
    n = c["count"][:].astype(float)
    first_sun = int(c.attrs["first_sun_group"])
    value = f["detectors/sensors/value"][:].ravel()
    total = n.sum(axis=0)
    k = np.median(value[total > 0] / total[total > 0])  # e0 / (pi r^2): the same for every sensor
    e = k * n[:first_sun].sum(axis=0)
    if "shadow_direct_sky_lx_h" in g:
        e = e + g["shadow_direct_sky_lx_h"][:]
    return e

print("| way | photons | CPU s (mean of %d) | RMS error of the sky and ground exposure |" % seeds)
print("|---|---|---|---|")
for way in ("photons", "shadow"):
    ref = sky_exposure(f"{work}/ref_{way}.h5")
    for b in budgets:
        errs, cpu = [], []
        for s in range(1, seeds + 1):
            e = sky_exposure(f"{work}/{way}_{b}_{s}.h5")
            errs.append(np.mean(((e - ref) / ref) ** 2))
            cpu.append(sum(float(x) for x in open(f"{work}/{way}_{b}_{s}.time").read().split()))
        print(f"| {way} | {b} | {np.mean(cpu):.1f} | {100 * np.sqrt(np.mean(errs)):.2f} % |")
PY
