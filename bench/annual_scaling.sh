#!/usr/bin/env bash
# The annual example on 1 to 8 ranks (issue 37 §3; docs/SCALING.md "An annual run on 1 to 8
# ranks"): examples/annual/annual_office.toml as it is (shadow rays and the gather), its two
# file paths made absolute, PHOTONS photons (default the example's 2M), one thread a rank,
# each rank count PASSES times (the order reversed every other pass: the machine drifts).
# Beyond the cores the ranks share them, so the efficiency is judged by CPU: user + system
# of mpirun and its ranks (/usr/bin/time), CPU(1) / CPU(R). The parts are the run's own
# lines: the gather's table, the direct pass, the result's writing and its annual step.
# Usage: bench/annual_scaling.sh   (from the repository root, after building build/src/luxtrace)
# Environment: RANKS ("1 2 4 8"), PHOTONS (2M), PASSES (2), KEEP=1 keeps the directory.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
luxtrace="$repo/build/src/luxtrace"
ranks=${RANKS:-"1 2 4 8"}
photons=${PHOTONS:-2M}
passes=${PASSES:-2}
[[ -x $luxtrace ]] || { echo "annual_scaling.sh: build $luxtrace first" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d /tmp/annual_scaling.XXXXXX)
[[ ${KEEP:-0} == 1 ]] || trap 'rm -rf "$work"' EXIT
"$repo/bench/annual_example_scene.sh" >"$work/scene.toml"

run() {  # ranks pass
    local out="$work/r$1_p$2"
    /usr/bin/time -f "%U %S %e" -o "$out.time" mpirun --oversubscribe --bind-to none --mca btl self,vader -n "$1" \
        "$luxtrace" run "$work/scene.toml" --photons "$photons" --seed 5 --threads 1 --output "$out.h5" >"$out.log" 2>&1
}
for ((p = 1; p <= passes; ++p)); do
    order=$ranks
    ((p % 2 == 0)) && order=$(echo "$ranks" | tr ' ' '\n' | tac | tr '\n' ' ')
    for r in $order; do run "$r" "$p"; done
done

/usr/bin/python3 - "$work" "$passes" $ranks <<'PY'
import re, sys
work, passes, ranks = sys.argv[1], int(sys.argv[2]), sys.argv[3:]

def figure(text, pattern):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else float("nan")

rows = {}
for r in ranks:
    for p in range(1, passes + 1):
        base = f"{work}/r{r}_p{p}"
        user, sys_, wall = (float(x) for x in open(base + ".time").read().split()[-3:])
        log = open(base + ".log").read()
        rows.setdefault(r, []).append((user + sys_, wall,
                                       figure(log, r"gather's rays at the annual grids: ([0-9.]+) s"),
                                       figure(log, r"direct light by shadow rays at the annual grids: ([0-9.]+) s"),
                                       figure(log, r"written in ([0-9.]+) s"),
                                       figure(log, r"annual ([0-9.]+),")))
mean = lambda xs: sum(xs) / len(xs)
cpu1 = mean([x[0] for x in rows[ranks[0]]])
print("| ranks | CPU s | efficiency (CPU, means) | wall s | gather table s | direct pass s | result s (annual step) |")
print("|---|---|---|---|---|---|---|")
for r in ranks:
    xs = rows[r]
    j = lambda i, f="%.2f": ", ".join(f % x[i] for x in xs)
    print(f"| {r} | {j(0, '%.1f')} | {cpu1 / mean([x[0] for x in xs]):.2f} | {j(1, '%.1f')} | {j(2)} | {j(3)} | "
          + ", ".join(f"{x[4]:.2f} ({x[5]:.2f})" for x in xs) + " |")
PY
