#!/usr/bin/python3
"""The annual metrics' errors against their scatter over seeds, and against a long run.

Runs an annual scene (default: examples/annual/annual_office.toml) K times with seeds
1..K at the same photon budget, and once with `--reference-factor` times the photons
(seed 1000), then prints, per detector:

  - calibration: for each figure, the scatter over the seeds against the reported sigma,
    ratio = sqrt(mean over seeds of ((x_k - mean x) / sigma_k)^2 * K / (K - 1)); a correct
    error model gives 1. Per-sensor figures (DA, continuous DA, UDI, ASE hours) and the
    hourly illuminance and direct sun are pooled over sensors (and hours) and seeds; the
    grid figures (sDA, ASE, means, EN 17037 shares) are pooled over seeds only (K - 1
    degrees of freedom each: with K = 10 one ratio has ~24 % sampling error).
  - reference: each seed's figure minus its bias against the long run's, z = (x - b - x_ref
    + b_ref) / sqrt(sigma^2 + sigma_ref^2), summarised as mean z and rms z over the seeds.

Docs: docs/VALIDATION.md "Annual daylight". Usage:

  /usr/bin/python3 scripts/annual_calibration.py --luxtrace build/src/luxtrace \
      --photons 10M --seeds 10 --reference-factor 10 --ranks 2 --out /tmp/annual_cal
"""
import argparse
import math
import os
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SENSOR_FIGURES = ["da", "continuous_da", "udi_fell_short", "udi_useful", "udi_exceeded", "ase_hours"]
GRID_FIGURES = ["sda", "ase", "mean_da", "mean_continuous_da", "mean_udi_fell_short", "mean_udi_useful",
                "mean_udi_exceeded"] + [f"en17037_{lvl}_{what}_hours" for lvl in ("minimum", "medium", "high")
                                        for what in ("target", "minimum")]
HOURLY = [("illuminance_lx", "illuminance_sigma_lx"), ("direct_sun_lx", "direct_sun_sigma_lx")]


def parse_photons(text):
    mult = {"k": 1e3, "K": 1e3, "M": 1e6, "G": 1e9}
    return int(float(text[:-1]) * mult[text[-1]]) if text[-1] in mult else int(float(text))


def run(args, seed, photons, out):
    if os.path.exists(out) and not args.rerun:
        return 0.0
    cmd = [args.luxtrace, "run", args.scene, "--photons", str(photons), "--seed", str(seed), "--output", out,
           "--quiet"]
    if args.ranks > 1:
        cmd = ["mpirun", "-n", str(args.ranks), "--bind-to", "none", "--oversubscribe"] + cmd + ["--threads", "1"]
    else:
        cmd += ["--threads", str(args.threads)]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    t0 = time.time()
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    return time.time() - t0


def read(path, detector):
    with h5py.File(path, "r") as f:
        a = f["annual"]
        g = a["detectors/" + detector]
        occupied = a["occupied"][:].astype(bool) & a["daylit"][:].astype(bool)
        d = {"attrs": {k: float(v) for k, v in g.attrs.items()}}
        for name in SENSOR_FIGURES:
            for suffix in ("", "_sigma", "_bias"):
                d[name + suffix] = g[name + suffix][:]
        for value, sigma in HOURLY:
            d[value] = g[value][:][occupied].astype(np.float64)
            d[sigma] = g[sigma][:][occupied].astype(np.float64)
    return d


def scatter_ratio(x, s):
    """x, s: [K, ...] values and sigmas; the pooled rms of (x - mean) / sigma, unbiased."""
    k = x.shape[0]
    ok = np.all(s > 0, axis=0)
    if not np.any(ok):
        return float("nan"), 0, int(np.sum(np.ptp(x, axis=0) > 0))
    z = (x - x.mean(axis=0))[:, ok] / s[:, ok]
    dof = (k - 1) * int(np.sum(ok))
    # figures that scatter although every seed reported a zero sigma
    silent = int(np.sum(~ok & (np.ptp(x, axis=0) > 0)))
    return math.sqrt(float(np.sum(z * z)) / dof), dof, silent


def bounds(dof):
    """The 99 % band of the ratio for a correct error model (chi-square, dof degrees)."""
    if dof <= 0:
        return float("nan"), float("nan")
    a = 2.0 / (9.0 * dof)
    q = lambda z: math.sqrt((1.0 - a + z * math.sqrt(a)) ** 3)  # Wilson-Hilferty
    return q(-2.5758), q(2.5758)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--luxtrace", default=os.path.join(ROOT, "build", "src", "luxtrace"))
    p.add_argument("--scene", default=os.path.join(ROOT, "examples", "annual", "annual_office.toml"))
    p.add_argument("--photons", default="10M")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--reference-factor", type=int, default=10)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--threads", type=int, default=2, help="with --ranks 1")
    p.add_argument("--out", default="annual_calibration")
    p.add_argument("--rerun", action="store_true", help="run again even where a result exists")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    photons = parse_photons(args.photons)
    files = []
    for seed in range(1, args.seeds + 1):
        out = os.path.join(args.out, f"seed_{seed:02d}.h5")
        t = run(args, seed, photons, out)
        print(f"seed {seed}: {photons} photons, {t:.1f} s", flush=True)
        files.append(out)
    ref = os.path.join(args.out, "reference.h5")
    t = run(args, 1000, photons * args.reference_factor, ref)
    print(f"reference: {photons * args.reference_factor} photons, {t:.1f} s", flush=True)

    with h5py.File(ref, "r") as f:
        detectors = list(f["annual/detectors"].keys())
    for det in detectors:
        runs = [read(path, det) for path in files]
        r = read(ref, det)
        print(f"\n== detector {det}: {len(runs)} seeds x {photons} photons; reference {args.reference_factor}x")
        print(f"{'figure':34s} {'scatter/sigma':>13s} {'dof':>7s} {'99% band':>13s} {'zero-sigma':>10s}")
        for name in SENSOR_FIGURES:
            ratio, dof, silent = scatter_ratio(np.array([d[name] for d in runs]),
                                               np.array([d[name + "_sigma"] for d in runs]))
            lo, hi = bounds(dof)
            print(f"{name + ' (per sensor)':34s} {ratio:13.3f} {dof:7d} {lo:6.2f}-{hi:5.2f} {silent:10d}")
        for value, sigma in HOURLY:
            ratio, dof, silent = scatter_ratio(np.array([d[value] for d in runs]), np.array([d[sigma] for d in runs]))
            lo, hi = bounds(dof)
            print(f"{value + ' (per hour)':34s} {ratio:13.3f} {dof:7d} {lo:6.2f}-{hi:5.2f} {silent:10d}")
        pooled_z2, pooled_dof = 0.0, 0
        print(f"\n{'grid figure':28s} {'seeds mean':>10s} {'sigma':>9s} {'bias':>9s} {'scatter':>9s} "
              f"{'ratio':>6s} {'reference':>10s} {'ref sigma':>9s} {'mean z':>7s} {'rms z':>6s}")
        for name in GRID_FIGURES:
            x = np.array([d["attrs"][name] for d in runs])
            s = np.array([d["attrs"].get(name + "_sigma", float("nan")) for d in runs])
            b = np.array([d["attrs"].get(name + "_bias", 0.0) for d in runs])
            ratio, dof, _ = scatter_ratio(x[:, None], s[:, None])
            if dof:
                pooled_z2 += ratio * ratio * dof
                pooled_dof += dof
            xr, sr, br = r["attrs"][name], r["attrs"].get(name + "_sigma", float("nan")), r["attrs"].get(
                name + "_bias", 0.0)
            z = (x - b - (xr - br)) / np.sqrt(s * s + sr * sr)
            print(f"{name:28s} {x.mean():10.4f} {np.sqrt(np.mean(s * s)):9.4f} {b.mean():9.4f} {x.std(ddof=1):9.4f} "
                  f"{ratio:6.2f} {xr:10.4f} {sr:9.4f} {np.mean(z):7.2f} {math.sqrt(np.mean(z * z)):6.2f}")
        if pooled_dof:
            lo, hi = bounds(pooled_dof)
            print(f"grid figures pooled: ratio {math.sqrt(pooled_z2 / pooled_dof):.3f} over {pooled_dof} dof "
                  f"(99 % band for a correct model {lo:.2f}-{hi:.2f}; the figures are correlated, so the band is "
                  f"narrower than the truth)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
