#!/usr/bin/env bash
# Runs one libFuzzer target of build-fuzz/ (tests/fuzz/README.md) on a working copy of
# its committed corpus:
#   bash tests/fuzz/run_fuzzer.sh TARGET SECONDS [more libFuzzer options]
# TARGET is scene, ies, mesh, result, weather, pts or radiance. New inputs go to build-fuzz/fuzz/TARGET/corpus,
# crashes to build-fuzz/fuzz/TARGET/artifacts/, the log to build-fuzz/fuzz/TARGET/log.
# LUXTRACE_FUZZ_WORK=DIR puts corpus/, artifacts/ and log there instead; LUXTRACE_FUZZ_SEEDS
# lists the seed files or folders to copy into it (globs allowed) instead of the whole
# committed corpus, e.g. LUXTRACE_FUZZ_SEEDS='tests/fuzz/corpus/result/sealed_*'.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
target=$1 seconds=$2
shift 2
bin=${LUXTRACE_FUZZ_BUILD:-$root/build-fuzz}/tests/fuzz/fuzz_$target
work=${LUXTRACE_FUZZ_WORK:-${LUXTRACE_FUZZ_BUILD:-$root/build-fuzz}/fuzz/$target}
work=$(realpath -m "$work")  # the fuzzer runs inside it
[ -x "$bin" ] || { echo "no $bin: build with -DLUXTRACE_FUZZ=ON first" >&2; exit 2; }
mkdir -p "$work/corpus" "$work/artifacts"
# shellcheck disable=SC2086  # word splitting and globbing of LUXTRACE_FUZZ_SEEDS wanted
for seed in ${LUXTRACE_FUZZ_SEEDS:-$here/corpus/$target}; do
  if [ -d "$seed" ]; then cp -n "$seed"/* "$work/corpus/" 2>/dev/null || true
  elif [ -f "$seed" ]; then cp -n "$seed" "$work/corpus/"
  else echo "no seed $seed" >&2; exit 2; fi
done
opts=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1
      -artifact_prefix="$work/artifacts/")
asan=detect_leaks=1
case $target in
  scene)  opts+=(-max_len=8192 -dict="$here/scene.dict") ;;
  ies)    opts+=(-max_len=32768) ;;
  # assimp's own crashes and hangs on damaged files are not ours: keep fuzzing past them
  # (each is still written to artifacts/ and must be triaged: a luxtrace frame is ours).
  mesh)   opts+=(-max_len=4096 -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1) ;;
  # HDF5 itself crashes on some damaged global heaps (README): keep going past them too,
  # and triage. HDF5's own leaks are suppressed by module (lsan.supp); handles luxtrace
  # leaves open are caught by the entry function instead.
  weather) opts+=(-max_len=16384) ;;
  pts)    opts+=(-max_len=16384) ;;
  radiance) opts+=(-max_len=16384) ;;
  result) opts+=(-max_len=65536 -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
          asan+=:suppressions=$here/asan.supp ;;
  *) echo "unknown target $target" >&2; exit 2 ;;
esac
export ASAN_OPTIONS=${ASAN_OPTIONS:-$asan}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd "$work"
rc=0
nice -n 5 "$bin" "${opts[@]}" "$@" "$work/corpus" > "$work/log" 2>&1 || rc=$?
grep -E "^#[0-9]+:? +(cov|INITED|DONE|pulse)|ERROR|SUMMARY|invariant|stat::|Test unit written" "$work/log" || true
echo "fuzz_$target: exit $rc; log $work/log"
exit "$rc"
