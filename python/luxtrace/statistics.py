"""The estimates of docs/SPEC.md §3 on numpy arrays.

Equation numbers are those of Voloboy, Galaktionov, Ershov, Zhdanov et al., *Analysis of
global illumination calculation errors*. Every function takes counts (integers: exact to
add over runs of different seeds) and returns float64 arrays; nothing here reads files.
"""
import numpy as np


def cell_sigma_rel(n, q, photons):
    """Relative error of detector cells, eq. (8): sqrt(q / n^2 - 1 / N).

    n and q are the cells' sums of E_i and E_i^2 over the N photons (any shape); cells
    without hits (n = 0) get NaN, since no error can be estimated from nothing.
    """
    n = np.asarray(n, dtype=float)
    q = np.asarray(q, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.sqrt(np.maximum(0.0, q / (n * n) - 1.0 / float(photons)))
    return np.where(n > 0, rel, np.nan)


def replicate_sigma_rel(sums, photons):
    """Relative error of a photon-weighted mean from the spread of R replicates (sobol).

    sums: [R, ...] counts per replicate; photons: [R] photons per replicate. The mean is
    sum(sums) / sum(photons); its variance is estimated as R / (R - 1) sum_r w_r^2
    (m_r - m)^2 with w_r = N_r / N and m_r = sums_r / N_r (R - 1 degrees of freedom;
    docs/QMC.md). NaN where the mean is 0, with fewer than 2 replicates, or when a
    replicate has no photons.
    """
    sums = np.asarray(sums, dtype=float)
    p = np.asarray(photons, dtype=float).reshape((-1,) + (1,) * (sums.ndim - 1))
    R = sums.shape[0]
    if R < 2 or np.any(p <= 0):
        return np.full(sums.shape[1:], np.nan)
    n = p.sum()
    mean = sums.sum(axis=0) / n
    w = p / n
    s = (w * w * (sums / p - mean) ** 2).sum(axis=0)
    sigma = np.sqrt(s * R / (R - 1.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(mean > 0, sigma / mean, np.nan)


def grid_summary(value, sigma_rel):
    """Eq. (9) over a grid of cells (any shape, already summed over bands).

    Returns a dict: mean_arithmetic, mean_quadratic, sigma_abs = sqrt(mean of sigma_c^2)
    with sigma_c = sigma_rel_c * L_c (0 for cells without hits), and sigma_rel_arithmetic /
    sigma_rel_quadratic = sigma_abs divided by the two means (NaN for a dark grid).
    """
    v = np.asarray(value, dtype=float).ravel()
    r = np.asarray(sigma_rel, dtype=float).ravel()
    s = np.where(np.isfinite(r), r * v, 0.0)
    k = v.size
    mean_a = v.sum() / k
    mean_q = np.sqrt((v * v).sum() / k)
    sigma = np.sqrt((s * s).sum() / k)
    return {
        "mean_arithmetic": mean_a,
        "mean_quadratic": mean_q,
        "sigma_abs": sigma,
        "sigma_rel_arithmetic": sigma / mean_a if mean_a > 0 else np.nan,
        "sigma_rel_quadratic": sigma / mean_q if mean_q > 0 else np.nan,
    }


def side_sigma_lx(s, q, area_m2, e0, photons):
    """Standard error of a triangle side's illuminance from its second moment (format 2).

    s = count_odd + count_even and q = sumsq of each side, both summed over bands, shape
    [T, 2]; (E0 / A_t) sqrt(max(0, Q - S^2 / N)) in lux: the sample variance of the
    per-photon contributions, times N, gives the variance of their sum.
    """
    s = np.asarray(s, dtype=float)
    q = np.asarray(q, dtype=float)
    a = np.asarray(area_m2, dtype=float).reshape(-1, *([1] * (s.ndim - 1)))
    return (e0 / a) * np.sqrt(np.maximum(0.0, q - s * s / float(photons)))


def global_estimate(odd, even, area_m2, e0, sigma_lx=None, lit_sides_only=False):
    """The surface map's summaries: eqs. (4)-(5) and, with per-side sigmas, their moment form.

    odd, even: band-summed counts [T, S] (S = 1 or 2 sides); area_m2: [T]. The half-maps
    are E_odd = 2 n_odd E0 / A, E_even likewise, and D = sqrt(sum A (E_odd - E_even)^2 /
    sum A), the RMS error sigma = D / 2 (eq. 5), relative to the area-weighted arithmetic
    mean or to the quadratic mean (eq. 4). With lit_sides_only (format 2) the sums run
    over the sides with any arrival, otherwise over every element. With sigma_lx [T, S]
    (format 2's second moment) also moment_sigma_lx = sqrt(sum A sigma^2 / sum A) and its
    two relative forms. Returns a dict named like the /global attributes.
    """
    odd = np.asarray(odd, dtype=float)
    even = np.asarray(even, dtype=float)
    a = np.broadcast_to(np.asarray(area_m2, dtype=float).reshape(-1, *([1] * (odd.ndim - 1))), odd.shape)
    use = (odd + even) > 0 if lit_sides_only else np.ones(odd.shape, dtype=bool)
    a = np.where(use, a, 0.0)
    total = a.sum()
    out = {"lit_area_m2": total, "lit_sides": int(np.count_nonzero(use))}
    with np.errstate(divide="ignore", invalid="ignore"):
        e_odd = np.where(use, 2.0 * odd * e0 / np.where(a > 0, a, 1.0), 0.0)
        e_even = np.where(use, 2.0 * even * e0 / np.where(a > 0, a, 1.0), 0.0)
    e = 0.5 * (e_odd + e_even)
    nan = float("nan")
    if total <= 0:
        out.update(odd_even_rms_lx=0.0, sigma_lx=0.0, mean_arithmetic_lx=0.0, mean_quadratic_lx=0.0,
                   sigma_rel_arithmetic=nan, sigma_rel_quadratic=nan)
        if sigma_lx is not None:
            out.update(moment_sigma_lx=0.0, moment_sigma_rel_arithmetic=nan, moment_sigma_rel_quadratic=nan)
        return out
    d = np.sqrt((a * (e_odd - e_even) ** 2).sum() / total)
    mean_a = (a * e).sum() / total
    mean_q = np.sqrt((a * e * e).sum() / total)
    out.update(odd_even_rms_lx=d, sigma_lx=0.5 * d, mean_arithmetic_lx=mean_a, mean_quadratic_lx=mean_q,
               sigma_rel_arithmetic=0.5 * d / mean_a if mean_a > 0 else nan,
               sigma_rel_quadratic=0.5 * d / mean_q if mean_q > 0 else nan)
    if sigma_lx is not None:
        sig = np.where(use, np.nan_to_num(np.asarray(sigma_lx, dtype=float)), 0.0)
        m = np.sqrt((a * sig * sig).sum() / total)
        out.update(moment_sigma_lx=m,
                   moment_sigma_rel_arithmetic=m / mean_a if mean_a > 0 else nan,
                   moment_sigma_rel_quadratic=m / mean_q if mean_q > 0 else nan)
    return out
