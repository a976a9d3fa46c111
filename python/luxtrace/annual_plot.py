"""Pictures of an annual daylight result (docs/ANNUAL.md) with matplotlib (Agg):

    da_figure(res, name)              DA per sensor in %, the 50 % line that sDA300/50% counts
    ase_figure(res, name)             ASE hours per sensor, the 250 h line of ASE1000,250h
    hours_figure(res, name, sensor)   a sensor's illuminance, hour of the day x day of the year

A grid detector is drawn as an image of its cells (as luxtrace.plot draws it, its ``up``
upwards), with the threshold as a contour line through the cell centres; a points
detector as dots at its sensors, those at or over the threshold ringed in black.
:func:`annual_pictures` writes NAME_da.png, NAME_ase.png and NAME_hours.png. From the shell::

    python3 -m luxtrace.annual_plot RESULT.h5 [--grid NAME] [--sensor C] [-o DIR]
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import plot as _plot  # noqa: E402
from . import result as _result  # noqa: E402

SDA_DA = 0.5  #: sDA300/50% counts the sensors with DA at or above this share
ASE_HOURS = 250.0  #: ASE1000,250h counts the sensors with more than this many hours
_MONTHS = ("Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec")


def _grid(res, name):
    """(detector, annual grid) of NAME; KeyError saying what is missing."""
    if res.annual is None:
        raise KeyError(f"{res.path or 'the result'}: not an annual result (no /annual)")
    return res.detector(name), res.annual.grid(name)


def _pm(m, scale, unit, digits=3):
    """'82.1 +- 1.3 %' of a Metric of floats (no error in a checkpoint)."""
    text = f"{scale * m.value:.{digits}g}"
    return text + ("" if m.sigma is None else f" \u00b1 {scale * m.sigma:.2g}") + unit


def _sensor_map(d, values, label, cmap, vmax, level, at_or_above, title):
    """``values`` [C] over detector ``d``: an image of its cells with a contour at ``level``,
    or its sensors as dots, those past ``level`` ringed."""
    if d.is_points:
        fig = _plot._points_figure(d, np.ma.masked_invalid(values), cmap, label, vmax, title)
        u, v = _plot._sensor_plane(d)
        p = np.asarray(d.positions, dtype=float)
        past = values >= level if at_or_above else values > level
        if past.any():
            ax = fig.axes[0]
            sign = "\u2265" if at_or_above else ">"
            ax.scatter((p @ u)[past], (p @ v)[past], s=130, facecolors="none", edgecolors="k", linewidths=1.2,
                       label=f"{sign} {level:g}")
            ax.legend(loc="upper right", fontsize=8)
        return fig
    image = np.asarray(values, dtype=float).reshape(d.ny, d.nx)
    fig, ax = plt.subplots(figsize=_plot._figsize(d), layout="constrained")
    im = ax.imshow(image, origin="lower", extent=_plot._extent(d), cmap=cmap, interpolation="nearest", vmin=0.0,
                   vmax=vmax)
    fig.colorbar(im, ax=ax, label=label)
    u, v = d.cell_coordinates()
    if d.nx > 1 and d.ny > 1 and image.min() < level < image.max():
        ax.contour(u, v, image, levels=[level], colors="w", linewidths=2.0)
    ax.set_title(title, fontsize=10)
    _plot._map_axes(ax, d)
    return fig


def _marked(d, what):
    """How the threshold is shown: a line over a grid, rings round the sensors past it."""
    return f"ringed: {what}" if d.is_points else f"white line: {what}"


def da_figure(res, name):
    """DA300 of every sensor of grid NAME in % (over the occupied hours), from 0 to 100 %,
    with the 50 % line: sDA300/50% is the area on its bright side."""
    d, g = _grid(res, name)
    da = g.sensors["da"]
    title = (f"{name} \u2014 daylight autonomy DA300 ({g.sensor_count} sensors), mean "
             f"{_pm(g.metrics['mean_da'], 100, ' %')}\nsDA300/50% {_pm(g.metrics['sda'], 100, ' %')} "
             f"(the area with DA \u2265 50 %; {_marked(d, '50 %')})")
    return _sensor_map(d, 100 * np.asarray(da.value, dtype=float), "DA300 (% of occupied hours)", "viridis", 100.0,
                       100 * SDA_DA, True, title)


def ase_figure(res, name):
    """Occupied hours of direct sun of 1000 lx or more at every sensor of grid NAME, with the
    250 h line: ASE1000,250h is the area beyond it."""
    d, g = _grid(res, name)
    hours = np.asarray(g.sensors["ase_hours"].value, dtype=float)
    top = max(float(np.nanmax(hours)) if hours.size else 0.0, 2 * ASE_HOURS)
    title = (f"{name} \u2014 hours of direct sun \u2265 1000 lx ({g.sensor_count} sensors)\n"
             f"ASE1000,250h {_pm(g.metrics['ase'], 100, ' %')} (the area with more than 250 h; "
             f"{_marked(d, '250 h')})")
    return _sensor_map(d, hours, "direct sun \u2265 1000 lx (occupied hours)", "magma", top, ASE_HOURS, False, title)


def typical_sensor(res, name):
    """The sensor whose DA is the grid's median (the first such): the heat map's default."""
    da = np.asarray(_grid(res, name)[1].sensors["da"].value, dtype=float)
    return int(np.argsort(da, kind="stable")[(len(da) - 1) // 2])


def hours_image(res, name, sensor):
    """[24, days] illuminance of sensor ``sensor`` of grid NAME (lx; NaN for an hour the
    file does not have), row = the hour of the day its middle lies in, column = the day."""
    a = res.annual
    g = _grid(res, name)[1]
    if not 0 <= sensor < g.sensor_count:
        raise ValueError(f"sensor {sensor} is outside grid '{name}' (0..{g.sensor_count - 1})")
    day = a.day_of_year()
    hour = np.clip(np.floor(np.asarray(a.hours.hour, dtype=float)).astype(int), 0, 23)
    image = np.full((24, int(day.max()) + 1), np.nan)
    image[hour, day] = np.asarray(g.illuminance_lx[:, sensor], dtype=float)
    return image


def hours_figure(res, name, sensor=None):
    """A sensor's illuminance over the year: hour of the day (local standard time) up, day
    of the year across, 0 lx (dark) black; the DA and occupied hours in the title."""
    if sensor is None:
        sensor = typical_sensor(res, name)
    d, g = _grid(res, name)
    image = hours_image(res, name, sensor)
    fig, ax = plt.subplots(figsize=(12, 4.8), layout="constrained")
    top = float(np.nanmax(image)) if np.nanmax(image) > 0 else 1.0
    cmap = plt.get_cmap("inferno").copy()
    cmap.set_bad("0.62")
    im = ax.imshow(np.ma.masked_invalid(image), origin="lower", aspect="auto", cmap=cmap, vmin=0.0, vmax=top,
                   extent=[0, image.shape[1], 0, 24], interpolation="nearest")
    fig.colorbar(im, ax=ax, label="E (lx)")
    occ = np.atleast_1d(res.annual.attrs.get("occupied_hours", []))
    if len(occ) == 2:
        for h in occ:
            ax.axhline(h, color="w", ls="--", lw=0.8)
    starts = np.cumsum([0, 31, 29 if image.shape[1] > 365 else 28, 31, 30, 31, 30, 31, 31, 30, 31, 30])
    ax.set_xticks(starts, _MONTHS)
    ax.set_yticks(range(0, 25, 3))
    ax.set_xlabel("day of the year")
    ax.set_ylabel("hour of the day (local standard time)")
    where = (f"at {_plot._vec(d.positions[sensor])}" if d.is_points
             else f"cell i = {sensor % d.nx}, j = {sensor // d.nx}")
    da = g.sensors["da"]
    da_text = f"{100 * da.value[sensor]:.3g}" + ("" if da.sigma is None else f" \u00b1 {100 * da.sigma[sensor]:.2g}")
    ax.set_title(f"{name} \u2014 sensor {sensor} ({where}): illuminance every hour, {res.annual.weather}\n"
                 f"DA300 {da_text} %, ASE hours {g.sensors['ase_hours'].value[sensor]:.4g}; "
                 f"dashed: the occupied hours", fontsize=10)
    return fig


def annual_pictures(res, name, out_dir, sensor=None):
    """Write NAME_da.png, NAME_ase.png and NAME_hours.png (sensor ``sensor``, default
    :func:`typical_sensor`) of grid NAME into ``out_dir``; returns the paths."""
    _grid(res, name)
    os.makedirs(out_dir, exist_ok=True)
    return [_plot.save(da_figure(res, name), os.path.join(out_dir, f"{name}_da.png")),
            _plot.save(ase_figure(res, name), os.path.join(out_dir, f"{name}_ase.png")),
            _plot.save(hours_figure(res, name, sensor), os.path.join(out_dir, f"{name}_hours.png"))]


def main(argv=None, prog="python3 -m luxtrace.annual_plot"):
    """Command line: the annual pictures of every grid (or those named). Bad input (no such
    file or grid, not an annual result, a sensor outside the grid) exits 2 with one message
    and writes nothing."""
    p = argparse.ArgumentParser(prog=prog, description="DA, ASE and hourly pictures of an annual luxtrace result.")
    p.add_argument("result", help="result file (.h5) of a scene with [annual]")
    p.add_argument("--grid", action="append", default=[], metavar="NAME",
                   help="pictures of sensor grid NAME (repeatable; default: every grid)")
    p.add_argument("--sensor", type=int, metavar="C",
                   help="the sensor of the hourly heat map (default: the one with the median DA)")
    p.add_argument("-o", "--out-dir", metavar="DIR", help="folder for the PNGs (default: beside the result)")
    a = p.parse_args(argv)
    out_dir = a.out_dir or os.path.dirname(os.path.abspath(a.result))

    def check():  # everything is checked before anything is written
        res = _result.open(a.result)
        if res.annual is None:
            raise ValueError(f"{a.result}: not an annual result (its scene has no [annual])")
        names = a.grid or sorted(res.annual.grids)
        for name in names:
            g = _grid(res, name)[1]
            if a.sensor is not None and not 0 <= a.sensor < g.sensor_count:
                raise ValueError(f"--sensor {a.sensor} is outside grid '{name}' (0..{g.sensor_count - 1})")
        return res, names
    checked = _plot.checked_input(prog, a.result, check)
    if checked is None:
        return 2
    res, names = checked
    for name in names:
        for w in annual_pictures(res, name, out_dir, a.sensor):
            print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
