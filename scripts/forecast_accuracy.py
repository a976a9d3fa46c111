#!/usr/bin/python3
"""Forecast accuracy of finished luxtrace runs (Debian's /usr/bin/python3; the files are
read through the repository's python/luxtrace).

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
import os
import sys

import numpy as np

# The package of this checkout, also when another version of it is installed.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import luxtrace  # noqa: E402


def accuracy(path, fractions=(0.05, 0.10, 0.25, 0.50), c_true=None):
    r = luxtrace.open(path)
    h = r.history
    target = h.target(0)
    t, photons = h.time_s, h.photons
    actual = t[-1]
    # Photons the target needed, from the final (best) constant of sigma = C/sqrt(N).
    c = c_true if c_true is not None else target.value[-1] * np.sqrt(photons[-1])
    n_needed = (c / target.goal) ** 2
    rows = []
    for frac in fractions:
        i = int(np.searchsorted(t, frac * actual))
        if i >= len(t) - 1 or not np.isfinite(target.forecast_s[i]):
            rows.append((frac, float("nan"), float("nan"), float("nan"), float("nan")))
            continue
        fc = target.forecast_s[i]
        fp = target.forecast_photons
        perr = (fp[i] - n_needed) / n_needed if fp is not None else float("nan")
        rows.append((frac, t[i], fc, (fc - actual) / actual, perr))
    return target.label, r.stop_reason, actual, len(t), rows


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
