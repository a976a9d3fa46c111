#!/usr/bin/python3
"""The cost of one reduction (docs/RUN_CONTROL.md "One reduction"), modelled from measured
inputs (issue 26 §3), checked against measured runs, and evaluated for a cluster.

Inputs (docs/SCALING.md says where each was measured):
  local work per rank, from build/bench/reduction_costs (ns per side, lit word, ...);
  the network's latency alpha and per-rank bandwidth beta, from build/bench/mpi_collectives
  (or a network's data sheet), and the receiver's summing rate.

Model of a closed model of T triangles (its T front sides lit: W = 5 T words of counts and
repeats, one band) on R ranks, per reduction:
  rank's own work   mark 2T sides + take W words (pack and clear)         (every rank)
                    add W/R words + chunk sums of T/R lit sides           (the owner)
                    (one rank: add_and_clear over 2T sides + chunk sums of T sides)
  waits             mask OR:      2 (R-1)/R M / beta + 2 log2(R) alpha,  M = 2T/8 bytes
                    header sum:   2 log2(R) alpha
                    reduce-scatter: (R-1)/R S / beta + log2(R) alpha + (R-1)/R W / sum_rate,
                                  S = 4 W bytes (32-bit words)
                    chunk sums to rank 0: (R-1) alpha + 56 C / beta,  C = 2 ceil(T / 4096)
The work takes a core from tracing; the waits do not (the threads trace on), but a
reduction must end within its period. The run's period is at least 100 times the work
(RunController: reductions cost at most 1 % of the run).

  /usr/bin/python3 bench/reduction_model.py [--measured FILE] [--costs-triangles 1e6]
FILE: the table bench/reduction_scaling.sh prints.
"""
import argparse
import math
import re
import subprocess
import sys


def local_costs(build, triangles, ranks):
    """seconds per unit from reduction_costs: {mark, take, add, chunks, one_rank}."""
    out = subprocess.run([f"{build}/bench/reduction_costs", "--triangles", str(triangles), "--ranks", str(ranks),
                          "--repeats", "5"], check=True, capture_output=True, text=True).stdout
    costs = {}
    for key, name in [("mark", "mark"), ("take", "take"), ("add", "add"), ("chunks", "chunks"),
                      ("one_rank", "1 rank")]:
        m = re.search(rf"^{re.escape(name)}\s+\S+ ms\s+(\S+) ns", out, re.M)
        costs[key] = float(m.group(1)) * 1e-9
    return costs


def reduction(T, R, c, alpha, beta, sum_rate, W=None):
    """(work_s, wait_s) of one reduction per rank; W: the words sent (default 5 T, every
    front side lit in the period)."""
    W = 5.0 * T if W is None else W
    if R == 1:
        return c["one_rank"] * 2 * T + c["chunks"] * T, 0.0
    work = c["mark"] * 2 * T + c["take"] * W + c["add"] * W / R + c["chunks"] * T / R
    lg = math.log2(R)
    M = 2 * T / 8
    S = 4 * W
    C = 2 * math.ceil(T / 4096)
    wait = (2 * (R - 1) / R * M / beta + 2 * lg * alpha) + 2 * lg * alpha
    wait += (R - 1) / R * S / beta + lg * alpha + (R - 1) / R * W / sum_rate
    wait += (R - 1) * alpha + 56 * C / beta
    return work, wait


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--measured", help="bench/reduction_scaling.sh's table")
    ap.add_argument("--costs-triangles", default="1e6")
    ap.add_argument("--cores", type=int, default=2, help="cores of the machine the measured runs ran on")
    # Shared memory on this machine (docs/SCALING.md, mpi_collectives on 2 ranks): 1 us,
    # 2.2 GB/s per rank for a large sum-reduction; local summing 9.3 GB/s of uint64
    # (2.3e9 words/s).
    ap.add_argument("--alpha", type=float, default=1e-6)
    ap.add_argument("--beta", type=float, default=2.2e9)
    ap.add_argument("--sum-rate", type=float, default=2.3e9)
    a = ap.parse_args()
    costs = local_costs(a.build, a.costs_triangles, 4)
    print("local costs (ns):", ", ".join(f"{k} {1e9 * v:.2f}" for k, v in costs.items()))

    if a.measured:
        # The measured work is wall time of a main thread that shares the machine's cores
        # with every rank's tracing threads and main thread: the model's CPU time times
        # that share (runnable threads / cores, at least 1) is what it predicts.
        print(f"\nmodel against measured (ms per reduction; {a.cores} cores):")
        print(f"{'triangles':>10} {'ranks':>5} {'words':>10} {'CPU':>8} {'share':>6} {'model':>8} {'work':>8} "
              f"{'ratio':>6}")
        ratios = []
        for line in open(a.measured):
            f = line.split()
            if len(f) < 10 or not f[0].isdigit():
                continue
            T, R, threads = int(f[0]), int(f[1]), int(f[2])
            work_ms = float(f[5])
            W = int(f[7]) / 4 if R > 1 else None
            cpu, _ = reduction(T, R, costs, a.alpha, a.beta, a.sum_rate, W)
            share = max(1.0, R * (threads + 1) / a.cores)
            model_ms = 1e3 * cpu * share
            ratios.append(work_ms / model_ms)
            print(f"{T:>10d} {R:>5d} {int(W or 0):>10d} {1e3 * cpu:>8.2f} {share:>6.1f} {model_ms:>8.2f} "
                  f"{work_ms:>8.2f} {work_ms / model_ms:>6.2f}")
        if ratios:
            g = math.exp(sum(math.log(r) for r in ratios) / len(ratios))
            print(f"measured / model: geometric mean {g:.2f}, range {min(ratios):.2f}-{max(ratios):.2f}")

    print("\na cluster: 100 Gb/s (12.5 GB/s per rank, alpha 2 us), summing as measured here")
    print(f"{'triangles':>10} {'ranks':>6} {'work ms':>9} {'wait ms':>9} {'period s':>9} {'cost %':>7}")
    for T in (1e6, 1e7):
        for R in (16, 128, 1000):
            w, wt = reduction(T, R, costs, 2e-6, 12.5e9, a.sum_rate)
            period = max(2.0, 100 * w, wt)
            print(f"{int(T):>10d} {R:>6d} {1e3 * w:>9.1f} {1e3 * wt:>9.1f} {period:>9.1f} {100 * w / period:>7.2f}")


if __name__ == "__main__":
    sys.exit(main())
