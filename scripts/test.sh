#!/usr/bin/env bash
# The README's test command: install dependencies, build, run every test (unit tests,
# statistical and end-to-end validation, MPI bit-identity under mpirun).
#   scripts/test.sh --sanitize   instead: the suite under ASan+UBSan (build-asan/), then
#                                under TSan (build-tsan/); see docs/SANITIZERS.md
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = --sanitize ]; then
    shift
    exec bash "$root/tests/sanitizers/run.sh" "$@"
fi
bash "$root/scripts/install_deps.sh"
bash "$root/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$root/build"
ctest --output-on-failure -j2 --timeout 900
