#!/usr/bin/env bash
# docs/REFERENCE.md section 4 against what runs write: a small sobol run of
# tests/data/scenes/every_key.toml (illuminance and luminance detectors, a task area, three
# targets) that also writes a checkpoint, and one of tests/data/reference/more_keys.toml
# (cylindrical with horizontal, semicylindrical, an observer with luminaires in view and
# notes, a maintenance factor all lights share) and one of
# tests/data/reference/daylight_keys.toml (sun and skies with ground glow: /daylight, a
# daylight_factor detector with en17037, a task area and a light scene);
# and one of tests/data/reference/annual_keys.toml ([annual]); and a bare Radiance model
# run; tests/result_reference.py compares the six files with the tables.
#   result_reference_test.sh LUXTRACE WORKDIR
set -euo pipefail
lux=$1
work=$2
src=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$work"
mkdir -p "$work"
"$lux" run "$src/tests/data/scenes/every_key.toml" --photons 40k --sampler sobol --replicates 4 \
    --report-every-photons 20k --checkpoint-every 0.000001 --checkpoint "$work/ck.h5" \
    --output "$work/r.h5" --threads 2 --quiet
test -f "$work/ck.h5" || { echo "no checkpoint was written" >&2; exit 1; }
"$lux" run "$src/tests/data/reference/more_keys.toml" --photons 20k --output "$work/more.h5" --threads 2 --quiet
"$lux" run "$src/tests/data/reference/daylight_keys.toml" --photons 20k --output "$work/daylight.h5" --threads 2 \
    --quiet
# tests/data/reference/annual_keys.toml: [annual] (/annual and its detectors).
"$lux" run "$src/tests/data/reference/annual_keys.toml" --photons 20k --output "$work/annual.h5" --threads 2 --quiet
# A bare Radiance model run (the radiance_* root attributes): the Cornell box and two sensors.
printf '0 0 -0.4 0 0 1\n0.2 0 -0.4 0 0 1\n' > "$work/cornell.pts"
"$lux" run "$src/tests/data/radiance/cornell.rad" --sensors "$work/cornell.pts" --sensor-radius 0.05 --scale 1 \
    --photons 20k --output "$work/radiance.h5" --threads 2 --quiet
/usr/bin/python3 "$src/tests/result_reference.py" "$src/docs/REFERENCE.md" "$work/r.h5" "$work/ck.h5" \
    "$work/more.h5" "$work/daylight.h5" "$work/annual.h5" "$work/radiance.h5"
rm -rf "$work"
