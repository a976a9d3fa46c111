"""Combining runs of one scene made with different seeds into one result.

Runs with different seeds trace independent photons, so their integer counts add up to
those of one run with all the photons (SPEC §3): the combination sums every count and
recomputes every estimate from the sums, with E0 = total_flux_lm / N_total. Nothing is
averaged that cannot be averaged exactly.
"""
import numpy as np

from . import statistics
from .result import FRONT, Detector, Result, SurfaceMap

# Attributes that describe what was simulated: they must agree for runs to be combined.
_ROOT_SAME = ("format_version", "total_flux_lm", "maintenance_factor", "sampler")
_DETECTOR_SAME = ("type", "units", "center", "normal", "up", "size", "cells", "view_direction", "half_angle_deg",
                  "error_estimator", "radius_m")
# A points detector's sensors: the same in every run, kept as they are.
_DETECTOR_SAME_DATASETS = ("positions", "directions")
# Root attributes of one run only (a combination has no single value of them).
_ROOT_PER_RUN = ("seed", "ranks", "threads_per_rank", "reductions", "reduction_stall_s", "reduction_wait_s",
                 "stop_reason", "elapsed_s", "photons", "flux_per_photon_lm", "replicates", "replicate_photons")
# Detector attributes recomputed from the summed counts.
_DETECTOR_RECOMPUTED = ("sigma_rel_arithmetic", "sigma_rel_quadratic", "mean_arithmetic", "mean_quadratic",
                        "mean_value", "mean_sigma_rel", "photons_received", "error_dof", "replicate_total")


class MismatchError(ValueError):
    """Results that are not runs of the same scene and settings, or not independent."""


def _same(a, b):
    if a is None or b is None:
        return a is None and b is None
    if isinstance(a, float) or isinstance(b, float):
        return a == b or (np.isfinite(a) and np.isfinite(b) and abs(a - b) <= 1e-12 * max(abs(a), abs(b)))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype.kind == "f" or b.dtype.kind == "f":
            return a.shape == b.shape and np.allclose(a, b, rtol=1e-12, atol=0.0)
        return a.shape == b.shape and np.array_equal(a, b)
    return a == b


def _name(r):
    return r.path or "a combined result"


def _check(rs):
    first = rs[0]
    for r in rs[1:]:
        for key in _ROOT_SAME:
            if not _same(first.attrs.get(key), r.attrs.get(key)):
                raise MismatchError(f"{_name(r)}: {key} = {r.attrs.get(key)!r}, but {_name(first)} has "
                                    f"{first.attrs.get(key)!r}: not runs of the same scene and settings")
        if first.bands != r.bands:
            raise MismatchError(f"{_name(r)}: bands {r.bands}, but {_name(first)} has {first.bands}")
        if not first.mesh.same_as(r.mesh):
            raise MismatchError(f"{_name(r)}: its mesh (vertices, triangles or materials) differs from "
                                f"{_name(first)}'s: not the same scene")
        if sorted(first.detectors) != sorted(r.detectors):
            raise MismatchError(f"{_name(r)}: detectors {sorted(r.detectors)}, but {_name(first)} has "
                                f"{sorted(first.detectors)}")
        for name, d in r.detectors.items():
            d0 = first.detectors[name]
            for key in _DETECTOR_SAME:
                if not _same(d0.attrs.get(key), d.attrs.get(key)):
                    raise MismatchError(f"{_name(r)}: detector '{name}' has {key} = {d.attrs.get(key)!r}, but "
                                        f"{_name(first)} has {d0.attrs.get(key)!r}")
            if d.count.shape != d0.count.shape:
                raise MismatchError(f"{_name(r)}: detector '{name}' has counts of shape {d.count.shape}, "
                                    f"{_name(first)} {d0.count.shape}")
    seen = {}
    for r in rs:
        for s in r.seeds:
            if s in seen:
                raise MismatchError(f"{_name(r)} and {seen[s]} both hold seed {s}: the same photons twice are not "
                                    "independent runs (use another seed for each run)")
            seen[s] = _name(r)
    if any(r.photons <= 0 for r in rs):
        raise MismatchError(f"{_name(next(r for r in rs if r.photons <= 0))}: no photons")


def _combine_surface(rs, e0, photons, notes):
    first = rs[0]
    area = first.mesh.area_m2
    version = first.format_version
    ds = {k: sum(r.surface.datasets[k] for r in rs) for k in SurfaceMap.TALLIES if k in first.surface.datasets}
    odd, even = ds["count_odd"], ds["count_even"]
    per_area = (e0 / area)[:, None, None]
    ds["illuminance"] = (odd + even).astype(float) * per_area
    ds["illuminance_direct"] = (ds["direct_odd"] + ds["direct_even"]).astype(float) * per_area
    ds["odd_even_difference_lx"] = 2.0 * (odd.astype(float) - even.astype(float)).sum(axis=2) * (e0 / area)[:, None]
    attrs = {}
    band_odd, band_even = odd.sum(axis=2), even.sum(axis=2)
    if version >= 2:
        ds["sigma_lx"] = statistics.side_sigma_lx(band_odd + band_even, ds["sumsq"].sum(axis=2), area, e0, photons)
        attrs.update(statistics.global_estimate(band_odd, band_even, area, e0, ds["sigma_lx"], lit_sides_only=True))
        attrs["error_estimator"] = first.surface.attrs.get("error_estimator", "second_moment")
    else:
        ds["sigma_lx"] = np.full(band_odd.shape, np.nan)
        est = statistics.global_estimate(band_odd[:, FRONT:FRONT + 1], band_even[:, FRONT:FRONT + 1], area, e0)
        est.pop("lit_area_m2")  # format 1 has no such attributes: its sums run over every triangle
        est.pop("lit_sides")
        attrs.update(est)
    for k in ("photons_escaped", "photons_absorbed", "photons_truncated"):
        attrs[k] = sum(int(r.surface.attrs.get(k, 0)) for r in rs)
    left = sorted(set(first.surface.attrs) - set(attrs))
    if left:
        notes.append(f"/global attributes not combined (no rule for them): {', '.join(left)}")
    return SurfaceMap(ds, attrs, area, version)


def _grid_total_q(d):
    """The grid's q (sum over photons of the registrations on the whole grid, squared),
    which the file holds only through mean_sigma_rel = sqrt(q / n^2 - 1/N) (eq. 8 for the
    grid as one cell): q = n^2 (mean_sigma_rel^2 + 1/N), rounded to the integer it is."""
    n = float(d.count.sum())
    if n == 0:
        return 0.0
    s = float(d.mean_sigma_rel)
    return float(np.rint(n * n * (s * s + 1.0 / d.photons)))


def _combine_detector(name, rs, photons, rep_photons, notes):
    ds0 = [r.detectors[name] for r in rs]
    d0 = ds0[0]
    data = {"count": sum(d.count for d in ds0), "sumsq": sum(d.sumsq for d in ds0)}
    # A cell's value is E0 n_c times a factor of the cell's geometry, with E0 = F / N:
    # the photon-weighted mean of the runs' values is the value of the summed counts.
    data["value"] = sum(d.photons * d.value for d in ds0) / photons
    sobol = rep_photons is not None
    if sobol:
        data["replicate_count"] = np.concatenate([d.replicate_count for d in ds0], axis=0)
        rel = statistics.replicate_sigma_rel(data["replicate_count"], rep_photons)
        data["sigma_rel"] = np.where(data["count"] > 0, rel, np.nan)
    else:
        data["sigma_rel"] = statistics.cell_sigma_rel(data["count"], data["sumsq"], photons)
    for k in _DETECTOR_SAME_DATASETS:
        if k in d0.datasets:
            for r, d in zip(rs[1:], ds0[1:]):
                if k not in d.datasets or not np.array_equal(d.datasets[k], d0.datasets[k]):
                    raise MismatchError(f"{_name(r)}: detector '{name}' has other sensor {k} than {_name(rs[0])}")
            data[k] = d0.datasets[k]
    attrs = {k: v for k, v in d0.attrs.items() if k not in _DETECTOR_RECOMPUTED}
    dropped = [k for k in list(attrs) if k not in _DETECTOR_SAME
               and not all(_same(attrs[k], d.attrs.get(k)) for d in ds0[1:])]
    for k in dropped:
        del attrs[k]
    if dropped:
        notes.append(f"detector '{name}': attributes that differ between the runs and have no combination rule "
                     f"were left out: {', '.join(sorted(dropped))}")
    areas = sorted({a for d in ds0 for a in d.task_areas})
    if areas:
        notes.append(f"detector '{name}': task areas left out (their metrics have no combination rule here): "
                     f"{', '.join(areas)}")
    out = Detector(name, data, attrs, photons, rep_photons)
    value, rel = out.band_sum()
    g = statistics.grid_summary(value, rel)
    attrs.update(sigma_rel_arithmetic=g["sigma_rel_arithmetic"], sigma_rel_quadratic=g["sigma_rel_quadratic"],
                 mean_arithmetic=g["mean_arithmetic"], mean_quadratic=g["mean_quadratic"],
                 mean_value=g["mean_arithmetic"], photons_received=sum(int(d.photons_received) for d in ds0))
    if sobol:
        total = np.concatenate([np.atleast_1d(d.attrs["replicate_total"]) for d in ds0]).astype(np.uint64)
        attrs["replicate_total"] = total
        attrs["mean_sigma_rel"] = float(statistics.replicate_sigma_rel(total, rep_photons))
        attrs["error_dof"] = len(rep_photons) - 1
    else:
        n = float(data["count"].sum())
        attrs["mean_sigma_rel"] = float(statistics.cell_sigma_rel(n, sum(_grid_total_q(d) for d in ds0), photons))
        attrs["error_dof"] = 0
    out.attrs = attrs
    return out


def combine(results):
    """One result from runs of the same scene with different seeds.

    Counts (surface maps, second moments, detector n_c and q_c, photon fates, photons)
    are summed; E0 = total_flux_lm / N_total; values, per-cell and per-side errors
    (eq. 8, the second moment), the global odd/even error (eq. 5) and the detector
    summaries (eq. 9, the grid mean's error) are recomputed from the sums.

    sobol results are combined through their replicates: a run with R randomisations and
    another with R' give R + R' independent replicates, and errors come from their spread
    (R + R' - 1 degrees of freedom).

    Raises MismatchError when the runs differ in mesh, bands, detectors, flux, sampler or
    format, or share a seed. Observers (UGR), task areas and attributes without a
    combination rule are left out; ``Result.notes`` lists them. The result has no history.
    """
    rs = list(results)
    if not rs:
        raise ValueError("combine: no results given")
    _check(rs)
    first = rs[0]
    photons = sum(r.photons for r in rs)
    e0 = float(first.total_flux_lm) / photons
    notes = []
    sobol = first.replicates > 0
    rep_photons = None
    if sobol:
        rep_photons = np.concatenate([np.atleast_1d(r.attrs["replicate_photons"]) for r in rs]).astype(np.uint64)
    surface = _combine_surface(rs, e0, photons, notes)
    detectors = {name: _combine_detector(name, rs, photons, rep_photons, notes) for name in first.detectors}
    attrs = {k: v for k, v in first.attrs.items() if k not in _ROOT_PER_RUN}
    differ = [k for k in list(attrs) if not all(_same(attrs[k], r.attrs.get(k)) for r in rs[1:])]
    for k in differ:
        del attrs[k]
    if differ:
        notes.append(f"root attributes that differ between the runs were left out: {', '.join(sorted(differ))}")
    attrs.update(format="luxtrace-result", photons=photons, flux_per_photon_lm=e0,
                 seeds=[s for r in rs for s in r.seeds], seed=first.seed,
                 elapsed_s=sum(float(r.elapsed_s or 0.0) for r in rs), stop_reason="combined",
                 combined_from=[_name(r) for r in rs], replicates=0 if rep_photons is None else len(rep_photons))
    if sobol:
        attrs["replicate_photons"] = rep_photons
    if any(r.annual is not None for r in rs):
        notes.append("/annual left out (its hourly values and metrics have no combination rule here)")
    observers = sorted({name for r in rs for name in r.observers})
    if observers:
        notes.append(f"observers left out (their glare figures have no combination rule here): "
                     f"{', '.join(observers)}")
    return Result(attrs, first.mesh, surface, detectors, {}, None, path=None, notes=notes)
