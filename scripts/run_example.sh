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
echo "Result file: $out/office.h5   (luxtrace info $out/office.h5; read it with h5py)"
