"""Annual results in Python: Result.annual holds the file's hours and each grid's hourly
values and metrics, and they agree with their definitions (LM-83's DA, sDA and ASE counted
from the hourly values, the occupied hours from the hours' middles)."""
import os

import h5py
import numpy as np
import pytest

import luxtrace
from conftest import edited_copy, run_luxtrace

NO_SUN = np.iinfo(np.uint64).max


@pytest.fixture(scope="module")
def year(annual_run):
    return luxtrace.open(annual_run)


def test_hours_table_follows_the_year(year):
    a = year.annual
    h = a.hours
    assert len(h) == 8760 and a.attrs["weather"].endswith("chicago.epw")
    lo, hi = a.occupied_hours
    np.testing.assert_array_equal(h.occupied == 1, (h.hour >= lo) & (h.hour < hi), "LM-83: the hour's middle")
    assert np.count_nonzero(h.daylit) == a.daylit_hours
    assert np.count_nonzero(h.sun_group != NO_SUN) == a.sun_hours
    assert not np.any((h.sun_group != NO_SUN) & (h.daylit == 0)), "a sun only in a daylit hour"
    assert np.count_nonzero(h.en17037_hour) == 4380, "EN 17037: half of the year's hours"
    assert np.all(h[h.daylit == 0].global_horizontal_lx == 0)
    day = a.day_of_year()
    assert day[0] == 0 and day[-1] == 364 and np.all(np.bincount(day) == 24)
    assert a.patches == 145 and a.sky_vectors_cd_m2.shape == (a.daylit_hours, 146)


@pytest.mark.parametrize("name", ["plane", "pts"])
def test_grid_metrics_are_their_hourly_definitions(year, name):
    a = year.annual
    g = a.grid(name)
    occupied = a.hours.occupied == 1
    e, direct = g.illuminance_lx[occupied], g.direct_sun_lx[occupied]
    assert g.illuminance_lx.shape == g.illuminance_sigma_lx.shape == (8760, g.sensor_count)
    assert np.all(g.illuminance_lx[a.hours.daylit == 0] == 0), "dark hours read 0"
    da = g.sensors["da"]
    np.testing.assert_allclose(da.value, np.mean(e >= 300, axis=0), atol=1e-12)
    np.testing.assert_allclose(g.sensors["ase_hours"].value, np.sum(direct >= 1000, axis=0), atol=1e-9)
    np.testing.assert_allclose(g.sensors["udi_fell_short"].value + g.sensors["udi_useful"].value
                               + g.sensors["udi_exceeded"].value, 1.0, atol=1e-12)
    assert g.metrics["sda"].value == pytest.approx(np.mean(da.value >= 0.5))
    assert g.metrics["ase"].value == pytest.approx(np.mean(g.sensors["ase_hours"].value > 250))
    assert g.metrics["mean_da"].value == pytest.approx(np.mean(da.value))
    assert g.replicates == 32 and np.all(da.sigma >= 0)
    np.testing.assert_allclose(da.corrected, da.value - da.bias)
    for level, (target, minimum) in luxtrace.annual.EN17037_LEVELS.items():
        x = g.en17037[level]
        assert (x.target_lx, x.minimum_lx) == (target, minimum)
        assert 0 <= x.target_hours.value <= 1 and x.target_hours.sigma >= 0 and 0 <= x.flip_probability <= 0.5


def test_sensors_are_the_detectors_cells_in_row_order(year):
    """Every group's coefficients summed give the detector's own counts: the sensors are its
    cells j * nx + i."""
    d, g = year.detector("plane"), year.annual.grid("plane")
    c = g.coefficients()
    assert c["count"].shape == (4071, d.nx * d.ny) and c["ground_group"] == 145 and c["first_sun_group"] == 146
    np.testing.assert_array_equal(c["count"].sum(axis=0), d.count[..., 0].ravel())
    assert year.annual.grid("pts").sensor_count == len(year.detector("pts").positions) == 4


def test_without_annual_and_combined(binary, room_runs, year, annual_run, tmp_path):
    assert luxtrace.open(room_runs["random", 1]).annual is None
    with pytest.raises(KeyError, match="plane, pts"):
        year.annual.grid("desk")
    other = run_luxtrace(binary, os.path.join(os.path.dirname(annual_run), "year.toml"), tmp_path / "seed2.h5",
                         "--photons", "20k", "--seed", "2")
    both = luxtrace.combine([year, luxtrace.open(other)])
    assert both.annual is None and any("/annual left out" in n for n in both.notes)


def test_a_damaged_annual_group_is_refused(annual_run, tmp_path):
    def cut(f):
        del f["annual/detectors/plane/da"]
        f["annual/detectors/plane/da"] = np.zeros(3)
    bad = edited_copy(annual_run, tmp_path / "bad.h5", cut)
    with pytest.raises(luxtrace.ResultError, match="annual/detectors/plane"):
        luxtrace.open(bad, check=False)


def test_a_checkpoints_metrics_have_no_errors(annual_run, tmp_path):
    """As in a checkpoint (REFERENCE.md §4): no _sigma and _bias, replicates 0. The reader
    says None for them."""
    def strip(f):
        for g in f["annual/detectors"].values():
            g.attrs["replicates"] = np.uint64(0)
            for k in [k for k in g.attrs if k.endswith(("_sigma", "_bias"))]:
                del g.attrs[k]
            for k in [k for k in g if k.endswith(("_sigma", "_bias")) and k not in luxtrace.annual.HOURLY]:
                del g[k]
    r = luxtrace.open(edited_copy(annual_run, tmp_path / "ck.h5", strip), check=False)
    g = r.annual.grid("plane")
    assert g.replicates == 0 and g.metrics["sda"].sigma is None and g.sensors["da"].bias is None
    assert g.en17037["minimum"].flip_probability is None and g.en17037["minimum"].target_hours.sigma is None
    np.testing.assert_array_equal(g.sensors["da"].corrected, g.sensors["da"].value)
    assert "+-" not in r.annual.summary()
