#!/usr/bin/env bash
# The sanitized test run (docs/SANITIZERS.md), what `scripts/test.sh --sanitize` does:
#   build-asan/  -DLUXTRACE_SANITIZE=address (ASan + UBSan, leaks on): the whole ctest suite
#                but slurm_end_to_end (see below)
#   build-tsan/  -DLUXTRACE_SANITIZE=thread  (ThreadSanitizer): the same suite; the tests
#                labelled "threads" (ctest -L threads) are the ones that run several
#                threads or ranks; the rest adds a few minutes
# Both RelWithDebInfo (-O2 -g, frame pointers) for usable stacks. Fails if any test fails.
# Usage: run.sh [address|thread]...   (default: both, ASan first)
# Environment: JOBS (parallel compile jobs, default nproc), CTEST_JOBS (default 2).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
kinds=("$@")
((${#kinds[@]})) || kinds=(address thread)
for k in "${kinds[@]}"; do
    case $k in address | thread) ;; *) echo "usage: $0 [address|thread]..." >&2; exit 2 ;; esac
done

bash "$root/scripts/install_deps.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

declare -A dir=([address]=build-asan [thread]=build-tsan)
declare -A what=([address]="ASan+UBSan" [thread]="TSan")
summary=() status=0
for k in "${kinds[@]}"; do
    build=$root/${dir[$k]}
    echo "=== $k: configure and build $build"
    t0=$SECONDS
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLUXTRACE_SANITIZE="$k" \
          -DLUXTRACE_BENCH=OFF >/dev/null
    cmake --build "$build" -j"${JOBS:-$(nproc)}"
    tb=$((SECONDS - t0))
    echo "=== $k: tests (${what[$k]})"
    t0=$SECONDS
    rc=0
    (
        # The sanitizer options of this tree (written by tests/CMakeLists.txt) for every
        # test, also those defined outside tests/CMakeLists.txt; a test's own
        # ENVIRONMENT property, where it has one, sets the same.
        while IFS= read -r kv; do [ -n "$kv" ] && export "$kv"; done <"$build/sanitizer.env"
        cd "$build"
        # slurm_end_to_end is left out: its limits (jobs of 1 to 5 minutes, 330 s for the
        # whole test) are set for the optimised build, and the sanitized luxtrace is 3 to 5
        # times slower, so it fails on time, not on a finding.
        ctest --output-on-failure -j"${CTEST_JOBS:-2}" --timeout 3600 --no-tests=error -E '^slurm_end_to_end$'
    ) || rc=$?
    tt=$((SECONDS - t0))
    ((rc == 0)) || status=1
    summary+=("$k (${what[$k]}): build ${tb} s, tests ${tt} s, $([ $rc -eq 0 ] && echo passed || echo FAILED)")
done
echo "=== sanitized run"
printf '%s\n' "${summary[@]}"
exit $status
