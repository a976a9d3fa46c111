#!/usr/bin/env bash
# Makes the seeds of the result target (tests/fuzz/corpus/result/): small results and
# checkpoints of the fixed scenes in /tmp/luxtrace-fuzz-result-scene/ (fuzz_entry.cpp
# writes them), plus truncated and bit-flipped copies.
#   bash tests/fuzz/make_result_seeds.sh LUXTRACE REPLAY OUT_DIR
# LUXTRACE: build/src/luxtrace; REPLAY: build/tests/fuzz/fuzz_replay or the libFuzzer
# executable build-fuzz/tests/fuzz/fuzz_result (either runs one input to write the scenes).
set -euo pipefail
luxtrace=$1 replay=$2 out=$3
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
: > "$tmp/empty"
if [ "$(basename "$replay")" = fuzz_replay ]; then "$replay" result "$tmp/empty" >/dev/null 2>&1
else "$replay" "$tmp/empty" >/dev/null 2>&1; fi  # writes the fixed scenes
scenes=/tmp/luxtrace-fuzz-result-scene
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$luxtrace" run $scenes/scene.toml --quiet --threads 1 --output "$tmp/rgb.h5" >/dev/null
"$luxtrace" run $scenes/scene_y.toml --quiet --threads 1 --output "$tmp/y.h5" >/dev/null
# A checkpoint: the wall-time limit comes before an unreachable target (exit 3).
for s in scene scene_y; do
  rc=0
  "$luxtrace" run $scenes/$s.toml --quiet --threads 1 --photons 1e12 --time-limit 0.3 --target 1e-9 \
    --output "$tmp/$s.out.h5" --checkpoint "$tmp/${s}_ck.h5" >/dev/null || rc=$?
  [ "$rc" = 3 ] || { echo "expected exit 3 from the checkpoint run of $s, got $rc" >&2; exit 1; }
done
cp "$tmp/rgb.h5" "$out/result_rgb"
cp "$tmp/y.h5" "$out/result_y"
cp "$tmp/scene_ck.h5" "$out/checkpoint_rgb"
cp "$tmp/scene_y_ck.h5" "$out/checkpoint_y"
# Damaged copies: truncated, and single bits flipped at a few places.
/usr/bin/python3 - "$out" <<'PY'
import os, sys
out = sys.argv[1]
for name in ("result_y", "checkpoint_y"):
    data = open(os.path.join(out, name), "rb").read()
    open(os.path.join(out, name + "_truncated_half"), "wb").write(data[: len(data) // 2])
    open(os.path.join(out, name + "_truncated_tail"), "wb").write(data[:-100])
    for frac in (0.01, 0.3, 0.6, 0.9):
        b = bytearray(data)
        b[int(len(b) * frac)] ^= 0x10
        open(os.path.join(out, "%s_flip_%02d" % (name, int(frac * 100))), "wb").write(bytes(b))
PY
ls -l "$out"
