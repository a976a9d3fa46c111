#!/usr/bin/python3
"""Calibration of the global error estimates over independent seeds (issue 13).

Runs `luxtrace run SCENE` for SEEDS seeds of PHOTONS photons each (random sampler) and
compares the RMS over the runs of each estimate stored in /global -- the second moment's
(moment_sigma_lx) and D/2 of eq. (5) (sigma_lx) -- with the observed scatter of the map,
sigma_obs = sqrt(sum_t A_t var_t / S), var_t the variance over the runs of side t's
illuminance, over the sides lit in every run's mean. The ratios come with a jackknife
standard error (leave one run out). Also prints C = sigma_rel_obs * sqrt(N) (quadratic
mean), the constant of the true error, from which the photons a relative target needs
follow as (C / goal)^2 (scripts/forecast_accuracy.py --c-true).

Usage (Debian's /usr/bin/python3; the files are read through the repository's python/luxtrace):
  scripts/global_calibration.py LUXTRACE SCENE.toml [--seeds 20] [--photons 262144]
                                [--first-seed 1001] [--work DIR] [--threads 2]
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

# The package of this checkout, also when another version of it is installed.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import luxtrace  # noqa: E402


def run_seeds(args):
    """Per run: the band-summed illuminance of every triangle side, the two global error
    estimates squared and the quadratic mean; and the sides' areas."""
    maps, moment2, odd_even2, side_area, mean_q = [], [], [], None, []
    for k in range(args.seeds):
        seed = args.first_seed + k
        out = os.path.join(args.work, f"seed{seed}.h5")
        subprocess.run([args.luxtrace, "run", args.scene, "--output", out, "--quiet", "--threads",
                        str(args.threads), "--photons", str(args.photons), "--seed", str(seed)],
                       check=True, stdout=subprocess.DEVNULL)
        s = luxtrace.open(out).surface
        maps.append(s.side_illuminance_lx.ravel())
        side_area = s.side_area_m2.ravel()
        moment2.append(float(s.moment_sigma_lx) ** 2)
        odd_even2.append(float(s.odd_even_sigma_lx) ** 2)
        mean_q.append(float(s.mean_quadratic_lx))
    return np.array(maps), np.array(moment2), np.array(odd_even2), side_area, np.array(mean_q)


def observed_sigma(maps, side_area):
    mean = maps.mean(axis=0)
    lit = mean > 0
    var = maps[:, lit].var(axis=0, ddof=1)
    return np.sqrt((side_area[lit] * var).sum() / side_area[lit].sum())


def ratios(maps, moment2, odd_even2, side_area):
    obs = observed_sigma(maps, side_area)
    return np.sqrt(moment2.mean()) / obs, np.sqrt(odd_even2.mean()) / obs, obs


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("luxtrace")
    p.add_argument("scene")
    p.add_argument("--seeds", type=int, default=20)
    p.add_argument("--photons", type=int, default=1 << 18)
    p.add_argument("--first-seed", type=int, default=1001)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--work", default=None)
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        args.work = args.work or tmp
        os.makedirs(args.work, exist_ok=True)
        maps, moment2, odd_even2, side_area, mean_q = run_seeds(args)
    r_m, r_oe, obs = ratios(maps, moment2, odd_even2, side_area)
    n = len(maps)
    jack = np.array([ratios(np.delete(maps, i, 0), np.delete(moment2, i), np.delete(odd_even2, i), side_area)[:2]
                     for i in range(n)])
    se = np.sqrt((n - 1) / n * ((jack - jack.mean(axis=0)) ** 2).sum(axis=0))
    spread_oe = np.sqrt(odd_even2).std(ddof=1) / np.sqrt(odd_even2).mean()
    spread_m = np.sqrt(moment2).std(ddof=1) / np.sqrt(moment2).mean()
    c_true = obs / mean_q.mean() * np.sqrt(args.photons)
    print(f"{args.scene}: {n} seeds x {args.photons} photons, {int((maps.mean(axis=0) > 0).sum())} lit sides")
    print(f"  observed sigma {obs:.5g} lx; C = sigma_rel(quad) sqrt(N) = {c_true:.5g}")
    print(f"  second moment: RMS {np.sqrt(moment2.mean()):.5g} lx, ratio {r_m:.4f} +- {se[0]:.4f},"
          f" run-to-run spread {100 * spread_m:.2f} %")
    print(f"  odd/even D/2:  RMS {np.sqrt(odd_even2.mean()):.5g} lx, ratio {r_oe:.4f} +- {se[1]:.4f},"
          f" run-to-run spread {100 * spread_oe:.2f} %")


if __name__ == "__main__":
    main()
