#!/usr/bin/python3
"""Time to a true error, and calibration of the error estimates, random against sobol.

The study of docs/QMC.md (issue 11). Needs Debian's /usr/bin/python3 (numpy, h5py); the
runs are read through the repository's python/luxtrace.

  /usr/bin/python3 scripts/qmc_study.py converge  [--work DIR] [--scenes ...] [--seeds 5]
  /usr/bin/python3 scripts/qmc_study.py calibrate [--work DIR] [--scenes ...] [--seeds 20]
  /usr/bin/python3 scripts/qmc_study.py offgrid   [--work DIR] [--scenes ...] [--seeds 8]
  /usr/bin/python3 scripts/qmc_study.py report    [--work DIR] [--scenes ...]

converge: per scene, one long sobol reference run (seed 1000), then for each sampler and
  seed fresh runs of 2^k photons, k rising until the true errors of the detector and of
  the global map are both below the lowest level (1 %). Each run is a plain `luxtrace
  run` on 2 threads; its wall time is timed around the process (what a user waits).
calibrate: 20 seeds x both samplers of 2^20 photons per scene; the files' own error
  estimates against the scatter over the seeds.
offgrid: sobol at 3 x 2^(k-1) photons (not a power of two per replicate) against 2^k and
  2^(k+1), the true error, several seeds: what a stop between powers of two costs.
report: the tables of docs/QMC.md from the files in DIR (runs already made are reused,
  so every step can be interrupted and continued).

True errors, per file, against the scene's reference (ref), in the form of the estimates
luxtrace reports (eq. 9 for a detector, eq. 4-5's area weighting for the global map):
  detector  e^2 = mean_c (L_c - Lref_c)^2 / mean_c(Lref_c)^2
  global    e^2 = sum_t A_t (E_t - Eref_t)^2 / sum_t A_t / (sum_t A_t Eref_t / sum_t A_t)^2
each minus the reference's own estimated variance in the same form (its eq. 9 sigma_abs^2,
its (D/2)^2), since the reference's noise adds to the difference. t runs over the triangle
sides the reference lit (E_t band-summed, A_t the side's area), as D/2 runs over the lit
sides; a format-1 file has its map on the front sides only.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The package of this checkout, also when another version of it is installed.
sys.path.insert(0, os.path.join(ROOT, "python"))
import luxtrace  # noqa: E402

SCENES = {
    # name: (scene file, detector, reference photons as a power of two, first k)
    "office": ("examples/office/office.toml", "desk", 28, 20),
    "montage": ("tests/data/qmc/montage.toml", "bench", 27, 14),
    "room": ("tests/data/run/room.toml", "table", 27, 17),
}
LEVELS = (0.03, 0.02, 0.01)
SEEDS = {"converge": 5, "calibrate": 20, "offgrid": 8}  # --seeds overrides them for a step
OFFGRID_K = {"office": 22, "montage": 22, "room": 20}  # off-grid runs at 2^k, 3 x 2^(k-1), 2^(k+1)
SAMPLERS = ("random", "sobol")
REF_SEED = 1000
K_MAX = 28


def run(args, scene, sampler, seed, photons, path):
    """One fresh luxtrace run unless its file is there; returns its wall time (s)."""
    meta = path + ".json"
    if os.path.exists(path) and os.path.exists(meta):
        with open(meta) as f:
            return json.load(f)["wall_s"]
    os.makedirs(os.path.dirname(path), exist_ok=True)
    cmd = [args.luxtrace, "run", os.path.join(ROOT, SCENES[scene][0]), "--photons", str(photons),
           "--seed", str(seed), "--sampler", sampler, "--threads", str(args.threads), "--target", "1e-9",
           "--quiet", "--output", path]
    t0 = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.monotonic() - t0
    if os.path.exists(path[:-3] + ".xdmf"):
        os.remove(path[:-3] + ".xdmf")
    with open(meta, "w") as f:
        json.dump({"wall_s": wall, "cmd": cmd}, f)
    return wall


class Maps:
    """The band-summed detector cells and global map of one result, with its estimates."""

    def __init__(self, path, detector):
        r = luxtrace.open(path)
        d = r.detector(detector)
        value, rel = d.band_sum()
        self.cells = value.ravel()
        self.cell_sigma_rel = rel.ravel()
        self.det_sigma_abs = d.sigma_rel_arithmetic * d.mean_arithmetic
        self.det_sigma_rel = d.sigma_rel_arithmetic
        s = r.surface
        self.area = s.side_area_m2  # [T, 2]
        self.tri = s.side_illuminance_lx  # [T, 2]
        self.glob_sigma_lx = s.odd_even_sigma_lx
        self.glob_sigma_rel = s.sigma_rel_arithmetic
        self.elapsed_s = float(r.elapsed_s)  # tracing and reductions, no start-up

    def det_error(self, ref):
        e2 = np.mean((self.cells - ref.cells) ** 2) - ref.det_sigma_abs ** 2
        return np.sqrt(max(e2, 0.0)) / np.mean(ref.cells)

    def glob_error(self, ref):
        lit = ref.tri > 0
        a, e, e_ref = self.area[lit], self.tri[lit], ref.tri[lit]
        s = a.sum()
        mean = np.sum(a * e_ref) / s
        e2 = np.sum(a * (e - e_ref) ** 2) / s - ref.glob_sigma_lx ** 2
        return np.sqrt(max(e2, 0.0)) / mean


def seeds(args, step):
    """How many seeds `step` makes: --seeds for the step being run, else its default
    (report reads the defaults, and only the runs it finds)."""
    return args.seeds if args.seeds and args.step == step else SEEDS[step]


def work_path(args, scene, name):
    return os.path.join(args.work, scene, name)


def reference(args, scene):
    k = SCENES[scene][2]
    path = work_path(args, scene, f"reference-sobol-seed{REF_SEED}-2^{k}.h5")
    run(args, scene, "sobol", REF_SEED, 2 ** k, path)
    return Maps(path, SCENES[scene][1])


def converge(args):
    for scene in args.scenes:
        ref = reference(args, scene)
        for seed in range(1, seeds(args, "converge") + 1):
            for sampler in SAMPLERS:
                for k in range(SCENES[scene][3], K_MAX + 1):
                    path = work_path(args, scene, f"{sampler}-seed{seed}-2^{k}.h5")
                    wall = run(args, scene, sampler, seed, 2 ** k, path)
                    m = Maps(path, SCENES[scene][1])
                    de, ge = m.det_error(ref), m.glob_error(ref)
                    print(f"{scene} {sampler} seed {seed} 2^{k}: detector {100 * de:.3f} %, "
                          f"global {100 * ge:.3f} %, {wall:.2f} s", flush=True)
                    if max(de, ge) < min(LEVELS):
                        break


def calibrate(args):
    for scene in args.scenes:
        for sampler in SAMPLERS:
            for seed in range(101, 101 + seeds(args, "calibrate")):
                run(args, scene, sampler, seed, 2 ** 20, work_path(args, scene, f"cal-{sampler}-seed{seed}.h5"))
        print(f"{scene}: calibration runs done", flush=True)


def offgrid(args):
    for scene in args.scenes:
        k = OFFGRID_K[scene]
        for seed in range(201, 201 + seeds(args, "offgrid")):
            for n in (2 ** k, 3 * 2 ** (k - 1), 2 ** (k + 1)):
                for sampler in SAMPLERS:  # random: the same analysis where nothing depends on N's bits
                    run(args, scene, sampler, seed, n, work_path(args, scene, f"off-{sampler}-seed{seed}-{n}.h5"))
        print(f"{scene}: off-grid runs done", flush=True)


def crossing(ns, walls, errs, level):
    """Photons and time at which errs first falls to level (log-log interpolation);
    walls: the runs' times (wall or run time)."""
    for i, e in enumerate(errs):
        if e <= level:
            if i == 0:
                return None  # below the level from the first run on: not measured
            x0, x1 = np.log(ns[i - 1]), np.log(ns[i])
            y0, y1 = np.log(errs[i - 1]), np.log(e)
            x = x0 + (np.log(level) - y0) * (x1 - x0) / (y1 - y0) if y1 != y0 else x1
            f = (x - x0) / (x1 - x0)
            wall = np.exp(np.log(walls[i - 1]) + f * (np.log(walls[i]) - np.log(walls[i - 1])))
            return np.exp(x), wall
    return None


def report_convergence(args, scene, out):
    ref = reference(args, scene)
    det = SCENES[scene][1]
    rows = {}
    for sampler in SAMPLERS:
        for seed in range(1, seeds(args, "converge") + 1):
            ns, walls, de, ge, dest, gest, runs = [], [], [], [], [], [], []
            for k in range(SCENES[scene][3], K_MAX + 1):
                path = work_path(args, scene, f"{sampler}-seed{seed}-2^{k}.h5")
                if not os.path.exists(path + ".json"):
                    break
                with open(path + ".json") as f:
                    walls.append(json.load(f)["wall_s"])
                m = Maps(path, det)
                runs.append(m.elapsed_s)
                ns.append(2 ** k)
                de.append(m.det_error(ref))
                ge.append(m.glob_error(ref))
                dest.append(m.det_sigma_rel)
                gest.append(m.glob_sigma_rel)
            rows[(sampler, seed)] = (ns, walls, de, ge, dest, gest, runs)
    print(f"\n### {scene} (detector `{det}`, reference 2^{SCENES[scene][2]} sobol photons)\n", file=out)
    print("| quantity | level | random: photons (M); wall s; run s (medians; photons min-max over seeds) "
          "| sobol: the same | photons random/sobol | wall time random/sobol | run time random/sobol |", file=out)
    print("|---|---|---|---|---|---|---|", file=out)
    for qi, quantity in ((2, "detector"), (3, "global")):
        for level in LEVELS:
            cells = []
            med = {}
            for sampler in SAMPLERS:
                mine = [r for (s, _), r in rows.items() if s == sampler]
                pts = [crossing(r[0], r[1], r[qi], level) for r in mine]
                run_pts = [crossing(r[0], r[6], r[qi], level) for r in mine]
                got = [(p, q) for p, q in zip(pts, run_pts) if p is not None]
                if len(got) < len(pts) or not got:
                    cells.append(f"{len(pts) - len(got)} of {len(pts)} seeds not bracketed")
                    med[sampler] = None
                    continue
                n = np.array([p[0] for p, _ in got]) / 1e6
                w = np.array([p[1] for p, _ in got])
                t = np.array([q[1] for _, q in got])
                med[sampler] = (np.median(n), np.median(w), np.median(t))
                cells.append(f"{np.median(n):.3g} ({n.min():.3g}-{n.max():.3g}); {np.median(w):.3g}; {np.median(t):.3g}")
            if med["random"] and med["sobol"]:
                ratios = [med["random"][i] / med["sobol"][i] for i in range(3)]
                text = [f"{ratios[0]:.2f}", f"{ratios[1]:.2f}", f"**{ratios[2]:.2f}**"]
            else:
                text = ["-"] * 3
            print(f"| {quantity} | {100 * level:.0f} % | {cells[0]} | {cells[1]} | {' | '.join(text)} |", file=out)
    # The error estimates at the largest common run against the true errors.
    print("\nTrue error and the run's own estimate at each power of two (medians over seeds):\n", file=out)
    print("| photons | random detector true / est. | sobol detector true / est. "
          "| random global true / est. | sobol global true / est. |", file=out)
    print("|---|---|---|---|---|", file=out)
    ks = sorted({n for r in rows.values() for n in r[0]})
    for n in ks:
        cols = []
        for qi, ei in ((2, 4), (3, 5)):
            for sampler in SAMPLERS:
                t, e = [], []
                for (s, _), r in rows.items():
                    if s == sampler and n in r[0]:
                        i = r[0].index(n)
                        t.append(r[qi][i])
                        e.append(r[ei][i])
                cols.append(f"{100 * np.median(t):.3f} / {100 * np.median(e):.3f} % ({len(t)})" if t else "-")
        print(f"| 2^{int(np.log2(n))} | {cols[0]} | {cols[1]} | {cols[2]} | {cols[3]} |", file=out)


def variance_ratio(est2, values, weights):
    """sqrt(mean over seeds of the estimated variance / the observed one), pooled.

    est2: [seeds] estimated variances of sum_c w_c X_c (the estimate's own form);
    values: [seeds, cells] the X_c; weights: [cells]. Observed: sum_c w_c var_seeds(X_c)."""
    return np.sqrt(np.mean(est2) / np.sum(weights * np.var(values, axis=0, ddof=1)))


def with_interval(est2, values, weights):
    """The ratio and a 95 % interval from the delete-one jackknife over seeds (a bootstrap
    would resample seeds with repeats, which biases an observed variance low)."""
    r = variance_ratio(est2, values, weights)
    n_seeds = len(est2)
    jk = np.array([variance_ratio(np.delete(est2, i), np.delete(values, i, axis=0), weights) for i in range(n_seeds)])
    se = np.sqrt((n_seeds - 1) / n_seeds * np.sum((jk - jk.mean()) ** 2))
    return f"{r:.3f} +- {1.96 * se:.3f}"


def report_calibration(args, scene, out):
    """The files' own estimates against the scatter of the same quantities over seeds:
    per cell (relative errors, pooled: mean_c sigma_rel,c^2 against mean_c var(L_c / Lbar_c)),
    eq. (9)'s sigma_abs^2 = mean_c sigma_c^2 against mean_c var(L_c), and the global
    (D/2)^2 against sum_t A_t var(E_t) / sum_t A_t over the triangle sides lit in every run."""
    det = SCENES[scene][1]
    for sampler in SAMPLERS:
        ms = []
        for seed in range(101, 101 + seeds(args, "calibrate")):
            path = work_path(args, scene, f"cal-{sampler}-seed{seed}.h5")
            if os.path.exists(path + ".json"):
                ms.append(Maps(path, det))
        if len(ms) < 2:
            continue
        cells = np.array([m.cells for m in ms])
        lit = np.all(cells > 0, axis=0)
        cells = cells[:, lit]
        k = cells.shape[1]
        rel = with_interval(np.array([np.mean(m.cell_sigma_rel[lit] ** 2) for m in ms]),
                             cells / cells.mean(axis=0), np.full(k, 1.0 / k))
        eq9 = with_interval(np.array([m.det_sigma_abs ** 2 for m in ms]) * lit.size / k,
                             cells, np.full(k, 1.0 / k))
        sides = np.array([m.tri for m in ms])
        lit_sides = np.all(sides > 0, axis=0)
        area = ms[0].area[lit_sides]
        glob = with_interval(np.array([m.glob_sigma_lx ** 2 for m in ms]), sides[:, lit_sides], area / area.sum())
        print(f"| {scene} | {sampler} | {len(ms)} | {rel} | {eq9} | {glob} |", file=out)


def report_offgrid(args, scene, out):
    ref = reference(args, scene)
    det = SCENES[scene][1]
    k = OFFGRID_K[scene]
    ns = (2 ** k, 3 * 2 ** (k - 1), 2 ** (k + 1))
    for sampler in SAMPLERS:
        errs = {n: ([], []) for n in ns}
        for seed in range(201, 201 + seeds(args, "offgrid")):
            for n in ns:
                path = work_path(args, scene, f"off-{sampler}-seed{seed}-{n}.h5")
                if not os.path.exists(path + ".json"):
                    break
                m = Maps(path, det)
                errs[n][0].append(m.det_error(ref) ** 2)
                errs[n][1].append(m.glob_error(ref) ** 2)
        n_seeds = min(len(errs[n][0]) for n in ns)
        if n_seeds == 0:
            continue
        cols = []
        for q in (0, 1):
            rms = {n: np.sqrt(np.mean(errs[n][q][:n_seeds])) for n in ns}
            # the power law through the two powers of two, at the point between them
            slope = np.log(rms[ns[2]] / rms[ns[0]]) / np.log(ns[2] / ns[0])
            interp = rms[ns[0]] * (ns[1] / ns[0]) ** slope
            cols.append(f"{100 * rms[ns[0]]:.3f} / {100 * rms[ns[1]]:.3f} / {100 * rms[ns[2]]:.3f} % "
                        f"(power law {100 * interp:.3f} %: {rms[ns[1]] / interp - 1:+.1%})")
        print(f"| {scene} | {sampler} | 2^{k}, 3x2^{k - 1}, 2^{k + 1} | {n_seeds} | {cols[0]} | {cols[1]} |", file=out)


def report(args):
    out = sys.stdout
    print("## Time to a true error\n", file=out)
    for scene in args.scenes:
        report_convergence(args, scene, out)
    print("\n## Calibration: estimate / observed scatter (sigma ratio, +- 95 % jackknife interval over seeds)\n", file=out)
    print("| scene | sampler | seeds | per cell (relative, pooled) | eq. (9) | global D/2 |", file=out)
    print("|---|---|---|---|---|---|", file=out)
    for scene in args.scenes:
        report_calibration(args, scene, out)
    print("\n## Stops between powers of two (RMS true error over seeds)\n", file=out)
    print("| scene | sampler | photons | seeds | detector | global |", file=out)
    print("|---|---|---|---|---|---|", file=out)
    for scene in args.scenes:
        report_offgrid(args, scene, out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("step", choices=("converge", "calibrate", "offgrid", "report"))
    p.add_argument("--work", default="qmc_study")
    p.add_argument("--luxtrace", default=os.path.join(ROOT, "build", "src", "luxtrace"))
    p.add_argument("--scenes", nargs="+", default=list(SCENES), choices=list(SCENES))
    p.add_argument("--seeds", type=int, default=None)
    p.add_argument("--threads", type=int, default=2)
    args = p.parse_args()
    args.work = os.path.abspath(args.work)
    {"converge": converge, "calibrate": calibrate, "offgrid": offgrid, "report": report}[args.step](args)


if __name__ == "__main__":
    main()
