#!/usr/bin/python3
"""Convergence and detector figures of a luxtrace result (Debian's /usr/bin/python3 with
python3-h5py and python3-matplotlib; draws with the Agg backend, no display needed).

usage: /usr/bin/python3 scripts/plot_convergence.py RESULT.h5 [-o DIR]
           [--detector NAME]... [--cell I,J]

Writes into DIR (default: the result's folder):
  convergence.png          error against wall time, log-log, one panel per target of the
                           run (/history/target_value) with its goal, the forecast made at
                           the last reduction and the time the goal was met; the global
                           map's relative error (eq. 5, quadratic) is drawn in every
                           relative-error panel
  NAME_value.png, NAME_error.png, NAME_error_hist.png, NAME_sections.png
                           per --detector: value map with colour bar, relative error per
                           cell, histogram of those errors with the eq. (9) values, and
                           sections through cell I,J (default: the brightest cell)
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as ticker  # noqa: E402
import numpy as np  # noqa: E402


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


# --------------------------------------------------------------------------- convergence
def target_kind(label):
    if label.endswith(" received"):
        return "count"
    if label.endswith(" abs"):
        return "abs"
    return "rel"


def target_units(f, label):
    """Units of an absolute-error target: its detector's, or lux for the global map."""
    if label.startswith("detector:"):
        name = label[len("detector:"):].split("[")[0].split(" ")[0]
        if name in f.get("detectors", {}):
            return text(f["detectors"][name].attrs["units"]).replace("^2", "\u00b2")
    return "lx"


def forecast_curve(t_last, n_last, v_last, goal, t_goal, power):
    """The forecast of the last reduction as a curve in time: value ~ N^power (N^-1/2 for
    errors, N for counts) through the last point, with the photon rate that reaches the
    goal exactly at the stored forecast time."""
    n_goal = n_last * (goal / v_last) ** (1.0 / power)
    rate = (n_goal - n_last) / (t_goal - t_last)
    t = np.geomspace(t_last, t_goal, 50)
    return t, v_last * ((n_last + rate * (t - t_last)) / n_last) ** power


def plot_convergence(f, out_dir):
    h = f["history"]
    t = h["time_s"][:]
    photons = h["photons"][:].astype(float)
    glob = h["sigma_rel_global"][:]
    labels, goals, values, forecasts = [], [], None, None
    if "target_value" in h:
        labels = [text(x) for x in h.attrs["target_labels"]]
        goals = list(np.atleast_1d(h.attrs["target_goals"]))
        values = h["target_value"][:]
        forecasts = h["target_forecast_s"][:]
    kinds = [target_kind(lb) for lb in labels]
    panels = list(range(len(labels)))
    if "rel" not in kinds:
        panels.append(None)  # the global map on its own
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 3.6 * len(panels) + 0.6), squeeze=False,
                             layout="constrained")
    fig.suptitle(f"{os.path.basename(f.filename)}: convergence "
                 f"(stopped by {text(f.attrs.get('stop_reason', '?'))})", fontsize=12)
    for ax, k in zip(axes[:, 0], panels):
        ok_g = (t > 0) & np.isfinite(glob) & (glob > 0)
        if k is None:
            ax.loglog(t[ok_g], 100 * glob[ok_g], "o-", ms=3, color="0.3", label="global map, quadratic (eq. 5)")
            ax.set_title("global map relative error", fontsize=10)
            ax.set_ylabel("relative error (%)")
        else:
            label, goal, kind = labels[k], goals[k], kinds[k]
            scale = 100.0 if kind == "rel" else 1.0
            v = values[:, k]
            ok = (t > 0) & np.isfinite(v) & (v > 0)
            ax.loglog(t[ok], scale * v[ok], "o-", ms=3, color="C0", label=label)
            if kind == "rel":
                ax.loglog(t[ok_g], 100 * glob[ok_g], "-", lw=1, color="0.6", label="global map (eq. 5, quadratic)")
            ax.axhline(scale * goal, color="C3", ls="--", lw=1.2, label="goal " + (f"{goal:.0f}" if kind == "count" else f"{scale * goal:.4g}")
                       + (" %" if kind == "rel" else ""))
            met = (v >= goal) if kind == "count" else (v <= goal)
            met &= ok
            if met.any():
                ax.axvline(t[int(np.argmax(met))], color="C2", lw=1.2, label=f"met at {t[int(np.argmax(met))]:.3g} s")
            # The forecast of the last reduction that had not met the goal yet.
            before = np.nonzero(ok & ~np.maximum.accumulate(met))[0]
            if len(before):
                i = int(before[-1])
                tf = forecasts[i, k]
                if np.isfinite(tf) and tf > t[i]:
                    power = 1.0 if kind == "count" else -0.5
                    ft, fv = forecast_curve(t[i], photons[i], v[i], goal, tf, power)
                    ax.loglog(ft, scale * fv, ":", color="C1", lw=1.6,
                              label=f"forecast at {t[i]:.3g} s: goal at {tf:.3g} s")
                    ax.plot([tf], [scale * goal], "D", color="C1", ms=5)
            ax.set_title(label, fontsize=10)
            ax.set_ylabel({"rel": "relative error (%)", "abs": f"error ({target_units(f, label)})",
                           "count": "photons received"}[kind])
        ax.set_xlabel("wall time (s)")
        for a in (ax.xaxis, ax.yaxis):  # plain numbers on the log axes
            a.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
            a.set_major_formatter(ticker.FuncFormatter(lambda x, _: f"{x:g}"))
            a.set_minor_formatter(ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    path = os.path.join(out_dir, "convergence.png")
    save(fig, path)
    return path


# --------------------------------------------------------------------------- detectors
def read_detector(f, name):
    if name not in f.get("detectors", {}):
        known = ", ".join(f["detectors"].keys()) if "detectors" in f else "none"
        sys.exit(f"plot_convergence: no detector '{name}' (the file has: {known})")
    g = f["detectors"][name]
    a = g.attrs
    d = {"name": name, "type": text(a["type"]), "units": text(a["units"]).replace("^2", "\u00b2"),
         "nx": int(a["cells"][0]), "ny": int(a["cells"][1]), "su": float(a["size"][0]), "sv": float(a["size"][1]),
         "mean": float(a["mean_value"]), "mean_rel": float(a["mean_sigma_rel"]),
         "arith": float(a["sigma_rel_arithmetic"]), "quad": float(a["sigma_rel_quadratic"]),
         "normal": np.asarray(a["normal"], float), "up": np.asarray(a["up"], float)}
    d["u"] = np.cross(d["up"], d["normal"])
    value = g["value"][:]
    bands = [text(b) for b in f.attrs.get("bands", ["Y"])]
    if value.shape[2] == 1:
        d["value"], d["rel"] = value[:, :, 0], g["sigma_rel"][:][:, :, 0]
        d["band"] = f"band {bands[0]}"
    else:
        # A photon carries one band: counts and sums of squares add, eq. (8) holds for the sum.
        n = g["count"][:].sum(axis=2).astype(float)
        q = g["sumsq"][:].sum(axis=2).astype(float)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.sqrt(np.maximum(0.0, q / n**2 - 1.0 / float(f.attrs["photons"])))
        d["value"], d["rel"] = value.sum(axis=2), np.where(n > 0, rel, np.nan)
        d["band"] = f"sum of {value.shape[2]} bands"
    return d


def vec(v):
    return "(" + ", ".join(f"{0.0 if abs(x) < 1e-12 else x:.3g}" for x in v) + ")"


def map_axes(ax, d):
    ax.set_xlabel(f"u (m) along {vec(d['u'])}")
    ax.set_ylabel(f"v (m) along up {vec(d['up'])}")


def detector_figures(f, name, cell, out_dir):
    d = read_detector(f, name)
    nx, ny, su, sv = d["nx"], d["ny"], d["su"], d["sv"]
    ext = [-su / 2, su / 2, -sv / 2, sv / 2]
    quantity = "E" if d["units"] == "lx" else "L"
    paths = []
    # Row 0 at the bottom (origin="lower"): the detector's up points up.
    fig, ax = plt.subplots(figsize=(9, 4.8))
    im = ax.imshow(d["value"], origin="lower", extent=ext, cmap="viridis", interpolation="nearest", vmin=0)
    fig.colorbar(im, ax=ax, label=f"{quantity} ({d['units']})")
    ax.set_title(f"{name} \u2014 {d['type']} ({d['band']}), mean {d['mean']:.4g} {d['units']} "
                 f"\u00b1 {100 * d['mean_rel']:.3g} %", fontsize=11)
    map_axes(ax, d)
    paths.append(save(fig, os.path.join(out_dir, f"{name}_value.png")))

    fig, ax = plt.subplots(figsize=(9, 4.8))
    cmap = plt.get_cmap("inferno").copy()
    cmap.set_bad("0.62")
    im = ax.imshow(np.ma.masked_invalid(100 * d["rel"]), origin="lower", extent=ext, cmap=cmap,
                   interpolation="nearest", vmin=0)
    fig.colorbar(im, ax=ax, label="\u03c3 rel (%)")
    jj, ii = np.nonzero(~np.isfinite(d["rel"]))
    ax.plot(-su / 2 + (ii + 0.5) * su / nx, -sv / 2 + (jj + 0.5) * sv / ny, "x", color="0.3", ms=6,
            label="no hits" if len(ii) else None)
    if len(ii):
        ax.legend(loc="upper right", fontsize=8)
    ax.set_title(f"{name} \u2014 relative error per cell (eq. 8); eq. (9): {100 * d['arith']:.3g} % arithmetic, "
                 f"{100 * d['quad']:.3g} % quadratic", fontsize=10)
    map_axes(ax, d)
    paths.append(save(fig, os.path.join(out_dir, f"{name}_error.png")))

    e = 100 * d["rel"][np.isfinite(d["rel"])]
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.hist(e, bins=int(np.clip(round(np.sqrt(max(len(e), 1))), 10, 60)), color="C3", alpha=0.75, edgecolor="0.25")
    ax.axvline(100 * d["arith"], color="C0", lw=2, label=f"eq. (9) arithmetic: {100 * d['arith']:.3g} %")
    ax.axvline(100 * d["quad"], color="C2", lw=2, ls="--", label=f"eq. (9) quadratic: {100 * d['quad']:.3g} %")
    ax.set_xlabel("relative error per cell (%)")
    ax.set_ylabel("cells")
    ax.set_title(f"{name} \u2014 relative errors of {len(e)} cells with hits "
                 f"({d['rel'].size - len(e)} without)", fontsize=11)
    ax.legend(fontsize=9)
    paths.append(save(fig, os.path.join(out_dir, f"{name}_error_hist.png")))

    if cell:
        i, j = (int(x) for x in cell.split(","))
        if not (0 <= i < nx and 0 <= j < ny):
            sys.exit(f"plot_convergence: --cell {cell} is outside detector '{name}' ({nx} x {ny} cells)")
    else:
        j, i = np.unravel_index(int(np.argmax(d["value"])), d["value"].shape)
    fig, axes = plt.subplots(2, 1, figsize=(8, 7.6))
    fig.suptitle(f"{name} \u2014 sections through cell i = {i}, j = {j} ({d['band']}); band: \u00b1 1 \u03c3",
                 fontsize=11)
    for ax, vals, rel, size, n, at, axis in (
            (axes[0], d["value"][j, :], d["rel"][j, :], su, nx, i, f"u (m) along {vec(d['u'])}"),
            (axes[1], d["value"][:, i], d["rel"][:, i], sv, ny, j, f"v (m) along up {vec(d['up'])}")):
        edges = np.linspace(-size / 2, size / 2, n + 1)
        s = np.where(np.isfinite(rel), rel * vals, 0.0)
        ax.stairs(vals + s, edges, baseline=vals - s, fill=True, color="C0", alpha=0.3)
        ax.stairs(vals, edges, baseline=None, color="C0", lw=1.8)
        ax.set_xlim(-size / 2, size / 2)
        ax.axvline(-size / 2 + (at + 0.5) * size / n, color="C3", ls="--", lw=1.2)
        ax.set_xlabel(axis)
        ax.set_ylabel(f"{quantity} ({d['units']})")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    axes[0].set_title(f"horizontal: row j = {j}", fontsize=10, loc="left")
    axes[1].set_title(f"vertical: column i = {i}", fontsize=10, loc="left")
    fig.tight_layout()
    paths.append(save(fig, os.path.join(out_dir, f"{name}_sections.png")))
    return paths


def save(fig, path):
    """Atomic: write a temporary file beside the target, then rename."""
    tmp = os.path.join(os.path.dirname(path) or ".", f".{os.path.basename(path)}.tmp.{os.getpid()}.png")
    fig.savefig(tmp, dpi=100)
    plt.close(fig)
    os.replace(tmp, path)
    return path


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("result", help="result file (.h5) of luxtrace run")
    p.add_argument("-o", "--out-dir", help="folder for the PNGs (default: beside the result)")
    p.add_argument("--detector", action="append", default=[], help="detector figures for NAME (repeatable)")
    p.add_argument("--cell", default="", help="i,j: the cell the sections go through (default: brightest)")
    a = p.parse_args(argv)
    out_dir = a.out_dir or os.path.dirname(os.path.abspath(a.result))
    os.makedirs(out_dir, exist_ok=True)
    with h5py.File(a.result, "r") as f:
        if text(f.attrs.get("format", "")) not in ("luxtrace-result", "luxtrace-checkpoint"):
            sys.exit(f"plot_convergence: {a.result} is not a luxtrace result")
        written = [plot_convergence(f, out_dir)]
        for name in a.detector:
            written += detector_figures(f, name, a.cell, out_dir)
    for w in written:
        print(w)


if __name__ == "__main__":
    main(sys.argv[1:])
