"""Annual daylight results: the /annual group of a result (docs/REFERENCE.md §4,
docs/ANNUAL.md) as :class:`Annual`, ``Result.annual`` (None for a run without ``[annual]``).

    a = luxtrace.open("office.h5").annual
    a.hours.month, a.hours.occupied              # the hours table, [H] each
    g = a.grid("desk")
    g.illuminance_lx, g.illuminance_sigma_lx     # [H, C] every hour, every sensor
    g.metrics["sda"].value, g.metrics["sda"].sigma
    g.sensors["da"].value                        # [C]
    g.en17037["minimum"].passed, g.en17037["minimum"].flip_probability

Every figure is read as luxtrace wrote it; nothing is recomputed here. The daylight
coefficients' counts ([G, C] three times, large for big grids) are read on demand by
:meth:`AnnualGrid.coefficients`.
"""
from collections import namedtuple

import h5py
import numpy as np

from ._attributes import AttrAccess, attributes

#: The per-hour datasets of /annual, the columns of :attr:`Annual.hours`.
HOUR_COLUMNS = ("month", "day", "hour", "occupied", "daylit", "en17037_hour", "sun_altitude_deg", "sun_azimuth_deg",
                "diffuse_horizontal_lx", "direct_normal_lx", "global_horizontal_lx", "sun_group",
                "weather_diffuse_horizontal_w_m2", "weather_direct_normal_w_m2", "weather_dew_point_c")
#: Per-sensor figures of a grid ([C] each, over the occupied hours); ase_hours in hours.
SENSOR_METRICS = ("da", "continuous_da", "udi_fell_short", "udi_useful", "udi_exceeded", "ase_hours")
#: A grid's figures (area shares and area means).
GRID_METRICS = ("sda", "ase", "mean_da", "mean_continuous_da", "mean_udi_fell_short", "mean_udi_useful",
                "mean_udi_exceeded")
#: EN 17037's levels: (target lx over 50 % of the plane, minimum target lx over 95 % of it).
EN17037_LEVELS = {"minimum": (300.0, 100.0), "medium": (500.0, 300.0), "high": (750.0, 500.0)}
#: The hourly datasets of a grid, [H, C] each.
HOURLY = ("illuminance_lx", "illuminance_sigma_lx", "direct_sun_lx", "direct_sun_sigma_lx")


class Metric(namedtuple("Metric", "value sigma bias")):
    """A figure with its standard error and SIMEX bias (None in a checkpoint, which has no
    errors); arrays [C] for a sensor's figures, floats for a grid's."""

    @property
    def corrected(self):
        """value - bias (the value itself when there is no bias)."""
        return self.value if self.bias is None else self.value - self.bias


En17037Level = namedtuple("En17037Level", "target_lx minimum_lx target_hours minimum_hours passed flip_probability")
En17037Level.__doc__ = ("One EN 17037 level of a grid: its two illuminances, the shares of the daylight hours at "
                        "which they cover 50 % and 95 % of the grid (:class:`Metric`), the verdict and the "
                        "probability that it is the wrong one (None in a checkpoint).")


class AnnualGrid(AttrAccess):
    """One sensor grid (an illuminance or points detector) of an annual run:
    /annual/detectors/NAME. ``illuminance_lx``, ``illuminance_sigma_lx``, ``direct_sun_lx``,
    ``direct_sun_sigma_lx`` [H, C] (float32 as stored; 0 when dark); ``sensors`` (name ->
    :class:`Metric` of [C] arrays), ``metrics`` (name -> :class:`Metric`), ``en17037``
    (level -> :class:`En17037Level`), ``replicates`` (0 in a checkpoint). C is the
    detector's cells in row order (j * nx + i) or its sensors in file order."""

    def __init__(self, name, attrs, datasets, path=None):
        self.name = name
        self.attrs = dict(attrs)
        self.path = path
        for k in HOURLY:
            setattr(self, k, datasets.get(k))
        self.sensors = {k: Metric(datasets[k], datasets.get(k + "_sigma"), datasets.get(k + "_bias"))
                        for k in SENSOR_METRICS if k in datasets}
        self.metrics = {k: Metric(self.attrs[k], self.attrs.get(k + "_sigma"), self.attrs.get(k + "_bias"))
                        for k in GRID_METRICS if k in self.attrs}
        self.en17037 = {}
        for level, (target_lx, minimum_lx) in EN17037_LEVELS.items():
            n = f"en17037_{level}"
            if n + "_pass" not in self.attrs:
                continue
            hours = [Metric(self.attrs[f"{n}_{k}_hours"], self.attrs.get(f"{n}_{k}_hours_sigma"), None)
                     for k in ("target", "minimum")]
            self.en17037[level] = En17037Level(target_lx, minimum_lx, hours[0], hours[1],
                                               bool(self.attrs[n + "_pass"]),
                                               self.attrs.get(n + "_flip_probability") if self.replicates else None)

    def __repr__(self):
        return f"<AnnualGrid {self.name}: {self.sensor_count} sensors, {self.hour_count} hours>"

    replicates = property(lambda self: int(self.attrs.get("replicates", 0)),
                          doc="replicate years the errors come from (0: a checkpoint, no errors)")
    sensor_count = property(lambda self: int(np.shape(self.illuminance_lx)[1]), doc="C")
    hour_count = property(lambda self: int(np.shape(self.illuminance_lx)[0]), doc="H")

    def coefficients(self):
        """The daylight coefficients' counts, read from the file now: ``count``, ``sumsq``,
        ``direct_count`` (uint64 [G, C]) and the attributes ``first_patch_group``,
        ``ground_group``, ``first_sun_group``."""
        if not self.path:
            raise KeyError(f"grid '{self.name}': no file to read the coefficients from")
        with h5py.File(self.path, "r") as f:
            g = f[f"annual/detectors/{self.name}/coefficients"]
            out = {k: v[()] for k, v in g.items()}
            out.update(attributes(g))
        return out


class Annual(AttrAccess):
    """The /annual group: the year's hours and skies and every sensor grid.

    ``attrs`` (``weather``, ``sky``, ``sky_mf``, ``daylit_hours``, ``sun_hours``,
    ``occupied_hours``, ... also readable as attributes); ``hours``: the hours table, a
    numpy record array [H] with the fields :data:`HOUR_COLUMNS` (``a.hours.month``,
    ``a.hours[4000]``); ``patch_bounds_deg`` [P, 4], ``patch_solid_angle_sr``,
    ``patch_projected_solid_angle_sr`` [P]; ``sky_vectors_cd_m2`` [R, P + 1] (each daylit
    hour's patches, then the ground); ``yearly_luminance_cd_m2_h`` [P + 1]; ``grids``
    (name -> :class:`AnnualGrid`)."""

    def __init__(self, attrs, datasets, grids):
        self.attrs = dict(attrs)
        present = [k for k in HOUR_COLUMNS if k in datasets]
        self.hours = np.rec.fromarrays([datasets[k] for k in present], names=present)
        for k in ("patch_bounds_deg", "patch_solid_angle_sr", "patch_projected_solid_angle_sr", "sky_vectors_cd_m2",
                  "yearly_luminance_cd_m2_h"):
            setattr(self, k, datasets.get(k))
        self.grids = dict(grids)

    def __repr__(self):
        return f"<Annual {self.weather}: {len(self.hours)} hours, grids {sorted(self.grids)}>"

    @property
    def patches(self):
        """P, the sky patches (the ground not counted)."""
        return int(np.shape(self.patch_solid_angle_sr)[0])

    def grid(self, name):
        """Sensor grid NAME; KeyError naming the grids there are otherwise."""
        try:
            return self.grids[name]
        except KeyError:
            raise KeyError(f"no annual sensor grid '{name}' (the result has: "
                           f"{', '.join(sorted(self.grids)) or 'none'})") from None

    def day_of_year(self):
        """[H]: each hour's day of the year from 0, from its month and day."""
        month, day = np.asarray(self.hours.month, dtype=int), np.asarray(self.hours.day, dtype=int)
        starts = np.cumsum([0] + [31, 29 if len(self.hours) > 8760 else 28, 31, 30, 31, 30, 31, 31, 30, 31, 30])
        return starts[np.clip(month, 1, 12) - 1] + day - 1

    def summary(self):
        """A few lines like ``luxtrace info``'s annual block."""
        h = self.hours
        lines = [f"annual {self.weather}: {self.daylit_hours} daylit hours of {len(h)}, {self.sun_hours} with a sun; "
                 f"{self.sky} skies over {self.patches} patches (sky_mf {self.sky_mf}); "
                 f"{int(np.count_nonzero(h.occupied))} occupied hours"]
        for g in self.grids.values():
            def pct(name):
                m = g.metrics[name]
                return f"{100 * m.value:.2f}" + ("" if m.sigma is None else f" +- {100 * m.sigma:.2f}") + " %"
            lines.append(f"grid {g.name}: {g.sensor_count} sensors, sDA {pct('sda')}, ASE {pct('ase')}, "
                         f"mean DA {pct('mean_da')}, UDI useful {pct('mean_udi_useful')}, EN 17037 "
                         + ", ".join(f"{k} {'pass' if v.passed else 'fail'}" for k, v in g.en17037.items()))
        return "\n".join(lines)


def read(f, path=None):
    """/annual of the open h5py file ``f`` as an :class:`Annual`, or None without it."""
    if "annual" not in f:
        return None
    a = f["annual"]
    datasets = {k: v[()] for k, v in a.items() if isinstance(v, h5py.Dataset)}
    H = len(datasets.get("month", ()))
    if any(np.shape(datasets.get(k, np.zeros(H))) != (H,) for k in HOUR_COLUMNS):
        raise ValueError("the /annual hour datasets differ in length")
    grids = {}
    for name, g in (a["detectors"].items() if "detectors" in a else ()):
        d = {k: v[()] for k, v in g.items() if isinstance(v, h5py.Dataset)}
        C = np.shape(d.get("da", ()))[0] if np.ndim(d.get("da", ())) == 1 else -1
        if any(np.shape(d.get(k)) != (H, C) for k in HOURLY) or any(
                np.shape(v) != (C,) for k, v in d.items() if k.split("_sigma")[0].split("_bias")[0] in SENSOR_METRICS):
            raise ValueError(f"/annual/detectors/{name}: its datasets are not [{H}, C] and [C] alike")
        grids[name] = AnnualGrid(name, attributes(g), d, path)
    return Annual(attributes(a), datasets, grids)
