#!/usr/bin/python3
"""Forecast accuracy of finished luxtrace runs (Debian's /usr/bin/python3 with h5py).

For each result file of a run that stopped on a target, compare the forecast finishing
time made at 5%, 10%, 25% and 50% of the run with the time the target was actually met
(the last reduction), and the forecast photon count with the photons the target needs
according to the final constant of sigma = C / sqrt(N) (the time forecast adds the photon
rate, which other load on the machine changes; the photon forecast does not depend on it).
With --c-true C, the photons needed come instead from the constant of the TRUE error,
sigma_rel = C / sqrt(N), measured over independent seeds by scripts/global_calibration.py:
then a noisy estimate's own final value does not set the yardstick it is judged by.
Usage: scripts/forecast_accuracy.py [--c-true C] RESULT.h5 [...]
"""
import sys

import h5py
import numpy as np


def accuracy(path, fractions=(0.05, 0.10, 0.25, 0.50), c_true=None):
    with h5py.File(path, "r") as f:
        h = f["history"]
        t = h["time_s"][:]
        forecast = h["target_forecast_s"][:, 0]
        photons = h["photons"][:]
        fphotons = h["target_forecast_photons"][:, 0] if "target_forecast_photons" in h else None
        label = np.atleast_1d(h.attrs["target_labels"])[0]
        reason = f.attrs["stop_reason"]
    actual = t[-1]
    # Photons the target needed, from the final (best) constant of sigma = C/sqrt(N).
    with h5py.File(path, "r") as f:
        h = f["history"]
        v = h["target_value"][:, 0]
        goal = np.atleast_1d(h.attrs["target_goals"])[0]
    c = c_true if c_true is not None else v[-1] * np.sqrt(photons[-1])
    n_needed = (c / goal) ** 2
    rows = []
    for frac in fractions:
        i = int(np.searchsorted(t, frac * actual))
        if i >= len(t) - 1 or not np.isfinite(forecast[i]):
            rows.append((frac, float("nan"), float("nan"), float("nan"), float("nan")))
            continue
        perr = (fphotons[i] - n_needed) / n_needed if fphotons is not None else float("nan")
        rows.append((frac, t[i], forecast[i], (forecast[i] - actual) / actual, perr))
    return label, reason, actual, len(t), rows


def main(argv):
    c_true = None
    if argv[:1] == ["--c-true"]:
        c_true, argv = float(argv[1]), argv[2:]
    for p in argv:
        label, reason, actual, n, rows = accuracy(p, c_true=c_true)
        print(f"{p}: target {label}, stopped by {reason}, met at {actual:.1f} s, {n} reductions")
        for frac, t, fc, err, perr in rows:
            print(f"  at {100 * frac:4.0f}% ({t:7.2f} s): forecast {fc:8.2f} s, time error {100 * err:+6.2f}%,"
                  f" photon forecast error {100 * perr:+6.2f}%")


if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1:2] == ["--c-true"] and len(sys.argv) < 4:
        sys.exit(__doc__)
    main(sys.argv[1:])
