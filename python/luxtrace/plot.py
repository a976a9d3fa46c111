"""Pictures of luxtrace results with matplotlib (drawn with Agg: no display needed).

Detector pictures, each built by a function returning the Figure (so a script or a test
can look at what is drawn) and saved by :func:`detector_pictures`:

    value_figure(det)            value map with a colour bar from 0 to the largest value
    error_figure(det)            relative error per cell (eq. 8), cells without hits marked
    error_histogram_figure(det)  histogram of those errors, the eq. (9) values marked
    sections_figure(det, i, j)   row j and column i through cell (i, j), with +-1 sigma bands

A points detector (.pts sensors) is drawn as dots at the sensors' positions, seen along
their mean direction, and its sections as every sensor's value in file order.

and the convergence history of a run: :func:`convergence_figure`. The maps put row 0 at
the bottom, so the detector's ``up`` points up and u = up x normal to the right (the
detector seen from its front side). With several bands the pictures show the band sum.

From the shell::

    python3 -m luxtrace.plot RESULT.h5 --detector desk [--cell I,J] [-o DIR] [--convergence]
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as ticker  # noqa: E402
import numpy as np  # noqa: E402

from . import result as _result  # noqa: E402

_DPI = 100


def _units(d):
    return d.units.replace("^2", "\u00b2")


def _quantity(d):
    return "E" if d.units == "lx" else "L"


def _vec(v):
    return "(" + ", ".join(f"{0.0 if abs(x) < 1e-12 else x:.3g}" for x in v) + ")"


def _band_note(d, bands=None):
    if d.bands == 1:
        return f"band {bands[0]}" if bands else ""
    return f"sum of {d.bands} bands"


def _map_axes(ax, d):
    ax.set_xlabel(f"u (m) along {_vec(d.u)}")
    ax.set_ylabel(f"v (m) along up {_vec(d.up)}")


def _extent(d):
    su, sv = d.size_m
    return [-su / 2, su / 2, -sv / 2, sv / 2]


def _figsize(d):
    """9 inches wide for the map (about 6.9), its labels and colour bar; the map keeps its
    aspect, between 2.4 and 8 inches high, with room for two title lines."""
    su, sv = d.size_m
    return 9.0, float(np.clip(6.9 * sv / su, 2.4, 8.0)) + 1.5


def _grid_line(d, photons):
    """'48 x 24 cells of 25 x 25 mm, 257951 photons received of 3.00e+06 emitted'."""
    su, sv = d.size_m
    return (f"{d.nx} \u00d7 {d.ny} cells of {1000 * su / d.nx:.3g} \u00d7 {1000 * sv / d.ny:.3g} mm, "
            f"{d.photons_received} photons received of {photons:.3g} emitted")


def _sensor_plane(d):
    """Two axes for drawing a points detector's sensors: across their mean direction (with
    a detector's default up: +z, or +y when that direction is within 26 degrees of +-z),
    or x and y when the directions cancel out. Returns (u, v) unit vectors."""
    n = np.asarray(d.directions, dtype=float).mean(axis=0)
    if np.linalg.norm(n) < 1e-6:
        return np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    n /= np.linalg.norm(n)
    up = np.array([0, 1.0, 0]) if abs(n[2]) > 0.9 else np.array([0, 0, 1.0])
    u = np.cross(up, n)
    u /= np.linalg.norm(u)
    return u, np.cross(n, u)


def _points_figure(d, values, cmap, label, vmax, title):
    """A points detector's sensors as dots at their positions (seen along their mean
    direction) coloured by ``values`` [nx] (masked: grey crosses)."""
    u, v = _sensor_plane(d)
    p = np.asarray(d.positions, dtype=float)
    x, y = p @ u, p @ v
    fig, ax = plt.subplots(figsize=(9.0, 7.0), layout="constrained")
    ok = ~np.ma.getmaskarray(values)
    sc = ax.scatter(x[ok], y[ok], c=np.ma.getdata(values)[ok], cmap=cmap, vmin=0.0, vmax=vmax, s=60,
                    edgecolors="0.3", linewidths=0.4)
    fig.colorbar(sc, ax=ax, label=label)
    if (~ok).any():
        ax.plot(x[~ok], y[~ok], "x", color="0.3", ms=6, label="no hits")
        ax.legend(loc="upper right", fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"(m) along {_vec(u)}")
    ax.set_ylabel(f"(m) along {_vec(v)}")
    ax.set_title(title, fontsize=10)
    return fig


def _points_line(d, photons):
    """'72 sensors, discs of r 0.5 m, 77759 photons received of 4e+05 emitted'."""
    return (f"{d.nx} sensors, discs of r {d.attrs.get('radius_m', float('nan')):.3g} m, {d.photons_received} "
            f"photons received of {photons:.3g} emitted")


def value_figure(d, bands=None):
    """The value map of detector ``d`` (band sum) in its units; the colour scale runs from
    0 to the largest cell value. A points detector's sensors are drawn as coloured dots."""
    value, _ = d.band_sum()
    if d.is_points:
        top = float(np.nanmax(value)) if np.any(value > 0) else 1.0
        note = _band_note(d, bands)
        return _points_figure(d, np.ma.masked_invalid(value[0]), "viridis", f"{_quantity(d)} ({_units(d)})", top,
                              f"{d.name} \u2014 {d.type}{f' ({note})' if note else ''}, mean {d.mean_value:.4g} "
                              f"{_units(d)} \u00b1 {100 * d.mean_sigma_rel:.3g} %\n{_points_line(d, float(d.photons))}")
    fig, ax = plt.subplots(figsize=_figsize(d), layout="constrained")
    top = float(np.nanmax(value)) if np.any(value > 0) else 1.0
    im = ax.imshow(value, origin="lower", extent=_extent(d), cmap="viridis", interpolation="nearest",
                   vmin=0.0, vmax=top)
    fig.colorbar(im, ax=ax, label=f"{_quantity(d)} ({_units(d)})")
    note = _band_note(d, bands)
    ax.set_title(f"{d.name} \u2014 {d.type}{f' ({note})' if note else ''}, mean {d.mean_value:.4g} {_units(d)} "
                 f"\u00b1 {100 * d.mean_sigma_rel:.3g} %\n{_grid_line(d, float(d.photons))}", fontsize=11)
    _map_axes(ax, d)
    return fig


def daylight_factor_figure(d):
    """The daylight factor map of a ``daylight_factor`` detector in %, with the grid's median
    and 95 % values (bias-corrected, with their errors) and the EN 17037 verdict when judged."""
    df = d.daylight_factor
    top = float(np.nanmax(df)) if np.any(df > 0) else 1.0
    if d.is_points:
        fig = _points_figure(d, np.ma.masked_invalid(df[0]), "viridis", "DF (%)", top, "")
        ax = fig.axes[0]
    else:
        fig, ax = plt.subplots(figsize=_figsize(d), layout="constrained")
        im = ax.imshow(df, origin="lower", extent=_extent(d), cmap="viridis", interpolation="nearest", vmin=0.0,
                       vmax=top)
        fig.colorbar(im, ax=ax, label="DF (%)")
    f = d.daylight_figures()
    line = f"E_h,ext {d.daylight_reference_lx:.4g} lx"
    if f is not None:
        m, q = f["median"], f["df_95"]
        line += (f"; median {m['corrected']:.3g} \u00b1 {m['sigma']:.2g} %, over 95 % {q['corrected']:.3g} "
                 f"\u00b1 {q['sigma']:.2g} % (bias-corrected)")
        if "en17037" in f:
            e = f["en17037"]
            line += f"\nEN 17037 (D_T {e['target_df']:.3g} %, D_TM {e['minimum_df']:.3g} %): {e['verdict']}"
    ax.set_title(f"{d.name} \u2014 daylight factor, mean {f['mean'] if f else float(np.mean(df)):.3g} %\n{line}",
                 fontsize=10)
    if not d.is_points:
        _map_axes(ax, d)
    return fig


def error_figure(d, bands=None):
    """Relative error per cell in % (eq. 8, or the replicate spread of sobol), from 0 to the
    largest; cells without hits are grey with a cross."""
    _, rel = d.band_sum()
    cmap = plt.get_cmap("inferno").copy()
    cmap.set_bad("0.62")
    with np.errstate(over="ignore"):  # a damaged file's error can overflow in %: shown as no estimate
        pct = np.ma.masked_invalid(100 * rel)
    top = float(pct.max()) if pct.count() else 1.0
    note = _band_note(d, bands)
    title = (f"{d.name} \u2014 relative error per cell{f' ({note})' if note else ''}; eq. (9): "
             f"{100 * d.sigma_rel_arithmetic:.3g} % arithmetic, {100 * d.sigma_rel_quadratic:.3g} % quadratic")
    if d.is_points:
        return _points_figure(d, pct[0], cmap, "\u03c3 rel (%)", top, title)
    fig, ax = plt.subplots(figsize=_figsize(d), layout="constrained")
    im = ax.imshow(pct, origin="lower", extent=_extent(d), cmap=cmap, interpolation="nearest", vmin=0.0, vmax=top)
    fig.colorbar(im, ax=ax, label="\u03c3 rel (%)")
    jj, ii = np.nonzero(~np.isfinite(rel))
    su, sv = d.size_m
    if len(ii):
        ax.plot(-su / 2 + (ii + 0.5) * su / d.nx, -sv / 2 + (jj + 0.5) * sv / d.ny, "x", color="0.3", ms=6,
                label="no hits")
        ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title, fontsize=10)
    _map_axes(ax, d)
    return fig


def error_histogram_figure(d, bands=None):
    """Histogram of the per-cell relative errors (cells with hits only), with the two
    eq. (9) summaries as vertical lines."""
    _, rel = d.band_sum()
    with np.errstate(over="ignore"):  # a damaged file can hold errors beyond any float in %
        e = 100 * rel
    e = e[np.isfinite(e)]
    fig, ax = plt.subplots(figsize=(8, 5), layout="constrained")
    bins = int(np.clip(round(np.sqrt(max(len(e), 1))), 10, 60))
    ax.hist(e, bins=bins, color="C3", alpha=0.75, edgecolor="0.25")
    ax.axvline(100 * d.sigma_rel_arithmetic, color="C0", lw=2,
               label=f"eq. (9) arithmetic: {100 * d.sigma_rel_arithmetic:.3g} %")
    ax.axvline(100 * d.sigma_rel_quadratic, color="C2", lw=2, ls="--",
               label=f"eq. (9) quadratic: {100 * d.sigma_rel_quadratic:.3g} %")
    ax.set_xlim(left=0)
    ax.set_xlabel("relative error per cell (%)")
    ax.set_ylabel("cells")
    note = _band_note(d, bands)
    ax.set_title(f"{d.name} \u2014 relative errors of {len(e)} cells with hits ({rel.size - len(e)} without)"
                 f"{f'; {note}' if note else ''}", fontsize=11)
    ax.legend(fontsize=9)
    return fig


def brightest_cell(d):
    """(i, j) of the cell with the largest band-summed value."""
    value, _ = d.band_sum()
    j, i = np.unravel_index(int(np.argmax(value)), value.shape)
    return int(i), int(j)


def sections_figure(d, i=None, j=None, bands=None):
    """Two sections through cell (i, j) (default: the brightest cell): row j along u on top,
    column i along up below, each value as steps with a +-1 sigma band."""
    if i is None or j is None:
        i, j = brightest_cell(d)
    if not (0 <= i < d.nx and 0 <= j < d.ny):
        raise ValueError(f"cell {i},{j} is outside detector '{d.name}' (i in 0..{d.nx - 1}, j in 0..{d.ny - 1})")
    value, rel = d.band_sum()
    if d.is_points:
        return _sensor_sequence_figure(d, i, value[0], rel[0], bands)
    su, sv = d.size_m
    fig, axes = plt.subplots(2, 1, figsize=(8, 7.6), layout="constrained")
    note = _band_note(d, bands)
    u, v = d.cell_coordinates()
    err = f"\u00b1 {100 * rel[j, i]:.3g} %" if np.isfinite(rel[j, i]) else "(no hits)"
    fig.suptitle(f"{d.name} \u2014 sections through cell i = {i}, j = {j}{f' ({note})' if note else ''}; "
                 f"band: \u00b1 1 \u03c3\nvalue {value[j, i]:.4g} {_units(d)} {err} at u = {u[i]:.3g} m, "
                 f"v = {v[j]:.3g} m from the centre", fontsize=11)
    for ax, vals, r, size, n, at, axis in (
            (axes[0], value[j, :], rel[j, :], su, d.nx, i, f"u (m) along {_vec(d.u)}"),
            (axes[1], value[:, i], rel[:, i], sv, d.ny, j, f"v (m) along up {_vec(d.up)}")):
        edges = np.linspace(-size / 2, size / 2, n + 1)
        s = np.where(np.isfinite(r), r * vals, 0.0)
        ax.stairs(vals + s, edges, baseline=vals - s, fill=True, color="C0", alpha=0.3, label="\u00b1 1 \u03c3")
        ax.stairs(vals, edges, baseline=None, color="C0", lw=1.8, label="value")
        ax.set_xlim(-size / 2, size / 2)
        ax.axvline(-size / 2 + (at + 0.5) * size / n, color="C3", ls="--", lw=1.2)
        ax.set_xlabel(axis)
        ax.set_ylabel(f"{_quantity(d)} ({_units(d)})")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    axes[0].set_title(f"horizontal: row j = {j}", fontsize=10, loc="left")
    axes[1].set_title(f"vertical: column i = {i}", fontsize=10, loc="left")
    return fig


def _sensor_sequence_figure(d, i, value, rel, bands=None):
    """A points detector's sections: every sensor's value in file order, with a +-1 sigma
    band, sensor i marked."""
    fig, ax = plt.subplots(figsize=(8, 4.6), layout="constrained")
    edges = np.arange(d.nx + 1) - 0.5
    s = np.where(np.isfinite(rel), rel * value, 0.0)
    ax.stairs(value + s, edges, baseline=value - s, fill=True, color="C0", alpha=0.3, label="\u00b1 1 \u03c3")
    ax.stairs(value, edges, baseline=None, color="C0", lw=1.8, label="value")
    ax.axvline(i, color="C3", ls="--", lw=1.2)
    note = _band_note(d, bands)
    err = f"\u00b1 {100 * rel[i]:.3g} %" if np.isfinite(rel[i]) else "(no hits)"
    ax.set_title(f"{d.name} \u2014 every sensor in file order{f' ({note})' if note else ''}; band: \u00b1 1 \u03c3\n"
                 f"sensor {i} at {_vec(d.positions[i])}: {value[i]:.4g} {_units(d)} {err}", fontsize=10)
    ax.set_xlabel("sensor (line order of the .pts file)")
    ax.set_ylabel(f"{_quantity(d)} ({_units(d)})")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def save(fig, path):
    """Write the figure as PNG atomically (a temporary file beside the target, then a
    rename) and close it. Returns the path."""
    tmp = os.path.join(os.path.dirname(path) or ".", f".{os.path.basename(path)}.tmp.{os.getpid()}.png")
    try:
        fig.savefig(tmp, dpi=_DPI)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def detector_pictures(res, name, out_dir, cell=None, scene=None):
    """Write NAME_value.png, NAME_error.png, NAME_error_hist.png and NAME_sections.png of
    detector ``name`` of result ``res`` into ``out_dir`` (and NAME_df.png, the daylight factor
    map in %, for a ``daylight_factor`` detector); ``cell`` = (i, j) for the sections
    (default: the brightest cell); ``scene``: the detector as the stored light scene of that
    name has it (:meth:`Result.scene_detector`). Returns the paths."""
    d = res.detector(name) if scene is None else res.scene_detector(scene, name)
    i, j = cell if cell is not None else brightest_cell(d)
    if not (0 <= i < d.nx and 0 <= j < d.ny):
        raise ValueError(f"cell {i},{j} is outside detector '{name}' (i in 0..{d.nx - 1}, j in 0..{d.ny - 1})")
    os.makedirs(out_dir, exist_ok=True)
    figures = ((value_figure, "value"), (error_figure, "error"), (error_histogram_figure, "error_hist"))
    paths = [save(make(d, res.bands), os.path.join(out_dir, f"{name}_{suffix}.png")) for make, suffix in figures]
    paths.append(save(sections_figure(d, i, j, res.bands), os.path.join(out_dir, f"{name}_sections.png")))
    if d.is_daylight:
        paths.append(save(daylight_factor_figure(d), os.path.join(out_dir, f"{name}_df.png")))
    return paths


# --------------------------------------------------------------------------- convergence
def _target_kind(label):
    if label.endswith(" received"):
        return "count"
    if label.endswith(" abs"):
        return "abs"
    return "rel"


def _target_units(res, label):
    """Units of an absolute-error target: its detector's, or lux for the global map."""
    if label.startswith("detector:"):
        name = label[len("detector:"):].split("[")[0].split(" ")[0]
        if name in res.detectors:
            return _units(res.detectors[name])
    return "lx"


def _forecast_curve(t_last, n_last, v_last, goal, t_goal, power):
    """The forecast of a reduction as a curve in time: value ~ N^power (N^-1/2 for errors,
    N for counts) through that point, with the photon rate that reaches the goal exactly
    at the stored forecast time."""
    n_goal = n_last * (goal / v_last) ** (1.0 / power)
    rate = (n_goal - n_last) / (t_goal - t_last)
    t = np.geomspace(t_last, t_goal, 50)
    return t, v_last * ((n_last + rate * (t - t_last)) / n_last) ** power


def convergence_figure(res):
    """Error against wall time, log-log, one panel per target of the run with its goal, the
    forecast made at the last reduction before the goal was met and the time it was met;
    the global map's relative error (eq. 5, quadratic) in every relative-error panel."""
    h = res.history
    if h is None or len(h) == 0:
        raise ValueError(f"{res.path or 'the result'} has no convergence history")
    t = np.asarray(h.time_s, dtype=float)
    photons = np.asarray(h.photons, dtype=float)
    glob = np.asarray(h.sigma_rel_global, dtype=float)
    labels, goals = h.target_labels, h.target_goals
    values = h.target_value
    forecasts = h.target_forecast_s
    kinds = [_target_kind(lb) for lb in labels]
    panels = list(range(len(labels)))
    if "rel" not in kinds:
        panels.append(None)  # the global map on its own
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 3.6 * len(panels) + 0.6), squeeze=False,
                             layout="constrained")
    fig.suptitle(f"{os.path.basename(res.path or 'combined')}: convergence (stopped by {res.stop_reason})",
                 fontsize=12)
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
            goal_text = f"{goal:.0f}" if kind == "count" else f"{scale * goal:.4g}"
            ax.axhline(scale * goal, color="C3", ls="--", lw=1.2,
                       label="goal " + goal_text + (" %" if kind == "rel" else ""))
            met = ((v >= goal) if kind == "count" else (v <= goal)) & ok
            if met.any():
                ax.axvline(t[int(np.argmax(met))], color="C2", lw=1.2, label=f"met at {t[int(np.argmax(met))]:.3g} s")
            before = np.nonzero(ok & ~np.maximum.accumulate(met))[0]
            if len(before):
                i = int(before[-1])
                tf = forecasts[i, k]
                if np.isfinite(tf) and tf > t[i]:
                    power = 1.0 if kind == "count" else -0.5
                    ft, fv = _forecast_curve(t[i], photons[i], v[i], goal, tf, power)
                    ax.loglog(ft, scale * fv, ":", color="C1", lw=1.6,
                              label=f"forecast at {t[i]:.3g} s: goal at {tf:.3g} s")
                    ax.plot([tf], [scale * goal], "D", color="C1", ms=5)
            ax.set_title(label, fontsize=10)
            ax.set_ylabel({"rel": "relative error (%)", "abs": f"error ({_target_units(res, label)})",
                           "count": "photons received"}[kind])
        ax.set_xlabel("wall time (s)")
        for a in (ax.xaxis, ax.yaxis):  # plain numbers on the log axes
            a.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
            a.set_major_formatter(ticker.FuncFormatter(lambda x, _: f"{x:g}"))
            a.set_minor_formatter(ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    return fig


# --------------------------------------------------------------------------- command line
def _parse_cell(text):
    try:
        i, j = (int(x) for x in text.split(","))
    except ValueError:
        raise ValueError(f"--cell: '{text}' is not i,j (two integers)") from None
    return i, j


def checked_input(prog, path, check):
    """``check()``'s value, or None after one message on stderr when the input is bad (no
    such file, a damaged file, a name or value the file does not have): the command lines
    then exit 2 having written nothing."""
    try:
        return check()
    except FileNotFoundError as e:
        print(f"{prog}: {path}: {e.strerror}", file=sys.stderr)
    except (ValueError, KeyError) as e:
        print(f"{prog}: {e.args[0] if e.args else e}", file=sys.stderr)
    return None


def main(argv=None, prog="python3 -m luxtrace.plot"):
    """Command line: detector pictures (and with --convergence the convergence plot) of a
    result. Bad input (no such file or detector, a damaged file, a bad cell) exits 2 with
    one message and writes nothing."""
    p = argparse.ArgumentParser(prog=prog, description="Detector pictures and convergence plot of a luxtrace result.")
    p.add_argument("result", help="result or checkpoint file (.h5)")
    p.add_argument("--detector", action="append", default=[], metavar="NAME", help="pictures of detector NAME (repeatable)")
    p.add_argument("--cell", default="", metavar="I,J", help="i,j: the cell the sections go through (default: the brightest)")
    p.add_argument("-o", "--out-dir", metavar="DIR", help="folder for the PNGs (default: beside the result)")
    p.add_argument("--convergence", action="store_true", help="also convergence.png (error against time)")
    p.add_argument("--scene", metavar="NAME", help="the detectors as the run's [[light_scene]] NAME has them")
    a = p.parse_args(argv)
    if not a.detector and not a.convergence:
        p.error("nothing to draw: give --detector NAME and/or --convergence")
    out_dir = a.out_dir or os.path.dirname(os.path.abspath(a.result))

    def check():  # everything is checked before anything is written
        res = _result.open(a.result)
        cell = _parse_cell(a.cell) if a.cell else None
        for name in a.detector:
            d = res.detector(name) if a.scene is None else res.scene_detector(a.scene, name)
            if cell and not (0 <= cell[0] < d.nx and 0 <= cell[1] < d.ny):
                raise ValueError(f"--cell {a.cell} is outside detector '{name}' "
                                 f"(i in 0..{d.nx - 1}, j in 0..{d.ny - 1})")
        if a.convergence and (res.history is None or len(res.history) == 0):
            raise ValueError(f"{a.result}: no convergence history")
        return res, cell
    checked = checked_input(prog, a.result, check)
    if checked is None:
        return 2
    res, cell = checked
    written = []
    if a.convergence:
        os.makedirs(out_dir, exist_ok=True)
        written.append(save(convergence_figure(res), os.path.join(out_dir, "convergence.png")))
    for name in a.detector:
        written += detector_pictures(res, name, out_dir, cell, a.scene)
    for w in written:
        print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
