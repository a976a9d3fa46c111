#!/usr/bin/env bash
# CPU seconds to a given error of the annual example's sky and ground with the light after a
# diffuse reflection gathered (issue 37 §2; docs/PERFORMANCE.md "Annual daylight with the
# gather"). The example (examples/annual/annual_office.toml) with only its 120 sensor points
# (the grid the Radiance comparison used; the work plane's 320 cells taken out), written
# to a temporary directory with [annual] direct = "shadow_rays" and indirect = "gather",
# and run on 1 rank x 2 threads:
#   - once long as the reference (REFERENCE photons, seed 99, patches of 0.12 m and 1,024
#     shadow rays per sky patch and sensor: its own sampling errors well below the runs');
#   - at each of BUDGETS photons with SEEDS seeds, timed by /usr/bin/time (user + system
#     CPU seconds of the whole command: loading and the year's skies, the gather's table,
#     the shadow rays, tracing, and the post-processing with its 32 replicate years, the
#     pictures and the Ladybug folder).
# Measured per sensor: the year's exposure from the sky patches and the ground (the shadow
# rays' direct plus the gathered: the year's sky as one common sky matrix), its RMS relative
# error over the sensors against the reference, averaged over the seeds (root mean square),
# and the mean over sensors and seeds of z^2 = (run - reference)^2 / (sigma^2 +
# sigma_ref^2), which a right error model keeps near 1.
# Usage: bench/annual_gather_speed.sh   (from the repository root, after building)
# Environment: BUDGETS ("250k 500k 1M 2M"), SEEDS (3), REFERENCE (40M), KEEP=1 keeps the
# temporary directory.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
luxtrace="$repo/build/src/luxtrace"
budgets=${BUDGETS:-"250k 500k 1M 2M"}
seeds=${SEEDS:-3}
reference=${REFERENCE:-40M}
[[ -x $luxtrace ]] || { echo "annual_gather_speed.sh: build $luxtrace first" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d /tmp/annual_gather_speed.XXXXXX)
[[ ${KEEP:-0} == 1 ]] || trap 'rm -rf "$work"' EXIT
"$repo/bench/annual_example_scene.sh" --all-photons >"$work/example.toml"
/usr/bin/python3 - "$work" <<'PY'
import re, sys
work = sys.argv[1]
s = open(f"{work}/example.toml").read()
s = re.sub(r'\[\[detector\]\]\nname = "work_plane".*?(?=\[\[detector\]\])', "", s, flags=re.S)
s = s.replace("[annual]\n", '[annual]\ndirect = "shadow_rays"\nindirect = "gather"\n', 1)
open(f"{work}/gather.toml", "w").write(s)
open(f"{work}/reference.toml", "w").write(
    s.replace('indirect = "gather"\n', 'indirect = "gather"\ngather_patch_m = 0.12\ndirect_sky_rays = 1024\n'))
PY
run() {  # scene photons seed out
    /usr/bin/time -f "%U %S" -o "$4.time" "$luxtrace" run "$work/$1.toml" --photons "$2" --seed "$3" --threads 2 \
        --quiet --output "$4.h5" > "$4.log" 2>&1
}
run reference "$reference" 99 "$work/ref"
for n in $budgets; do
    for ((s = 1; s <= seeds; ++s)); do run gather "$n" "$s" "$work/gather_${n}_$s"; done
done
/usr/bin/python3 - "$work" "$seeds" $budgets <<'PY'
import sys, h5py, numpy as np
work, seeds, budgets = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
def sky(path):
    g = h5py.File(path, "r")["annual/detectors/sensors"]
    e = g["shadow_direct_sky_lx_h"][:] + g["gathered_sky_lx_h"][:]
    # What the discs still count (light off glossy, mirror and glass surfaces; none here).
    c = g["coefficients"]
    first_sun = int(c.attrs["first_sun_group"])
    assert c["count"][:first_sun].sum() == 0, "the example's room has no glossy surface"
    s = np.hypot(g["shadow_direct_sky_sigma_lx_h"][:], g["gathered_sky_sigma_lx_h"][:])
    return e, s
ref, ref_sigma = sky(f"{work}/ref.h5")
print("| photons | CPU s (mean of %d) | RMS error of the sky and ground exposure | mean z^2 |" % seeds)
print("|---|---|---|---|")
for b in budgets:
    errs, z2, cpu = [], [], []
    for s in range(1, seeds + 1):
        e, sigma = sky(f"{work}/gather_{b}_{s}.h5")
        errs.append(np.mean(((e - ref) / ref) ** 2))
        z2.append(np.mean((e - ref) ** 2 / (sigma ** 2 + ref_sigma ** 2)))
        cpu.append(sum(float(x) for x in open(f"{work}/gather_{b}_{s}.time").read().split()))
    print(f"| {b} | {np.mean(cpu):.2f} | {100 * np.sqrt(np.mean(errs)):.2f} % | {np.mean(z2):.2f} |")
PY
