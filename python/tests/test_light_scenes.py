"""Light scenes recombined in Python from /light_groups (issue 22): weights all 1 give the
plain run's figures, and a dimmed combination gives what luxtrace itself wrote for the
scene's [[light_scene]] (the C++ estimator, an independent implementation)."""
import os

import h5py
import numpy as np
import pytest

import luxtrace
from conftest import REPO, run_luxtrace

TWO_GROUPS = os.path.join(REPO, "tests", "data", "run", "two_groups.toml")


@pytest.fixture(scope="module", params=["random", "sobol"])
def two_groups(binary, tmp_path_factory, request):
    """two_groups.toml, 50k photons; sobol's errors come from the weighted replicate counts."""
    out = tmp_path_factory.mktemp("groups") / f"two_{request.param}.h5"
    return run_luxtrace(binary, TWO_GROUPS, out, "--photons", "50k", "--sampler", request.param)


def test_groups_in_index_order(two_groups):
    assert luxtrace.open(two_groups).light_groups == ["a", "b"]


def test_weights_one_give_the_plain_run(two_groups):
    r = luxtrace.open(two_groups)
    ls = r.light_scene({"a": 1, "b": 1})
    # Integer counts summed with weight 1 are exact, so are the figures made from them.
    s, p = ls.surface, r.surface
    np.testing.assert_array_equal(ls.detectors["table"].count, r.detectors["table"].count)
    np.testing.assert_array_equal(ls.detectors["table"].sumsq, r.detectors["table"].sumsq)
    np.testing.assert_allclose(ls.detectors["table"].value, r.detectors["table"].value, rtol=1e-14)
    np.testing.assert_allclose(ls.detectors["table"].sigma_rel, r.detectors["table"].sigma_rel, rtol=1e-12)
    assert ls.detectors["table"].mean_value == pytest.approx(r.detectors["table"].mean_value, rel=1e-14)
    assert ls.detectors["table"].mean_sigma_rel == pytest.approx(r.detectors["table"].mean_sigma_rel, rel=1e-12)
    np.testing.assert_allclose(s.illuminance_lx, p.illuminance_lx, rtol=1e-14)
    np.testing.assert_allclose(s.sigma_lx, p.sigma_lx, rtol=1e-12)
    assert s.mean_arithmetic_lx == pytest.approx(p.mean_arithmetic_lx, rel=1e-12)
    assert s.odd_even_sigma_lx == pytest.approx(p.odd_even_sigma_lx, rel=1e-12)


def test_dimmed_combination_equals_the_files_light_scene(two_groups):
    r = luxtrace.open(two_groups)
    ls = r.light_scene({"a": 0.1, "b": 1.0})
    with h5py.File(two_groups, "r") as f:
        dim = f["light_scenes/dim"]
        np.testing.assert_allclose(dim.attrs["weights"], [0.1, 1.0])
        d = dim["detectors/table"]
        np.testing.assert_allclose(ls.detectors["table"].value, d["value"][()], rtol=1e-10)
        np.testing.assert_allclose(ls.detectors["table"].sigma_rel, d["sigma_rel"][()], rtol=1e-10)
        assert ls.detectors["table"].mean_value == pytest.approx(d.attrs["mean_value"], rel=1e-10)
        assert ls.detectors["table"].mean_sigma_rel == pytest.approx(d.attrs["mean_sigma_rel"], rel=1e-10)
        g = dim["global"]
        np.testing.assert_allclose(ls.surface.illuminance_lx, g["illuminance"][()], rtol=1e-10)
        np.testing.assert_allclose(ls.surface.illuminance_direct_lx, g["illuminance_direct"][()], rtol=1e-10)
        np.testing.assert_allclose(ls.surface.sigma_lx, g["sigma_lx"][()], rtol=1e-10)
        np.testing.assert_allclose(ls.surface.odd_even_difference_lx, g["odd_even_difference_lx"][()], rtol=1e-10,
                                   atol=1e-12)
        for k in ("mean_arithmetic_lx", "mean_quadratic_lx", "sigma_lx", "moment_sigma_lx"):
            assert ls.surface.summary[k] == pytest.approx(g.attrs[k], rel=1e-10), k
        if "replicate_sigma_lx" in g:  # sobol: the replicate maps' spread, as the file's
            np.testing.assert_allclose(ls.surface.replicate_sigma_lx, g["replicate_sigma_lx"][()], rtol=1e-10)
            assert ls.surface.replicate_sigma_lx_global == pytest.approx(g.attrs["replicate_sigma_lx"], rel=1e-10)
        else:
            assert ls.surface.replicate_sigma_lx is None
    # Dimming a to 10 % lowers the mean below the plain run's.
    assert ls.detectors["table"].mean_value < r.detectors["table"].mean_value


def test_bad_combinations_are_refused(two_groups, room_runs):
    r = luxtrace.open(two_groups)
    with pytest.raises(KeyError, match="no light group c"):
        r.light_scene({"c": 1})
    with pytest.raises(ValueError, match="weight"):
        r.light_scene({"a": -1})
    with pytest.raises(ValueError, match="no light groups"):
        luxtrace.open(room_runs["random", 1]).light_scene({"all": 1})


def test_recombined_daylight_factors_match_the_declared_light_scene(binary, tmp_path):
    """A combination's DF map (its daylight sources at their groups' weights, /daylight) is
    the declared [[light_scene]]'s to rounding, with the same errors, in Python and in
    `luxtrace info --scene` (the daylit example: overcast and clear groups)."""
    import subprocess
    scene = os.path.join(REPO, "examples", "daylight", "side_lit_office.toml")
    path = run_luxtrace(binary, scene, tmp_path / "day.h5", "--photons", "300k")
    r = luxtrace.open(path)
    stored = r.scene_detector("overcast", "work_plane")
    mine = r.light_scene({"overcast": 1.0}).detectors["work_plane"]
    assert mine.daylight_reference_lx == pytest.approx(stored.daylight_reference_lx, rel=1e-12)
    np.testing.assert_allclose(mine.daylight_factor, stored.daylight_factor, rtol=1e-10)
    np.testing.assert_allclose(mine.daylight_factor_sigma, stored.daylight_factor_sigma, rtol=1e-10)
    none = r.light_scene({"overcast": 0.0, "clear": 0.0}).detectors["work_plane"]
    assert none.daylight_reference_lx == 0.0 and none.daylight_factor is None
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out = subprocess.run([binary, "info", path, "--scene", "overcast=1"], env=env, capture_output=True,
                         text=True, check=True).stdout
    line = next(x for x in out.splitlines() if "DF mean" in x)
    df = float(line.split("DF mean")[1].split()[0])
    assert df == pytest.approx(stored.attrs["DF_mean_pct"], abs=0.006)
