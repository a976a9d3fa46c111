#!/usr/bin/env bash
# The annual example (examples/annual/annual_office.toml) on stdout with its two file paths
# (the weather file, the sensor points) made absolute, so that the annual benches can write
# it anywhere; with --all-photons, without its `direct` and `indirect` keys (every grid's
# light by the photons over the sensors' discs, the way issue 24's benches measured).
# Usage: bench/annual_example_scene.sh [--all-photons] > SCENE.toml
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
example="$repo/examples/annual"
drop=()
if [[ ${1:-} == --all-photons ]]; then drop=(-e '/^direct = /d' -e '/^indirect = /d')
elif [[ -n ${1:-} ]]; then echo "annual_example_scene.sh: unknown option $1" >&2; exit 2; fi
sed -e "s|\"\\.\\./\\.\\./tests/|\"$repo/tests/|" \
    -e "s|^points = \"work_plane.pts\"|points = \"$example/work_plane.pts\"|" \
    "${drop[@]}" "$example/annual_office.toml"
