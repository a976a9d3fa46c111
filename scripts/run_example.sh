#!/usr/bin/env bash
# The README's first command: install dependencies, build, and simulate the bundled
# office under mpirun with 2 ranks, then the daylit office (examples/daylight) and the same
# office over a year of weather (examples/annual). Results go to out/office/, out/daylight/
# and out/annual/.
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
echo

# The daylit office: a side-lit room under the CIE overcast sky (daylight factors, EN 17037)
# and under the sun of 21 March at 13:00 in Berlin (the sun patch), as two light scenes of
# one run; pictures of each scene's detector (README "Daylight").
day="$root/out/daylight"
mkdir -p "$day"
"$lux" check "$root/examples/daylight/side_lit_office.toml"
echo
mpirun -n 2 --bind-to none --oversubscribe "$lux" run "$root/examples/daylight/side_lit_office.toml" \
  --threads 1 --output "$day/side_lit_office.h5"
echo
/usr/bin/python3 "$root/scripts/plot_detector.py" "$day/side_lit_office.h5" --scene overcast --detector work_plane \
  -o "$day/overcast"
/usr/bin/python3 "$root/scripts/plot_detector.py" "$day/side_lit_office.h5" --scene sunny --detector floor -o "$day/sunny"
"$lux" render "$day/side_lit_office.h5" --view inside --scene sunny -o "$day/sunny/inside.png"
echo
echo "Daylight:      $day/side_lit_office.h5   (luxtrace info; the light scenes 'overcast' and 'sunny')"
echo "DF map:        $day/overcast/work_plane_df.png   (daylight factor %, median, 95 % value, EN 17037 verdict)"
echo "Sun patch:     $day/sunny/floor_value.png, rendered: $day/sunny/inside.png"

# The same office through a year of Chicago weather (examples/annual): every sky patch, the
# ground and every hour's sun as light groups of one run; each sensor's hourly illuminance
# and LM-83's sDA and ASE, UDI and EN 17037, each with its error (README "Annual daylight").
ann="$root/out/annual"
mkdir -p "$ann"
"$lux" check "$root/examples/annual/annual_office.toml" | grep -v "warning: sun of hour"
echo
mpirun -n 2 --bind-to none --oversubscribe "$lux" run "$root/examples/annual/annual_office.toml" \
  --threads 1 --output "$ann/annual_office.h5" --quiet
# The year, and each grid's sDA, ASE, UDI and EN 17037 with their errors.
"$lux" info "$ann/annual_office.h5"
/usr/bin/python3 "$root/scripts/plot_annual.py" "$ann/annual_office.h5" -o "$ann" >/dev/null
echo "Annual:        $ann/annual_office.h5   (/annual/detectors/work_plane and /sensors: hourly values, metrics)"
echo "               $ann/annual_office_ladybug/   (the Ladybug Tools results folder: honeybee-radiance-postprocess reads it)"
echo "               $ann/*.png   (DA and ASE maps of each grid, a sensor's hours x days)"

# A Radiance model as Honeybee wrote it (tests/data/radiance/honeybee: Honeybee's sample
# model folder, MIT, with a 10 000 lx overcast sky in Honeybee's format), run as it is with
# its office sensor grid: the Radiance files in oconv's order, --sensors for the .pts. Each
# sensor's illuminance and its error go to a plain table beside the result (docs/RADIANCE_USERS.md).
rad="$root/out/radiance"
hb="$root/tests/data/radiance/honeybee"
mkdir -p "$rad"
echo
(cd "$hb/model" && mpirun -n 2 --bind-to none --oversubscribe "$lux" run ../sky_10000lx.sky \
  scene/envelope.mat scene/shades.mat scene/envelope.rad scene/shades.rad aperture/aperture.mat aperture/aperture.rad \
  --sensors grid/office.pts --photons 100M --threads 1 --output "$rad/office.h5" --quiet)
echo "Radiance:      $rad/office.h5   (Honeybee's sample office, its 54-sensor grid)"
echo "               $rad/office.office.txt   (x y z E sigma_E per sensor, in the .pts order; E / 100 is the daylight factor in %)"
