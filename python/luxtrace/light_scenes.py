"""Light scenes recombined after the run (issue 22, docs/REFERENCE.md §4 /light_groups).

A result of a scene with more than one light group keeps each group's own integer tallies.
Photons of different groups are disjoint, so a combination with weights w_g is exact: a
detector cell's n = sum_g w_g n_g and q = sum_g w_g^2 q_g (eq. 8 then holds as for the plain
run), a triangle side's S = sum_g w_g (odd + even)_g and Q = sum_g w_g^2 sumsq_g, and the
odd and even half-maps of eq. (5) are weighted alike. The formulas are those of
src/stats/weighted_tallies.hpp and src/stats/estimates.cpp: the C++ /light_scenes/NAME
values agree to rounding.
"""
import numpy as np

from . import statistics


class LightSceneSurface:
    """The surface map of a combination: illuminance_lx, illuminance_direct_lx [T,2,B],
    odd_even_difference_lx and sigma_lx [T,2], and the /global summaries as attributes
    (mean_arithmetic_lx, odd_even_sigma_lx = D / 2 of eq. 5, moment_sigma_lx, ...)."""

    def __init__(self, tallies, weights, area_m2, e0, photons, replicate_photons=None):
        def weighted(key, square=False):
            return sum((w * w if square else w) * t[key].astype(float) for w, t in zip(weights, tallies))
        area = np.asarray(area_m2, dtype=float)[:, None, None]
        odd, even = weighted("count_odd"), weighted("count_even")
        self.illuminance_lx = (odd + even) * e0 / area
        self.illuminance_direct_lx = (weighted("direct_odd") + weighted("direct_even")) * e0 / area
        odd_b, even_b = odd.sum(axis=2), even.sum(axis=2)
        self.odd_even_difference_lx = 2.0 * (odd_b - even_b) * e0 / area[:, :, 0]
        self.sigma_lx = statistics.side_sigma_lx(odd_b + even_b, weighted("sumsq", True).sum(axis=2), area_m2, e0,
                                                 photons)
        g = statistics.global_estimate(odd_b, even_b, area_m2, e0, self.sigma_lx, lit_sides_only=True)
        self.summary = g  #: the /global attributes of the combination, by name
        self.mean_arithmetic_lx = g["mean_arithmetic_lx"]
        self.mean_quadratic_lx = g["mean_quadratic_lx"]
        self.odd_even_rms_lx = g["odd_even_rms_lx"]
        self.odd_even_sigma_lx = g["sigma_lx"]
        self.sigma_rel_arithmetic = g["sigma_rel_arithmetic"]
        self.moment_sigma_lx = g["moment_sigma_lx"]
        self.moment_sigma_rel_arithmetic = g["moment_sigma_rel_arithmetic"]
        self.lit_area_m2 = g["lit_area_m2"]
        #: sobol: each side's error from the spread of its weighted replicate maps
        #: (replicate_sigma_lx [T,2]) and the map's (replicate_sigma_lx_global, as the file's
        #: attribute replicate_sigma_lx); None for random runs.
        self.replicate_sigma_lx = self.replicate_sigma_lx_global = None
        if replicate_photons is not None and all("replicate_count" in t for t in tallies):
            reps = sum(w * t["replicate_count"].astype(float) for w, t in zip(weights, tallies)).sum(axis=2)
            rel = statistics.replicate_sigma_rel(np.moveaxis(reps, -1, 0), replicate_photons)
            e = (odd_b + even_b) * e0 / area[:, :, 0]
            self.replicate_sigma_lx = np.where(odd_b + even_b > 0, rel * e, 0.0)  # an unlit side: 0, as the file
            lit = odd_b + even_b > 0
            a = np.broadcast_to(area[:, :, 0], lit.shape)
            s = np.where(lit, np.nan_to_num(self.replicate_sigma_lx), 0.0)
            self.replicate_sigma_lx_global = float(np.sqrt((a * s * s)[lit].sum() / a[lit].sum()))


class LightSceneDetector:
    """One detector of a combination: count and sumsq (weighted n and q, float [ny,nx,B]),
    value, sigma_rel and sigma per cell, and the whole grid's mean_value with its
    mean_sigma_rel (from the weighted totals, as the file's mean)."""

    def __init__(self, name, tallies, weights, per_count, photons, replicate_photons=None):
        self.name = name
        self.count = sum(w * t["count"].astype(float) for w, t in zip(weights, tallies))
        self.sumsq = sum(w * w * t["sumsq"].astype(float) for w, t in zip(weights, tallies))
        self.value = self.count * per_count
        total_n = sum(w * float(t["total_count"]) for w, t in zip(weights, tallies))
        total_q = sum(w * w * float(t["total_sumsq"]) for w, t in zip(weights, tallies))
        cells = self.count.shape[0] * self.count.shape[1]
        self.mean_value = total_n * per_count / cells
        self.photons_received = sum(int(t["photons_received"]) for w, t in zip(weights, tallies) if w > 0)
        self._reps, self._rep_photons = None, replicate_photons
        if replicate_photons is not None and all("replicate_count" in t for t in tallies):
            # sobol: the spread of the weighted replicate counts (docs/QMC.md).
            reps = sum(w * t["replicate_count"].astype(float) for w, t in zip(weights, tallies))
            self._reps = reps
            rel = statistics.replicate_sigma_rel(reps, replicate_photons)
            self.sigma_rel = np.where(self.count > 0, rel, np.nan)
            totals = sum(w * np.asarray(t["replicate_total"], dtype=float) for w, t in zip(weights, tallies))
            self.mean_sigma_rel = float(statistics.replicate_sigma_rel(totals, replicate_photons))
        else:
            self.sigma_rel = statistics.cell_sigma_rel(self.count, self.sumsq, photons)
            self.mean_sigma_rel = float(statistics.cell_sigma_rel(total_n, total_q, photons))

    @property
    def sigma(self):
        """float [ny,nx,B]: absolute standard error per cell."""
        return self.value * self.sigma_rel

    # A daylight_factor detector of the run: E_h,ext of the combination (its daylight
    # sources at their groups' weights) and, when positive, the DF map [ny,nx] in % with
    # its standard error (band sums; a photon carries one band, so counts and sums of
    # squares add over bands). The quantiles and EN 17037 verdicts need the run's own
    # bootstrap: the declared [[light_scene]]s have them (Result.scene_detector).
    daylight_reference_lx = None
    daylight_factor = None
    daylight_factor_sigma = None

    def _set_daylight(self, reference_lx, photons):
        self.daylight_reference_lx = reference_lx
        if not reference_lx > 0:
            return
        value = self.value.sum(axis=2)
        if self._reps is not None:
            rel = statistics.replicate_sigma_rel(self._reps.sum(axis=3), self._rep_photons)
            rel = np.where(self.count.sum(axis=2) > 0, rel, np.nan)
        else:
            rel = statistics.cell_sigma_rel(self.count.sum(axis=2), self.sumsq.sum(axis=2), photons)
        self.daylight_factor = 100.0 * value / reference_lx
        self.daylight_factor_sigma = self.daylight_factor * rel

    def __repr__(self):
        return f"<LightSceneDetector {self.name}: mean {self.mean_value:.5g} +- {100 * self.mean_sigma_rel:.3g} %>"


class LightScene:
    """A combination of light groups (see :meth:`luxtrace.Result.light_scene`): ``weights``
    (group -> w), ``surface`` (:class:`LightSceneSurface`, None when the run kept one map
    for all groups) and ``detectors`` (name -> :class:`LightSceneDetector`)."""

    def __init__(self, result, weights):
        groups = result.light_group_tallies
        if not groups:
            raise ValueError(f"{result.path or 'the result'}: no light groups (a scene with one light group "
                             "keeps no /light_groups)")
        unknown = sorted(set(weights) - set(groups))
        if unknown:
            raise KeyError(f"no light group {', '.join(unknown)} (the file has: {', '.join(result.light_groups)})")
        for g, w in weights.items():
            if not np.isfinite(w) or w < 0:
                raise ValueError(f"light group {g}: weight {w} is not a finite number >= 0")
        names = result.light_groups
        self.weights = {g: float(weights.get(g, 0.0)) for g in names}
        w = [self.weights[g] for g in names]
        e0, photons = result.flux_per_photon_lm, result.photons
        rep_photons = result.attrs.get("replicate_photons")
        rep_photons = None if rep_photons is None else np.atleast_1d(rep_photons)
        surf = [groups[g]["surface"] for g in names]
        self.surface = None
        if all(s for s in surf):
            self.surface = LightSceneSurface(surf, w, result.mesh.area_m2, e0, photons, rep_photons)
        self.detectors = {}
        for name, d in result.detectors.items():
            if not all(name in groups[g]["detectors"] for g in names):
                continue
            n = d.count.astype(float)
            # value = n e0 value_per_lm: the factor of the plain grid, from a lit cell.
            lit = n > 0
            per_count = float(d.value[lit][0] / n[lit][0]) if lit.any() else 0.0
            self.detectors[name] = LightSceneDetector(name, [groups[g]["detectors"][name] for g in names], w,
                                                      per_count, photons, rep_photons)
            if d.is_daylight:
                self.detectors[name]._set_daylight(self.daylight_reference_lx(result, w), photons)

    @staticmethod
    def daylight_reference_lx(result, w):
        """E_h,ext of the combination with weights ``w`` (per light group, in index order):
        each daylight source's unobstructed horizontal illuminance at its group's weight
        (/daylight); 0 without daylight."""
        day = getattr(result, "daylight", None)
        if day is None or "light_group" not in day.datasets:
            return 0.0
        groups = np.asarray(day.datasets["light_group"], dtype=int)
        e = np.asarray(day.datasets["unobstructed_horizontal_lx"], dtype=float)
        return float(sum(w[g] * x for g, x in zip(groups, e) if g < len(w)))

    def __repr__(self):
        return f"<LightScene {self.weights}: detectors {sorted(self.detectors)}>"
