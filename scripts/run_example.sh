#!/usr/bin/env bash
# The README's first command: install dependencies, build, and simulate the bundled
# office under mpirun with 2 ranks. Results go to out/office/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install_deps.sh"
bash "$root/scripts/build.sh" --target luxtrace
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$root/out/office"
mkdir -p "$out"
lux="$root/build/src/luxtrace"
"$lux" check "$root/examples/office/office.toml"
echo
mpirun -n 2 --bind-to none --oversubscribe "$lux" run "$root/examples/office/office.toml" \
  --threads 1 --output "$out/office.h5"
echo
# Pictures: the room as seen by the scene's "overview" camera (global illumination from
# the stored maps), drawn by luxtrace; the desk and wall detectors (value, error,
# histogram, sections), drawn by the Python package with matplotlib.
"$lux" render "$out/office.h5" --view overview -o "$out/office_view.png"
/usr/bin/python3 "$root/scripts/plot_detector.py" "$out/office.h5" --detector desk --detector west_wall -o "$out"
echo
echo "Result file:   $out/office.h5   (luxtrace info $out/office.h5; in Python: python/luxtrace)"
echo "ParaView:      $out/office.xdmf"
echo "Rendered view: $out/office_view.png (luminance in $out/office_view.exr)"
echo "Desk pictures: $out/desk_value.png, desk_error.png, desk_error_hist.png, desk_sections.png"
echo "               (scripts/plot_detector.py; in Python: import luxtrace, README \"Results in Python\")"
