#!/usr/bin/python3
"""The constant of the direct sun's variance where a shadow's edge cuts the sun's disc
(tracer/direct_daylight.cpp, crossed_strata_variance; docs/ANNUAL.md "Direct light by shadow
rays"). A disc sampled by n x n strata, one jittered ray each, cut by a straight edge: the
stratified mean's variance is the sum over strata of q (1 - q) / n^2 (q the stratum's lit
share), and the estimator counts the strata whose ray differs from a 4-neighbour's
("flagged"). Over random edges (angle uniform, offset uniform within 0.7 of the centre),
E[sum q (1 - q)] / E[flagged] is what each flagged stratum must add for the estimate to be
right on average. Prints it (0.098 with the defaults: about one in ten).

Usage: /usr/bin/python3 bench/direct_sun_strata.py [--side 4] [--edges 20000] [--seed 1]
"""
import argparse

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--side", type=int, default=4)
    ap.add_argument("--edges", type=int, default=20000)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    n, fine = a.side, 32
    sub = (np.arange(fine) + 0.5) / fine
    var = flagged = 0.0
    for _ in range(a.edges):
        angle, offset = rng.uniform(0, np.pi), rng.uniform(-0.7, 0.7)
        nx, ny = np.cos(angle), np.sin(angle)
        lit = lambda x, y: (x - 0.5) * nx + (y - 0.5) * ny < offset
        q, ray = np.zeros((n, n)), np.zeros((n, n))
        for i in range(n):
            for j in range(n):
                x, y = np.meshgrid((i + sub) / n, (j + sub) / n)
                q[i, j] = lit(x, y).mean()
                ray[i, j] = lit((i + rng.uniform()) / n, (j + rng.uniform()) / n)
        if ray.min() == ray.max():
            continue  # all alike: the estimator's other branch
        var += (q * (1 - q)).sum()
        for i in range(n):
            for j in range(n):
                near = [ray[k, l] for k, l in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)) if 0 <= k < n and 0 <= l < n]
                flagged += any(v != ray[i, j] for v in near)
    print(f"{n} x {n} strata, {a.edges} edges: E[sum q (1 - q)] / E[flagged strata] = {var / flagged:.4f}")


if __name__ == "__main__":
    main()
