#!/usr/bin/env bash
# docs/REFERENCE.md section 4 against what a run writes: a small sobol run of
# tests/data/scenes/every_key.toml (illuminance and luminance detectors, three targets)
# that also writes a checkpoint; tests/result_reference.py compares both files with the tables.
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
/usr/bin/python3 "$src/tests/result_reference.py" "$src/docs/REFERENCE.md" "$work/r.h5" "$work/ck.h5"
rm -rf "$work"
