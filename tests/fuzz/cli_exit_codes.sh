#!/usr/bin/env bash
# The command line on every result-target input (corpus and crashers): `luxtrace info`,
# `luxtrace render` and `luxtrace run --restart` must end with exit 0 (the file is fine)
# or 2 (bad input, one message), never 1 (internal error) or a signal.
#   cli_exit_codes.sh LUXTRACE FUZZ_REPLAY WORK_DIR DIR...
set -uo pipefail
luxtrace=$1 replay=$2 work=$3
shift 3
rm -rf "$work" && mkdir -p "$work"
: > "$work/empty"
"$replay" result "$work/empty" >/dev/null 2>&1  # writes the scenes the results name
scenes=/tmp/luxtrace-fuzz-result-scene
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bad=0 n=0
check() {  # description command...
  local what=$1
  shift
  "$@" > "$work/out" 2>&1
  local rc=$?
  n=$((n + 1))
  if [ "$rc" != 0 ] && [ "$rc" != 2 ]; then
    echo "FAILED: $what: exit $rc"
    sed 's/^/    /' "$work/out" | tail -5
    bad=$((bad + 1))
  fi
}
for dir in "$@"; do
  for f in "$dir"/*; do
    [ -f "$f" ] || continue
    case $(basename "$f") in README*) continue ;; esac
    cp "$f" "$work/in.h5"
    check "info $f" "$luxtrace" info "$work/in.h5"
    check "render $f" "$luxtrace" render "$work/in.h5" --size 8x6 --samples 1 --threads 1 -o "$work/view.png"
    # Detector pictures are drawn by the Python package: python/tests/test_read.py reads
    # and draws these same inputs in one process (a Python start per input costs ~1 s).
    case $(basename "$f") in *_y*) scenes_of="scene_y" ;; *_rgb*) scenes_of="scene" ;; *) scenes_of="scene scene_y" ;; esac
    for s in $scenes_of; do
      # A budget of 1 photon: everything is read and checked, then the restart is refused
      # (exit 2) because the checkpoint already holds more; nothing is traced.
      check "run $s --restart $f" "$luxtrace" run "$scenes/$s.toml" --quiet --threads 1 --photons 1 \
        --restart "$work/in.h5" --output "$work/restarted.h5"
    done
  done
done
echo "cli_exit_codes: $n commands, $bad failed"
[ "$bad" = 0 ]
