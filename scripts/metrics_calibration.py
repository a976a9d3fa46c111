#!/usr/bin/python3
"""Calibration of the illuminance metrics over seeds (docs/VALIDATION.md, case 6).

Runs tests/data/validation/point_floor_metrics.toml (a point source over a floor) once
per seed and compares the stored Eavg, Emin, Emax and U0 of the whole grid and of the
task area "side" with their analytic values, in units of their stored errors:

  z_avg = (E_avg - ref_avg) / E_avg_sigma
  z_min_raw = (E_min - ref_min) / E_min_sigma            (the plain minimum)
  z_min = (E_min - E_min_bias - ref_min) / E_min_sigma   (bias-corrected)
  z_max = (E_max - E_max_bias - ref_max) / E_max_sigma
  z_U0 = (U0 - U0_bias - ref_min / ref_avg) / U0_sigma

Needs Debian's /usr/bin/python3 (numpy, h5py); the results are read through the
repository's python/luxtrace.

  /usr/bin/python3 scripts/metrics_calibration.py build/src/luxtrace [--seeds 20] [--first 100] [--sampler random]
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

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "validation",
                     "point_floor_metrics.toml")
FLUX_LM, HEIGHT_M, CELL_M = 1000.0, 2.0, 0.4  # must match the scene file


def reference(i0, i1, j0, j1):
    """Eavg, Emin, Emax of the analytic cell means (8 x 8 midpoint rule per cell)."""
    intensity = FLUX_LM / (4.0 * np.pi)
    sub = (np.arange(8) + 0.5) / 8
    means = []
    for j in range(j0, j1):
        for i in range(i0, i1):
            x, y = np.meshgrid(-2.0 + (i + sub) * CELL_M, -2.0 + (j + sub) * CELL_M)
            means.append((intensity * HEIGHT_M / (x * x + y * y + HEIGHT_M ** 2) ** 1.5).mean())
    means = np.array(means)
    return means.mean(), means.min(), means.max()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("luxtrace")
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--first", type=int, default=100)
    ap.add_argument("--sampler", default="random")
    a = ap.parse_args()
    areas = {"whole grid": (None, reference(0, 10, 0, 10)),  # None: the detector's own metrics
             "task area": ("side", reference(6, 10, 2, 5))}
    z = {k: [] for k in areas}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "run.h5")
        for seed in range(a.first, a.first + a.seeds):
            subprocess.run([a.luxtrace, "run", SCENE, "--output", out, "--quiet", "--threads", "2", "--seed",
                            str(seed), "--sampler", a.sampler], check=True, stdout=subprocess.DEVNULL)
            d = luxtrace.open(out).detector("floor_E")
            for name, (area, (avg, lo, hi)) in areas.items():
                m = d.attrs if area is None else d.task_areas[area].attrs
                z[name].append([(m["E_avg_lx"] - avg) / m["E_avg_sigma_lx"],
                                (m["E_min_lx"] - lo) / m["E_min_sigma_lx"],
                                (m["E_min_lx"] - m["E_min_bias_lx"] - lo) / m["E_min_sigma_lx"],
                                (m["E_max_lx"] - m["E_max_bias_lx"] - hi) / m["E_max_sigma_lx"],
                                (m["U0"] - m["U0_bias"] - lo / avg) / m["U0_sigma"],
                                m["U0_unreliable"]])
    cols = ["Eavg", "Emin plain", "Emin - bias", "Emax - bias", "U0 - U0_bias"]
    print(f"{a.seeds} seeds from {a.first}, sampler {a.sampler}")
    for name, rows in z.items():
        r = np.array(rows, dtype=float)
        print(f"{name}: unreliable in {int(r[:, 5].sum())} runs")
        for k, c in enumerate(cols):
            print(f"  {c:13s} mean z {r[:, k].mean():+.2f}  mean z^2 {(r[:, k] ** 2).mean():.2f}  "
                  f"worst |z| {np.abs(r[:, k]).max():.2f}")


if __name__ == "__main__":
    main()
