"""Reading luxtrace result and checkpoint files (docs/SPEC.md §4) into typed objects.

A file is read whole into memory and closed again, so a :class:`Result` needs no
``with`` block and can be combined, plotted or exported after the file is gone. Every
attribute of every group is also kept in a plain ``attrs`` dict, so attributes a newer
luxtrace adds are there without a change to this package.
"""
import builtins
import csv
import os
import zlib

import h5py
import numpy as np

from . import sensor_table, statistics
from ._attributes import AttrAccess, attributes, plain
from .annual import read as read_annual

#: The newest result layout this package reads (SPEC §4 ``format_version``).
NEWEST_FORMAT_VERSION = 2
FRONT, BACK = 0, 1  #: side indices of the surface maps: front = where the normal points

_SEAL_BYTES = 512
_SEAL_MAGIC = b"luxtrace-seal v1 "
_HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


class ResultError(ValueError):
    """A file that is not a luxtrace result, is damaged, or is of an unknown format."""


def crc32_and_length(f):
    """CRC-32 and length of what remains of the open binary file ``f`` (the seal's sums)."""
    crc, length = 0, 0
    while True:
        block = f.read(1 << 20)
        if not block:
            return crc, length
        crc = zlib.crc32(block, crc)
        length += len(block)


def check_seal(path):
    """Check the seal luxtrace 0.2 and later put in a file's first 512 bytes (SPEC §4).

    Returns True for a sealed file whose CRC-32 and length match, False for an unsealed
    file of luxtrace 0.1 (HDF5's signature at byte 0); raises ResultError for a file that
    was cut short, appended to, changed, or is not HDF5 at all.
    """
    with builtins.open(path, "rb") as f:
        head = f.read(_SEAL_BYTES)
        if head.startswith(_HDF5_SIGNATURE):
            return False
        if not head.startswith(_SEAL_MAGIC):
            raise ResultError(f"{path}: damaged file: it does not begin with a luxtrace seal or an HDF5 signature")
        try:
            words = head[len(_SEAL_MAGIC):].split(b"\n", 1)[0].split()
            if words[0] != b"crc32" or words[2] != b"length":
                raise ValueError
            want_crc, want_length = int(words[1], 16), int(words[3])
        except (ValueError, IndexError):
            raise ResultError(f"{path}: damaged file: its luxtrace seal cannot be read") from None
        crc, length = crc32_and_length(f)
    if length != want_length:
        raise ResultError(f"{path}: damaged file: it has {length} bytes after its seal, {want_length} when "
                          "luxtrace wrote it (cut short, or appended to)")
    if crc != want_crc:
        raise ResultError(f"{path}: damaged file: its contents changed after luxtrace wrote it (CRC-32 mismatch)")
    return True


class Group(AttrAccess):
    """A group of the file as it was read: ``attrs`` (dict) and ``datasets`` (name -> array).

    Observers (``/observers/NAME``) and anything this package has no class for come as a
    Group; item access reads a dataset: ``g["count"]``.
    """

    def __init__(self, name, attrs, datasets):
        self.name = name
        self.attrs = dict(attrs)
        self.datasets = dict(datasets)

    def __getitem__(self, key):
        return self.datasets[key]

    def __contains__(self, key):
        return key in self.datasets

    def __repr__(self):
        return f"<{type(self).__name__} {self.name}: datasets {sorted(self.datasets)}, attrs {sorted(self.attrs)}>"


class Mesh:
    """The triangulated scene as placed: vertices [V,3] (m), triangles [T,3] (vertex
    indices, counter-clockwise seen from the front side), area_m2 [T], material [T]
    (index into material_names)."""

    def __init__(self, vertices, triangles, area_m2, material, material_names):
        self.vertices = np.asarray(vertices, dtype=float)
        self.triangles = np.asarray(triangles)
        self.area_m2 = np.asarray(area_m2, dtype=float)
        self.material = np.asarray(material)
        self.material_names = list(material_names)

    @property
    def triangle_count(self):
        return len(self.area_m2)

    def same_as(self, other):
        return (self.vertices.shape == other.vertices.shape and self.triangles.shape == other.triangles.shape
                and np.array_equal(self.vertices, other.vertices) and np.array_equal(self.triangles, other.triangles)
                and np.array_equal(self.material, other.material) and self.material_names == other.material_names)


class SurfaceMap(AttrAccess):
    """Per-triangle maps of the whole scene (``/global``), always in format 2's shape.

    Count and illuminance arrays are [T, 2, B]: triangle, side (0 = front, the side the
    normal points to; 1 = back) and band. A format-1 file counted both sides together; its
    data are shown as the front side with a zero back side, and what format 1 does not
    store (``sumsq``, ``sigma_lx``) is None or NaN. ``attrs`` holds every /global attribute.
    """

    #: The integer tallies every figure of the map is computed from (``sumsq`` from format 2
    #: on); :func:`_read_tallies` reads them, a combination adds them up.
    TALLIES = ("count_odd", "count_even", "direct_odd", "direct_even", "sumsq")

    def __init__(self, datasets, attrs, area_m2, format_version):
        self.datasets = dict(datasets)
        self.attrs = dict(attrs)
        self.area_m2 = np.asarray(area_m2, dtype=float)
        self.format_version = format_version

    # ------------------------------------------------------------------ counts
    count_odd = property(lambda self: self.datasets["count_odd"], doc="uint64 [T,2,B]: arrivals of odd photons")
    count_even = property(lambda self: self.datasets["count_even"], doc="uint64 [T,2,B]: arrivals of even photons")
    direct_odd = property(lambda self: self.datasets["direct_odd"], doc="uint64 [T,2,B]: first hits after emission")
    direct_even = property(lambda self: self.datasets["direct_even"], doc="uint64 [T,2,B]")
    sumsq = property(lambda self: self.datasets.get("sumsq"),
                     doc="uint64 [T,2,B]: sum over photons of (arrivals per photon)^2; None in format 1")

    # ------------------------------------------------------------------ maps (lux)
    illuminance_lx = property(lambda self: self.datasets["illuminance"], doc="float64 [T,2,B]: all arrivals")
    illuminance_direct_lx = property(lambda self: self.datasets["illuminance_direct"],
                                     doc="float64 [T,2,B]: first arrivals after emission")

    @property
    def illuminance_secondary_lx(self):
        """float64 [T,2,B]: interreflected light, all arrivals minus direct ones."""
        return self.illuminance_lx - self.illuminance_direct_lx

    odd_even_difference_lx = property(lambda self: self.datasets["odd_even_difference_lx"],
                                      doc="float64 [T,2]: E_odd - E_even, band-summed (the terms of eq. 5)")

    @property
    def sigma_lx(self):
        """float64 [T,2]: standard error of each side's band-summed illuminance from the
        second moment (format 2); NaN for format-1 files, which lack the moment."""
        return self.datasets["sigma_lx"]

    @property
    def side_illuminance_lx(self):
        """float64 [T,2]: each side's illuminance, bands summed (what ``sigma_lx`` is the
        error of, and what the global figures of eqs. 4-5 average)."""
        return self.illuminance_lx.sum(axis=2)

    @property
    def side_area_m2(self):
        """float64 [T,2]: the area of each triangle side (A_t on both), the weights of the
        global figures."""
        return np.repeat(self.area_m2[:, None], 2, axis=1)

    # ------------------------------------------------------------------ summaries
    def _attr(self, name, default=float("nan")):
        return self.attrs.get(name, default)

    odd_even_sigma_lx = property(lambda self: self._attr("sigma_lx"),
                                 doc="RMS error of the map from the odd/even halves, D / 2 (eq. 5)")
    odd_even_rms_lx = property(lambda self: self._attr("odd_even_rms_lx"), doc="D of eq. (5)")
    sigma_rel_arithmetic = property(lambda self: self._attr("sigma_rel_arithmetic"))
    sigma_rel_quadratic = property(lambda self: self._attr("sigma_rel_quadratic"))
    mean_arithmetic_lx = property(lambda self: self._attr("mean_arithmetic_lx"))
    mean_quadratic_lx = property(lambda self: self._attr("mean_quadratic_lx"))
    moment_sigma_lx = property(lambda self: self._attr("moment_sigma_lx"),
                               doc="format 2: area-weighted RMS of the per-side sigmas; NaN in format 1")
    moment_sigma_rel_arithmetic = property(lambda self: self._attr("moment_sigma_rel_arithmetic"))
    moment_sigma_rel_quadratic = property(lambda self: self._attr("moment_sigma_rel_quadratic"))
    error_estimator = property(lambda self: self._attr("error_estimator", "odd_even"),
                               doc='"second_moment" or "odd_even" (format 1 has only the latter)')
    lit_area_m2 = property(lambda self: self._attr("lit_area_m2"))
    photons_escaped = property(lambda self: self._attr("photons_escaped", 0))
    photons_absorbed = property(lambda self: self._attr("photons_absorbed", 0))
    photons_truncated = property(lambda self: self._attr("photons_truncated", 0))


class Detector(AttrAccess):
    """One measuring grid (``/detectors/NAME``).

    Arrays are [ny, nx, B]: row j along the detector's ``up`` axis, column i along
    u = up x normal, band b. A ``points`` detector (Radiance .pts sensors) has ny = 1 and
    column i = sensor i, at ``positions[i]`` facing ``directions[i]``, and no grid plane
    (``center``, ``normal``, ``up``, ``size_m`` are NaN). ``attrs`` holds every attribute of
    the group (also those added after this package was written); the properties below name
    the known ones.
    """

    #: The integer tallies of a grid (``replicate_count`` for sobol only); values and errors
    #: are computed from them. :func:`_read_tallies` reads them.
    TALLIES = ("count", "sumsq", "replicate_count")

    def __init__(self, name, datasets, attrs, photons, replicate_photons=None, task_areas=None):
        self.name = name
        self.datasets = dict(datasets)
        self.attrs = dict(attrs)
        self.photons = int(photons)
        self.replicate_photons = None if replicate_photons is None else np.asarray(replicate_photons)
        #: ``/detectors/NAME/task_areas``: a :class:`Group` per task area, by name, whose
        #: ``attrs`` hold the area's ``cell_range`` and illuminance metrics (``E_avg_lx``, ...)
        self.task_areas = dict(task_areas or {})

    def __repr__(self):
        return f"<Detector {self.name}: {self.type}, {self.nx} x {self.ny} cells, {self.bands} band(s)>"

    # ------------------------------------------------------------------ datasets
    count = property(lambda self: self.datasets["count"], doc="uint64 [ny,nx,B]: n_c = sum of E_i over photons")
    sumsq = property(lambda self: self.datasets["sumsq"], doc="uint64 [ny,nx,B]: q_c = sum of E_i^2")
    value = property(lambda self: self.datasets["value"], doc="float64 [ny,nx,B] in `units` (lx or cd/m^2)")
    sigma_rel = property(lambda self: self.datasets["sigma_rel"],
                         doc="float64 [ny,nx,B]: relative error per cell (eq. 8, or replicate spread); NaN: no hits")
    replicate_count = property(lambda self: self.datasets.get("replicate_count"),
                               doc="uint64 [R,ny,nx,B]: sobol only, n_c per replicate; None otherwise")

    positions = property(lambda self: self.datasets.get("positions"),
                         doc="float64 [nx,3]: points detectors, sensor i's position (m); None otherwise")
    directions = property(lambda self: self.datasets.get("directions"),
                          doc="float64 [nx,3]: points detectors, sensor i's unit direction; None otherwise")

    @property
    def is_points(self):
        """Whether this is a points detector (sensors of a .pts file, one cell each)."""
        return self.type == "points"

    @property
    def sigma(self):
        """float64 [ny,nx,B]: absolute standard error per cell, in `units`."""
        return self.value * self.sigma_rel

    @property
    def bands(self):
        return self.value.shape[2]

    # ------------------------------------------------------------------ known attributes
    def _attr(self, name, default=float("nan")):
        return self.attrs.get(name, default)

    type = property(lambda self: self._attr("type", ""), doc='"illuminance", "luminance", ...')
    units = property(lambda self: self._attr("units", ""), doc='"lx" or "cd/m^2"')
    center = property(lambda self: np.asarray(self._attr("center"), dtype=float))
    normal = property(lambda self: np.asarray(self._attr("normal"), dtype=float))
    up = property(lambda self: np.asarray(self._attr("up"), dtype=float))
    size_m = property(lambda self: tuple(float(x) for x in self._attr("size", (float("nan"),) * 2)),
                      doc="(along u, along up) in m")
    nx = property(lambda self: int(self._attr("cells")[0]))
    ny = property(lambda self: int(self._attr("cells")[1]))
    mean_value = property(lambda self: self._attr("mean_value"), doc="the grid's mean, band-summed")
    mean_sigma_rel = property(lambda self: self._attr("mean_sigma_rel"), doc="relative error of mean_value")
    sigma_rel_arithmetic = property(lambda self: self._attr("sigma_rel_arithmetic"), doc="eq. (9)")
    sigma_rel_quadratic = property(lambda self: self._attr("sigma_rel_quadratic"), doc="eq. (9)")
    photons_received = property(lambda self: self._attr("photons_received", 0))
    error_estimator = property(lambda self: self._attr("error_estimator", "independent_photons_eq8"))
    error_dof = property(lambda self: self._attr("error_dof", 0), doc="0 (eq. 8), or R - 1 for sobol")

    # ------------------------------------------------------------------ daylight factors
    daylight_factor = property(lambda self: self.datasets.get("daylight_factor"),
                               doc="float64 [ny,nx]: DF = 100 E / E_h,ext in %, bands summed (daylight_factor "
                                   "detectors); None otherwise")
    daylight_factor_sigma = property(lambda self: self.datasets.get("daylight_factor_sigma"),
                                     doc="float64 [ny,nx]: its standard error in %; NaN where a cell got no photon")
    daylight_reference_lx = property(lambda self: self._attr("daylight_reference_lx"),
                                     doc="E_h,ext (lx), the daylight's unobstructed horizontal illuminance")

    @property
    def is_daylight(self):
        """Whether the result holds daylight factors for this detector."""
        return self.daylight_factor is not None

    def daylight_figures(self, area=None):
        """The DF figures of the whole grid (``area`` None) or of a task area: a dict with
        mean, median and df_95 (each value, sigma, bias and the bias-corrected value, in %;
        docs/DAYLIGHT.md) and, with ``en17037``, its targets and verdicts. None for a
        detector without daylight factors."""
        return daylight_figures(self.attrs if area is None else self.task_areas[area].attrs)

    @property
    def u(self):
        """Unit vector of the columns: up x normal (as the detector was built)."""
        u = np.cross(self.up, self.normal)
        return u / np.linalg.norm(u)

    def cell_coordinates(self):
        """(u [nx], v [ny]) of the cell centres in m from the detector's centre (NaN for a
        points detector, which has no grid plane: see ``positions``)."""
        if self.is_points:
            return np.full(self.nx, np.nan), np.full(self.ny, np.nan)
        su, sv = self.size_m
        return (-su / 2 + (np.arange(self.nx) + 0.5) * su / self.nx,
                -sv / 2 + (np.arange(self.ny) + 0.5) * sv / self.ny)

    def cell_centres(self):
        """float64 [ny,nx,3]: world position of every cell's centre (m); a points
        detector's sensor positions."""
        if self.is_points:
            return np.asarray(self.positions, dtype=float).reshape(1, self.nx, 3)
        u, v = self.cell_coordinates()
        return (self.center + u[None, :, None] * self.u + v[:, None, None] * self.up)

    def band_sum(self):
        """(value [ny,nx], sigma_rel [ny,nx]) of the band sum.

        A photon carries one band, so counts and sums of squares add over bands and
        eq. (8) holds for the sum as for one band; sobol results use the replicate counts
        summed over bands instead. With one band these are the stored arrays.
        """
        if self.bands == 1:
            return self.value[:, :, 0], self.sigma_rel[:, :, 0]
        value = self.value.sum(axis=2)
        if self.replicate_count is not None and self.replicate_photons is not None:
            rel = statistics.replicate_sigma_rel(self.replicate_count.sum(axis=3), self.replicate_photons)
            rel = np.where(self.count.sum(axis=2) > 0, rel, np.nan)
        else:
            rel = statistics.cell_sigma_rel(self.count.sum(axis=2), self.sumsq.sum(axis=2), self.photons)
        return value, rel

    def sensor_table(self):
        """Points detectors: a ``luxtrace.SensorTable`` (positions [n,3] m, E_lx [n],
        sigma_E_lx [n], bands summed), the numbers of the table ``luxtrace run`` writes beside
        the result; ValueError for other detectors."""
        return sensor_table.sensor_table(self)

    def to_csv(self, path, band_names=None):
        """Write one row per cell: i, j, the cell centre (u, v from the detector's centre and
        x, y, z in the scene), then per band the value, its relative and absolute errors and
        the counts n_c, q_c; with several bands also the band sum. Units are in the header.
        Returns the path."""
        names = list(band_names) if band_names else [f"band{b}" for b in range(self.bands)]
        u, v = self.cell_coordinates()
        xyz = self.cell_centres()
        unit = self.units
        header = ["i", "j", "u_m", "v_m", "x_m", "y_m", "z_m"]
        cols = []
        for b, name in enumerate(names):
            header += [f"value_{name} [{unit}]", f"sigma_rel_{name}", f"sigma_{name} [{unit}]",
                       f"count_{name}", f"sumsq_{name}"]
            cols.append((self.value[:, :, b], self.sigma_rel[:, :, b], self.sigma[:, :, b],
                         self.count[:, :, b], self.sumsq[:, :, b]))
        if self.bands > 1:
            sv, sr = self.band_sum()
            header += [f"value_sum [{unit}]", "sigma_rel_sum", f"sigma_sum [{unit}]"]
        with builtins.open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            for j in range(self.ny):
                for i in range(self.nx):
                    row = [i, j, repr(float(u[i])), repr(float(v[j]))] + [repr(float(c)) for c in xyz[j, i]]
                    for val, rel, sig, n, q in cols:
                        row += [repr(float(val[j, i])), repr(float(rel[j, i])), repr(float(sig[j, i])),
                                int(n[j, i]), int(q[j, i])]
                    if self.bands > 1:
                        row += [repr(float(sv[j, i])), repr(float(sr[j, i])), repr(float(sv[j, i] * sr[j, i]))]
                    w.writerow(row)
        return path


def daylight_figures(attrs):
    """The DF figures stored as attributes (``DF_*``, ``en17037_*``) of a detector, task area
    or light scene detector group, as a dict; None where there are none."""
    if "DF_median_pct" not in attrs:
        return None
    out = {"cells_without_photons": int(attrs["DF_cells_without_photons"]),
           "mean": float(attrs["DF_mean_pct"]), "mean_sigma": float(attrs["DF_mean_sigma_pct"])}
    for key, prefix in (("median", "DF_median"), ("df_95", "DF_95")):
        value, sigma, bias = (float(attrs[f"{prefix}{s}_pct"]) for s in ("", "_sigma", "_bias"))
        out[key] = {"value": value, "sigma": sigma, "bias": bias, "corrected": value - bias}
    if "en17037_verdict" in attrs:
        out["en17037"] = {
            "target_df": float(attrs["en17037_target_df_pct"]),
            "minimum_df": float(attrs["en17037_minimum_df_pct"]),
            "target_verdict": str(attrs["en17037_target_verdict"]),
            "target_photons_factor": float(attrs["en17037_target_photons_factor"]),
            "minimum_verdict": str(attrs["en17037_minimum_verdict"]),
            "minimum_photons_factor": float(attrs["en17037_minimum_photons_factor"]),
            "verdict": str(attrs["en17037_verdict"]),
            "photons_factor": float(attrs["en17037_photons_factor"]),
        }
    return out


class TargetHistory:
    """One target's history: its ``label`` and ``goal``, and per reduction its ``value``
    (the error or count the goal is for), ``forecast_s`` (forecast time to the goal) and
    ``forecast_photons`` (forecast photons to it), arrays [rows]; a column the file lacks
    is None."""

    def __init__(self, label, goal, value, forecast_s, forecast_photons):
        self.label = label
        self.goal = goal
        self.value = value
        self.forecast_s = forecast_s
        self.forecast_photons = forecast_photons

    def __repr__(self):
        return f"<TargetHistory {self.label}: goal {self.goal:g}, {0 if self.value is None else len(self.value)} rows>"


class History:
    """The convergence history (``/history``): one row per reduction.

    time_s, photons, sigma_rel_global, forecast_s [rows]; with targets also
    target_value, target_forecast_s, target_forecast_photons [rows, targets] and
    target_labels, target_goals; one target's columns: :meth:`target`. Absent datasets
    are None.
    """

    def __init__(self, datasets, attrs):
        self.datasets = dict(datasets)
        self.attrs = dict(attrs)

    def __getattr__(self, name):
        if name in ("datasets", "attrs"):
            raise AttributeError(name)
        if name in self.datasets:
            return self.datasets[name]
        if name in ("time_s", "photons", "sigma_rel_global", "forecast_s", "target_value", "target_forecast_s",
                    "target_forecast_photons"):
            return None
        raise AttributeError(name)

    @property
    def target_labels(self):
        return list(self.attrs.get("target_labels", []))

    @property
    def target_goals(self):
        return list(np.atleast_1d(self.attrs.get("target_goals", [])))

    def target(self, key=0):
        """The columns of one ``[[run.target]]`` as a :class:`TargetHistory`: ``key`` is its
        index in ``target_labels`` or its label. KeyError naming the targets otherwise."""
        labels = self.target_labels
        k = labels.index(key) if isinstance(key, str) and key in labels else key
        if not isinstance(k, (int, np.integer)) or not 0 <= k < len(labels):
            raise KeyError(f"no target {key!r} in the history (targets: {', '.join(labels) or 'none'})")

        def column(name):
            a = self.datasets.get(name)
            return None if a is None else a[:, k]
        return TargetHistory(labels[k], float(self.target_goals[k]), column("target_value"),
                             column("target_forecast_s"), column("target_forecast_photons"))

    def __len__(self):
        t = self.datasets.get("time_s")
        return 0 if t is None else len(t)


class Result(AttrAccess):
    """A luxtrace result or checkpoint, read whole (see :func:`open`), or several combined
    (see :func:`luxtrace.combine`).

    ``attrs``: every root attribute; ``mesh``: :class:`Mesh`; ``surface``:
    :class:`SurfaceMap`; ``detectors`` and ``observers``: dicts of :class:`Detector` and
    :class:`Group` by name; ``history``: :class:`History` (None for a combination).
    """

    def __init__(self, attrs, mesh, surface, detectors, observers=None, history=None, path=None, notes=()):
        self.attrs = dict(attrs)
        self.mesh = mesh
        self.surface = surface
        self.detectors = dict(detectors)
        self.observers = dict(observers or {})
        self.history = history
        self.path = path
        self.notes = list(notes)  #: what a combination left out, and why
        #: ``/light_groups``' raw counts by group name, in index order (see _read_tallies);
        #: empty for a run with one light group, and for a combination
        self.light_group_tallies = {}

    def __repr__(self):
        return (f"<Result {self.path or 'combined'}: {self.photons} photons, format {self.format_version}, "
                f"detectors {sorted(self.detectors)}>")

    def _attr(self, name, default=None):
        return self.attrs.get(name, default)

    format = property(lambda self: self._attr("format"), doc='"luxtrace-result" or "luxtrace-checkpoint"')
    format_version = property(lambda self: int(self._attr("format_version", 1)))
    is_checkpoint = property(lambda self: self.format == "luxtrace-checkpoint")
    luxtrace_version = property(lambda self: self._attr("luxtrace_version"))
    scene_file = property(lambda self: self._attr("scene_file"))
    scene_name = property(lambda self: self._attr("scene_name"))
    seed = property(lambda self: self._attr("seed"), doc="the run's seed (of a combination: the first)")
    seeds = property(lambda self: tuple(self._attr("seeds", (self._attr("seed"),))),
                     doc="all seeds: one for a run, one per run for a combination")
    photons = property(lambda self: int(self._attr("photons", 0)), doc="photons emitted, N")
    flux_per_photon_lm = property(lambda self: self._attr("flux_per_photon_lm"), doc="E0 = total_flux_lm / N")
    total_flux_lm = property(lambda self: self._attr("total_flux_lm"), doc="initial flux of all lights")
    maintenance_factor = property(lambda self: self._attr("maintenance_factor", 1.0))
    elapsed_s = property(lambda self: self._attr("elapsed_s"))
    stop_reason = property(lambda self: self._attr("stop_reason"))
    bands = property(lambda self: list(self._attr("bands", ["Y"])))
    sampler = property(lambda self: self._attr("sampler", "random"))
    replicates = property(lambda self: int(self._attr("replicates", 0)), doc="R of sobol, 0 for random")
    ranks = property(lambda self: self._attr("ranks"))
    threads_per_rank = property(lambda self: self._attr("threads_per_rank"))

    @property
    def light_groups(self):
        """The light groups' names in index order (the order of /light_scenes' ``weights``);
        empty when the run had one light group."""
        return list(self.light_group_tallies)

    def light_scene(self, weights):
        """The result with light group g at weight ``weights[g]`` (groups not named are off),
        recombined from each group's own counts with exact errors: a
        :class:`luxtrace.light_scenes.LightScene` with ``surface`` and ``detectors``.
        KeyError for an unknown group, ValueError for a negative weight or a file without
        light groups."""
        from .light_scenes import LightScene
        return LightScene(self, dict(weights))

    # ``daylight``: the /daylight group (site, time, each sun and sky light's model, sun
    # position and unobstructed horizontal illuminance) as a :class:`Group`, or None for a
    # run without sun or sky; set by :func:`open`.
    daylight = None

    # ``annual``: the /annual group (annual daylight: the year's hours, each sensor grid's
    # hourly illuminance and metrics with their errors) as a :class:`luxtrace.annual.Annual`,
    # or None for a run without ``[annual]`` (and for a combination); set by :func:`open`.
    annual = None

    def scene_detector(self, scene, name):
        """Detector NAME as the run's ``[[light_scene]]`` SCENE left it in the file
        (/light_scenes/SCENE/detectors/NAME): its values and errors under that scene's
        weights and, for a ``daylight_factor`` detector, its daylight factors and EN 17037
        figures, with the detector's own geometry. KeyError naming what the file has
        otherwise."""
        base = self.detector(name)
        if not self.path:
            raise KeyError("the combined result has no stored light scenes")
        with h5py.File(self.path, "r") as f:
            scenes = f["light_scenes"] if "light_scenes" in f else {}
            if scene not in scenes:
                known = ", ".join(sorted(scenes)) or "none"
                raise KeyError(f"{self.path}: no light scene '{scene}' (the file has: {known})")
            dets = scenes[scene]["detectors"] if "detectors" in scenes[scene] else {}
            if name not in dets:
                raise KeyError(f"{self.path}: light scene '{scene}' has no detector '{name}'")
            grp = dets[name]
            areas = grp["task_areas"].items() if "task_areas" in grp else ()
            return Detector(name, _read_datasets(grp), {**base.attrs, **attributes(grp)}, self.photons,
                            task_areas={a: Group(a, attributes(t), _read_datasets(t)) for a, t in areas})

    def detector(self, name):
        """The detector NAME; KeyError naming the detectors there are otherwise."""
        try:
            return self.detectors[name]
        except KeyError:
            known = ", ".join(sorted(self.detectors)) or "none"
            where = self.path or "the combined result"
            raise KeyError(f"{where}: no detector '{name}' (the file has: {known})") from None

    def summary(self):
        """A few lines like ``luxtrace info``'s: photons, the global map, each detector."""
        s = self.surface
        lines = [f"{self.path or 'combined result'}: format {self.format_version}, sampler {self.sampler}, "
                 f"seed(s) {', '.join(str(x) for x in self.seeds)}",
                 f"photons {self.photons}, flux {self.total_flux_lm:g} lm",
                 f"global map: mean {s.mean_arithmetic_lx:.4g} lx, RMS error {s.odd_even_sigma_lx:.4g} lx "
                 f"({100 * s.sigma_rel_arithmetic:.3g} % arithmetic)"]
        for d in self.detectors.values():
            lines.append(f"detector {d.name}: {d.type}, mean {d.mean_value:.5g} {d.units} "
                         f"+- {100 * d.mean_sigma_rel:.3g} %, per-cell error {100 * d.sigma_rel_arithmetic:.3g} % "
                         f"(eq. 9)")
        return "\n".join(lines)


def _read_datasets(group, skip=()):
    return {k: v[()] for k, v in group.items() if isinstance(v, h5py.Dataset) and k not in skip}


def _read_tallies(f, version):
    """The integer tallies of an open file: ``(surface, detectors, light_groups)``, the surface map's
    :attr:`SurfaceMap.TALLIES` (format 1's [T,B] as [T,2,B]) and, by detector name, each
    grid's :attr:`Detector.TALLIES`, and each light group's own (see
    :func:`_read_light_group_tallies`). The one place the raw counts are read: every value and
    error is computed from them, so a layout that splits them further (a light group or
    replicate dimension) is taken apart here."""
    g = f["global"]
    surface = {k: g[k][()] for k in SurfaceMap.TALLIES if k in g}
    if version == 1:
        surface = {k: _with_sides(a) for k, a in surface.items()}
    detectors = {name: {k: grp[k][()] for k in Detector.TALLIES if k in grp}
                 for name, grp in (f["detectors"].items() if "detectors" in f else ())}
    return surface, detectors, _read_light_group_tallies(f)


def _read_light_group_tallies(f):
    """``/light_groups/NAME`` (issue 22): by group name, its ``index``, ``flux_lm``, ``lights``,
    ``surface`` (the map's TALLIES and ``replicate_count``, or None when the run kept one map
    for all groups) and ``detectors`` (name -> count, sumsq, replicate_count and the totals
    ``photons_received``, ``total_count``, ``total_sumsq``, ``replicate_total``)."""
    if "light_groups" not in f:
        return {}
    out = {}
    for name, grp in f["light_groups"].items():
        surface = {k: grp[k][()] for k in SurfaceMap.TALLIES + ("replicate_count",) if k in grp}
        dets = {}
        for dname, d in (grp["detectors"].items() if "detectors" in grp else ()):
            dets[dname] = {k: d[k][()] for k in Detector.TALLIES if k in d}
            dets[dname].update({k: plain(d.attrs[k]) for k in
                                ("photons_received", "total_count", "total_sumsq", "replicate_total") if k in d.attrs})
        out[name] = {"index": int(grp.attrs["index"]), "flux_lm": float(grp.attrs["flux_lm"]),
                     "lights": int(grp.attrs.get("lights", 0)), "detectors": dets,
                     "surface": surface if "count_odd" in surface else None}
    return dict(sorted(out.items(), key=lambda kv: kv[1]["index"]))


def _with_sides(a):
    """A format-1 [T,B] map as format 2's [T,2,B]: the data on the front, zeros behind."""
    out = np.zeros((a.shape[0], 2) + a.shape[1:], dtype=a.dtype)
    out[:, FRONT] = a
    return out


def open(path, check=True):  # noqa: A001  (luxtrace.open, like h5py.File / openmc.StatePoint)
    """Read a result or checkpoint file of any format_version luxtrace writes (1 or 2).

    With ``check`` the file's seal is verified first, as ``luxtrace info`` does. Raises
    ResultError for a damaged file, a file that is not a luxtrace result, or a format
    newer than this package; FileNotFoundError when there is no such file.
    """
    path = os.fspath(path)
    if check:
        check_seal(path)
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise ResultError(f"{path}: not an HDF5 file ({e})") from None
    try:
        with f:
            res = _read(f, path)
    except ResultError:
        raise
    except (OSError, RuntimeError, KeyError, ValueError, TypeError, IndexError) as e:
        # HDF5's checksums, missing datasets, attributes of the wrong kind: a file that
        # was changed after luxtrace wrote it (unsealed files of 0.1 are not checked first).
        raise ResultError(f"{path}: damaged result: {e}") from None
    _validate(res, path)
    return res


def _read(f, path):
    """The groups of an open file as a Result (shapes not yet checked)."""
    attrs = attributes(f)
    if attrs.get("format") not in ("luxtrace-result", "luxtrace-checkpoint"):
        raise ResultError(f"{path}: not a luxtrace result (root attribute format = {attrs.get('format')!r})")
    version = int(attrs.get("format_version", 1))
    if not 1 <= version <= NEWEST_FORMAT_VERSION:
        raise ResultError(f"{path}: format_version {version}; this package reads 1 to {NEWEST_FORMAT_VERSION}")
    if attrs.get("format") == "luxtrace-checkpoint" and "checkpoint" in f and "mesh" not in f and "global" not in f:
        # A tally checkpoint: what a run keeps when its write failed (docs/RELIABILITY.md §8).
        raise ResultError(f"{path}: a tally checkpoint (the run's tallies alone, no maps or estimates): write the "
                          f"result from it with: luxtrace run SCENE --restart {path}")
    for g in ("mesh", "global"):
        if g not in f:
            raise ResultError(f"{path}: damaged result: no /{g} group")
    m = f["mesh"]
    names = m.attrs.get("material_names", m["material_names"][()] if "material_names" in m else [])
    mesh = Mesh(m["vertices"][()], m["triangles"][()], m["area"][()], m["material"][()], plain(np.asarray(names)))
    surface_tallies, detector_tallies, group_tallies = _read_tallies(f, version)
    g = _read_datasets(f["global"], skip=SurfaceMap.TALLIES)
    if version == 1:
        for k in ("illuminance", "illuminance_direct", "odd_even_difference_lx"):
            g[k] = _with_sides(g[k])
        g["sigma_lx"] = np.full((mesh.triangle_count, 2), np.nan)
    surface = SurfaceMap({**surface_tallies, **g}, attributes(f["global"]), mesh.area_m2, version)
    photons = int(attrs.get("photons", 0))
    rep_photons = attrs.get("replicate_photons")
    detectors = {}
    for name, tallies in detector_tallies.items():
        grp = f["detectors"][name]
        areas = grp["task_areas"].items() if "task_areas" in grp else ()
        detectors[name] = Detector(name, {**tallies, **_read_datasets(grp, skip=Detector.TALLIES)}, attributes(grp),
                                   photons, None if rep_photons is None else np.atleast_1d(rep_photons),
                                   {a: Group(a, attributes(t), _read_datasets(t)) for a, t in areas})
    observers = {}
    if "observers" in f:
        for name, grp in f["observers"].items():
            observers[name] = Group(name, attributes(grp), _read_datasets(grp))
    history = History(_read_datasets(f["history"]), attributes(f["history"])) if "history" in f else None
    res = Result(attrs, mesh, surface, detectors, observers, history, path=path)
    res.light_group_tallies = group_tallies
    res.daylight = Group("daylight", attributes(f["daylight"]), _read_datasets(f["daylight"])) if "daylight" in f else None
    res.annual = read_annual(f, path)
    return res


def _validate(r, path):
    """Shapes that agree with each other, so that no later computation misreads a damaged
    file: the mesh's arrays, the maps [T,2,B] and each detector's [ny,nx,B]."""
    def bad(what):
        raise ResultError(f"{path}: damaged result: {what}")
    m = r.mesh
    T, B = m.triangle_count, len(r.bands)
    if m.triangles.shape != (T, 3) or m.material.shape != (T,) or m.vertices.ndim != 2 or m.vertices.shape[1] != 3:
        bad("the /mesh arrays do not agree in size")
    if T and (m.triangles.min() < 0 or m.triangles.max() >= len(m.vertices)):
        bad("/mesh/triangles names vertices that do not exist")
    known = SurfaceMap.TALLIES + ("illuminance", "illuminance_direct", "sigma_lx", "odd_even_difference_lx")
    for k in known:  # datasets a newer luxtrace adds are passed on unchecked
        if k not in r.surface.datasets:
            if k == "sumsq" and r.format_version == 1:
                continue
            bad(f"no /global/{k}")
        v = r.surface.datasets[k]
        want = (T, 2) if k in ("sigma_lx", "odd_even_difference_lx") else (T, 2, B)
        if np.shape(v) != want:
            bad(f"/global/{k} has shape {np.shape(v)}, expected {want} ({T} triangles, {B} bands)")
    for name, d in r.detectors.items():
        cells, size = np.atleast_1d(d.attrs.get("cells", [])), np.atleast_1d(d.attrs.get("size", [1, 1]))
        if d.is_points:  # sensors instead of a grid plane: positions and directions [nx, 3]
            size = np.ones(2)
        if (cells.shape != (2,) or size.shape != (2,) or not np.all(np.isfinite(size)) or not np.all(size > 0)
                or not np.all(cells >= 1) or not np.all(cells == np.floor(cells))):
            bad(f"/detectors/{name}: attributes cells or size are not two positive numbers")
        want = (d.ny, d.nx, B)
        for k in ("count", "sumsq", "value", "sigma_rel"):
            if np.shape(d.datasets.get(k)) != want:
                bad(f"/detectors/{name}/{k} has shape {np.shape(d.datasets.get(k))}, expected {want}")
        if d.is_points:
            for k in ("positions", "directions"):
                if np.shape(d.datasets.get(k)) != (d.nx, 3) or d.ny != 1:
                    bad(f"/detectors/{name}/{k} has shape {np.shape(d.datasets.get(k))}, expected ({d.nx}, 3)")
            continue
        if np.shape(d.attrs.get("size")) != (2,):
            bad(f"/detectors/{name}: attributes cells or size are not two positive numbers")
        for k in ("normal", "up", "center"):
            if np.shape(d.attrs.get(k)) != (3,):
                bad(f"/detectors/{name}: attribute {k} is not a 3-vector")
