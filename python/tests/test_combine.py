"""Combining seeds: the counts of independent runs add, so a combination must equal one
run holding all their photons, and must refuse runs that are not of the same scene."""
import os

import numpy as np
import pytest

import luxtrace


def _attrs_close(got, want, keys):
    for k in keys:
        assert got[k] == pytest.approx(want[k], rel=1e-10, abs=1e-300), k


DETECTOR_STATS = ("mean_value", "mean_sigma_rel", "sigma_rel_arithmetic", "sigma_rel_quadratic", "mean_arithmetic",
                  "mean_quadratic", "photons_received")
GLOBAL_STATS = ("sigma_lx", "odd_even_rms_lx", "sigma_rel_arithmetic", "sigma_rel_quadratic", "mean_arithmetic_lx",
                "mean_quadratic_lx")


@pytest.mark.parametrize("sampler", ["random", "sobol"])
def test_one_run_combined_is_itself(room_runs, sampler):
    """The combination recomputes every estimate from counts: on one file it must give the
    binary's own numbers back (any format the binary writes)."""
    r = luxtrace.open(room_runs[sampler, 1])
    c = luxtrace.combine([r])
    _attrs_close(c.surface.attrs, r.surface.attrs, GLOBAL_STATS)
    if r.format_version >= 2:
        _attrs_close(c.surface.attrs, r.surface.attrs, ("moment_sigma_lx", "lit_area_m2"))
        np.testing.assert_allclose(c.surface.sigma_lx, r.surface.sigma_lx, rtol=1e-10)
    for name, d in r.detectors.items():
        cd = c.detectors[name]
        np.testing.assert_allclose(cd.value, d.value, rtol=1e-12)
        np.testing.assert_allclose(cd.sigma_rel, d.sigma_rel, rtol=1e-10)
        _attrs_close(cd.attrs, d.attrs, DETECTOR_STATS)
        assert cd.error_dof == d.error_dof and cd.error_estimator == d.error_estimator


def test_two_format2_runs_equal_one_run_of_all_their_photons(v2_pair):
    a, b, both = (luxtrace.open(p) for p in v2_pair)
    c = luxtrace.combine([a, b])
    assert c.photons == both.photons == 8000 and c.seeds == (11, 12)
    for k in ("count_odd", "count_even", "direct_odd", "direct_even", "sumsq"):
        assert np.array_equal(c.surface.datasets[k], both.surface.datasets[k]), k
    np.testing.assert_allclose(c.surface.illuminance_lx, both.surface.illuminance_lx, rtol=1e-12)
    np.testing.assert_allclose(c.surface.sigma_lx, both.surface.sigma_lx, rtol=1e-9)
    np.testing.assert_allclose(c.surface.odd_even_difference_lx, both.surface.odd_even_difference_lx, rtol=1e-12)
    _attrs_close(c.surface.attrs, both.surface.attrs,
                 GLOBAL_STATS + ("moment_sigma_lx", "moment_sigma_rel_arithmetic", "lit_area_m2", "photons_absorbed"))
    g, gb = c.detectors["grid"], both.detectors["grid"]
    assert np.array_equal(g.count, gb.count) and np.array_equal(g.sumsq, gb.sumsq)
    np.testing.assert_allclose(g.value, gb.value, rtol=1e-12)
    np.testing.assert_allclose(g.sigma_rel, gb.sigma_rel, rtol=1e-9)
    _attrs_close(g.attrs, gb.attrs, DETECTOR_STATS)
    assert c.history is None and c.observers == {} and any("eye" in n for n in c.notes)


def test_two_seeds_of_the_binary_agree_and_shrink_the_error(room_runs):
    a, b = luxtrace.open(room_runs["random", 1]), luxtrace.open(room_runs["random", 2])
    c = luxtrace.combine([a, b])
    assert c.photons == 400000 and c.flux_per_photon_lm == pytest.approx(2000 / 400000)
    for name in a.detectors:
        da, db, dc = a.detectors[name], b.detectors[name], c.detectors[name]
        assert np.array_equal(dc.count, da.count + db.count)
        sa, sb = da.mean_value * da.mean_sigma_rel, db.mean_value * db.mean_sigma_rel
        # Independent runs of one scene: their grid means agree within their errors ...
        assert abs(da.mean_value - db.mean_value) / np.hypot(sa, sb) < 5
        # ... and the combination, with twice the photons, has the inverse-variance error
        # of the two (equal photons: 1/sqrt(2) of each), up to the noise of the estimates.
        sc = dc.mean_value * dc.mean_sigma_rel
        assert sc == pytest.approx(1 / np.sqrt(1 / sa**2 + 1 / sb**2), rel=0.1)
        assert dc.mean_value == pytest.approx((da.mean_value + db.mean_value) / 2, rel=1e-12)
    assert c.surface.sigma_lx.shape == (a.mesh.triangle_count, 2)


def test_sobol_combines_through_replicates(room_runs):
    a, b = luxtrace.open(room_runs["sobol", 1]), luxtrace.open(room_runs["sobol", 2])
    c = luxtrace.combine([a, b])
    assert c.replicates == a.replicates + b.replicates == 16
    t = c.detectors["table"]
    assert t.error_dof == 15 and t.replicate_count.shape[0] == 16
    assert np.array_equal(t.replicate_count.sum(axis=0), t.count), "every registration is in one replicate"
    sa, sb = (r.detectors["table"].mean_sigma_rel * r.detectors["table"].mean_value for r in (a, b))
    assert abs(a.detectors["table"].mean_value - b.detectors["table"].mean_value) / np.hypot(sa, sb) < 5


def test_mismatches_are_refused(room_runs, room_variant, v2_pair):
    a = luxtrace.open(room_runs["random", 1])
    with pytest.raises(luxtrace.MismatchError, match="seed 1"):
        luxtrace.combine([a, luxtrace.open(room_runs["random", 1])])
    with pytest.raises(luxtrace.MismatchError, match="sampler"):
        luxtrace.combine([a, luxtrace.open(room_runs["sobol", 2])])
    with pytest.raises(luxtrace.MismatchError, match="total_flux_lm"):
        luxtrace.combine([a, luxtrace.open(room_variant("flux_lm = 800", "flux_lm = 900"))])
    with pytest.raises(luxtrace.MismatchError, match="cells"):
        luxtrace.combine([a, luxtrace.open(room_variant("cells = [10, 8]", "cells = [10, 9]"))])
    with pytest.raises(luxtrace.MismatchError, match="mesh"):
        luxtrace.combine([a, luxtrace.open(room_variant("subdivisions = 6", "subdivisions = 5"))])
    v1 = luxtrace.open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "room_v1.h5"))
    with pytest.raises(luxtrace.MismatchError, match="format_version"):
        luxtrace.combine([v1, luxtrace.open(v2_pair[0])])
    with pytest.raises(ValueError):
        luxtrace.combine([])


@pytest.mark.parametrize("sampler", ["random", "sobol"])
def test_combined_errors_are_honest_against_an_independent_run(room_runs, sampler):
    """Seeds 1 + 2 combined against seed 3 with as many photons: per cell,
    z = (L_12 - L_3) / sqrt(sigma_12^2 + sigma_3^2) must stay within 5, and the mean of z^2
    over the K cells within 1 +- 5 sqrt(2/K) (docs/VALIDATION.md's rule). Combined errors
    too small would push mean z^2 up, too large down."""
    c = luxtrace.combine([luxtrace.open(room_runs[sampler, s]) for s in (1, 2)])
    ref = luxtrace.open(room_runs[sampler, 3])
    for name in ("table", "wall"):
        dc, dr = c.detectors[name], ref.detectors[name]
        ok = (dc.count[:, :, 0] > 0) & (dr.count[:, :, 0] > 0)
        z = ((dc.value - dr.value) / np.hypot(dc.sigma, dr.sigma))[:, :, 0][ok]
        k = z.size
        assert k >= 40
        assert np.abs(z).max() < 5, name
        assert abs(np.mean(z**2) - 1) < 5 * np.sqrt(2 / k), (name, np.mean(z**2))
        zm = (dc.mean_value - dr.mean_value) / np.hypot(dc.mean_value * dc.mean_sigma_rel,
                                                          dr.mean_value * dr.mean_sigma_rel)
        assert abs(zm) < 5, (name, zm)


RGB_SCENE = """
[scene]
name = "colour"
bands = ["R", "G", "B"]
[[material]]
name = "plane"
reflectance = [0.8, 0.5, 0.2]
[[shape]]
type = "box"
center = [0, 0, 1]
size = [4, 4, 2]
inward = true
material = "plane"
[[light]]
type = "point"
position = [0.3, 0.2, 1.5]
flux_lm = 1000
colour = [1, 0.5, 0.25]
[[detector]]
name = "floor"
center = [0, 0, 0.01]
size = [2, 1]
cells = [6, 4]
"""


@pytest.mark.parametrize("sampler", ["random", "sobol"])
def test_three_bands_combined_alone_are_themselves(binary, tmp_path, sampler):
    """With three bands the grid summaries are of band-summed cells (a photon carries one
    band): the combination's, from the summed counts or replicates, equal the binary's."""
    from conftest import run_luxtrace
    scene = tmp_path / "rgb.toml"
    scene.write_text(RGB_SCENE)
    r = luxtrace.open(run_luxtrace(binary, scene, tmp_path / "rgb.h5", "--photons", "100k", "--seed", "4",
                                   "--sampler", sampler))
    c = luxtrace.combine([r])
    d, cd = r.detectors["floor"], c.detectors["floor"]
    assert d.bands == 3
    np.testing.assert_allclose(cd.sigma_rel, d.sigma_rel, rtol=1e-10)
    _attrs_close(cd.attrs, d.attrs, DETECTOR_STATS)
    _attrs_close(c.surface.attrs, r.surface.attrs, GLOBAL_STATS)


def _same_result(a, b):
    assert a.format_version == b.format_version and a.photons == b.photons
    for k, v in a.surface.datasets.items():
        np.testing.assert_array_equal(b.surface.datasets[k], v, err_msg=k)
    for name, d in a.detectors.items():
        for k, v in d.datasets.items():
            np.testing.assert_array_equal(b.detectors[name].datasets[k], v, err_msg=f"{name}/{k}")
        assert set(b.detectors[name].attrs) == set(d.attrs)


def test_a_written_combination_reads_back_and_luxtrace_reads_it(binary, room_runs, tmp_path):
    import subprocess
    c = luxtrace.combine([luxtrace.open(room_runs["random", s]) for s in (1, 2)])
    path = luxtrace.write(c, tmp_path / "merged.h5")
    assert luxtrace.check_seal(path) is True
    back = luxtrace.open(path)
    _same_result(c, back)
    assert back.seeds == (1, 2) and back.stop_reason == "combined"
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    info = subprocess.run([binary, "info", path], capture_output=True, text=True, env=env)
    assert info.returncode == 0, info.stdout + info.stderr
    t = c.detectors["table"]
    assert f"mean {t.mean_value:.2f} lx +- {100 * t.mean_sigma_rel:.2f} %" in info.stdout, info.stdout
    assert "400000" in info.stdout
    xdmf = subprocess.run([binary, "export-xdmf", path], capture_output=True, text=True, env=env)
    assert xdmf.returncode == 0, xdmf.stderr


def test_format2_written_reads_back(v2_pair, tmp_path):
    c = luxtrace.combine([luxtrace.open(p) for p in v2_pair[:2]])
    back = luxtrace.open(luxtrace.write(c, tmp_path / "merged_v2.h5"))
    _same_result(c, back)
    assert back.surface.sumsq.shape == (2, 2, 2) and back.format_version == 2
