#!/usr/bin/env bash
# Loading speed of Radiance scenes against the mesh loaders (issue 25 "Speed";
# docs/PERFORMANCE.md "Loading Radiance scenes"). Writes one geometry, QUADS separate
# quadrilaterals (2 x QUADS triangles) on a wavy sheet, three ways in a temporary directory:
# a .rad of `polygon`s, an OBJ and an ASCII PLY of the same quads with the same numbers in
# the same text form (each quad its own four vertices, as in the .rad), and times
# read_radiance against load_mesh (assimp) on them with build/bench/radiance_load_bench.
# Usage: bench/radiance_load.sh   (from the repository root, after building radiance_load_bench)
# Environment: QUADS (1000000), REPEATS (3), KEEP=1 keeps the temporary directory,
# RADIANCE_LOAD_BENCH (the bench binary; build/bench/radiance_load_bench).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bench=${RADIANCE_LOAD_BENCH:-"$repo/build/bench/radiance_load_bench"}
quads=${QUADS:-1000000}
repeats=${REPEATS:-3}

[[ -x $bench ]] || { echo "radiance_load.sh: build $bench first (cmake --build build --target radiance_load_bench)" >&2; exit 2; }
work=$(mktemp -d /tmp/radiance_load.XXXXXX)
[[ ${KEEP:-0} == 1 ]] || trap 'rm -rf "$work"' EXIT

# One awk pass writes the three files: quad i at column i % side, row i / side, a flat
# 0.1 m square at a height that varies from quad to quad (numbers of several digits).
awk -v n="$quads" -v rad="$work/sheet.rad" -v obj="$work/sheet.obj" -v ply="$work/sheet.ply" \
    -v faces="$work/faces.ply" 'BEGIN {
    side = int(sqrt(n)) + 1
    print "void plastic grey\n0\n0\n5 .5 .5 .5 0 0\n" > rad
    print "# " n " quads" > obj
    printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n", 4 * n > ply
    printf "element face %d\nproperty list uchar int vertex_indices\nend_header\n", n > ply
    for (i = 0; i < n; i++) {
        x0 = (i % side) * 0.1; y0 = int(i / side) * 0.1
        z = sprintf("%.6g", 0.05 * sin(7.0 * x0) * cos(5.0 * y0))
        line = ""
        for (k = 0; k < 4; k++) {
            x = x0 + (k == 1 || k == 2) * 0.1; y = y0 + (k >= 2) * 0.1
            v = sprintf("%.6g %.6g %s", x, y, z)
            line = line " " v
            print "v " v > obj
            print v > ply
        }
        printf "grey polygon q%d\n0\n0\n12%s\n\n", i, line > rad
        printf "f %d %d %d %d\n", 4 * i + 1, 4 * i + 2, 4 * i + 3, 4 * i + 4 > obj
        printf "4 %d %d %d %d\n", 4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3 > faces
    }
}'
cat "$work/faces.ply" >>"$work/sheet.ply"  # PLY: every vertex, then every face
rm "$work/faces.ply"

echo "# radiance_load.sh: $quads quads ($((2 * quads)) triangles), $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)"
ls -l "$work" | awk 'NR > 1 {printf "#   %s %.1f MB\n", $9, $5 / 1e6}'
"$bench" "$work/sheet.rad" "$work/sheet.obj" "$work/sheet.ply" --repeats "$repeats"
