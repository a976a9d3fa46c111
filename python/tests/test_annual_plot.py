"""Annual pictures draw the grid's data: the DA map's pixels are the sensors' DA with the
50 % line where DA interpolates to 50 %, the ASE map's the ASE hours (points: the sensors
past 250 h ringed), the heat map puts every hour at its day and hour; the PNGs are written,
and bad input writes nothing."""
import os

import matplotlib.pyplot as plt
import numpy as np
import pytest

import luxtrace
from luxtrace import annual_plot
from conftest import edited_copy


@pytest.fixture(scope="module")
def year(annual_run):
    return luxtrace.open(annual_run)


def test_da_map_is_the_grids_da_with_its_50_percent_line(year):
    d, g = year.detector("plane"), year.annual.grid("plane")
    fig = annual_plot.da_figure(year, "plane")
    ax = fig.axes[0]
    im = ax.images[0]
    np.testing.assert_allclose(im.get_array(), 100 * g.sensors["da"].value.reshape(d.ny, d.nx))
    assert im.get_clim() == (0.0, 100.0) and im.origin == "lower"
    # The box darkens columns 0 and 1: the line runs between the centres of columns 1 and 2,
    # where the DA interpolated linearly between them is 50 %.
    da = 100 * g.sensors["da"].value.reshape(d.ny, d.nx)
    assert np.all(da[:, :2] == 0) and np.all(da[:, 2:] > 50)
    u, _ = d.cell_coordinates()
    want = u[1] + (u[2] - u[1]) * (50 - da[:, 1]) / (da[:, 2] - da[:, 1])
    xs = np.concatenate([p.vertices[:, 0] for c in ax.collections for p in c.get_paths()])
    assert len(xs) >= 2 and want.min() - 1e-9 <= xs.min() and xs.max() <= want.max() + 1e-9
    plt.close(fig)


def test_ase_map_and_points_rings(year):
    g = year.annual.grid("plane")
    fig = annual_plot.ase_figure(year, "plane")
    im = fig.axes[0].images[0]
    np.testing.assert_allclose(im.get_array().ravel(), g.sensors["ase_hours"].value)
    assert im.get_clim()[1] == max(500.0, g.sensors["ase_hours"].value.max())
    plt.close(fig)
    p = year.annual.grid("pts")
    fig = annual_plot.ase_figure(year, "pts")
    dots, rings = fig.axes[0].collections
    np.testing.assert_allclose(dots.get_array(), p.sensors["ase_hours"].value)
    assert len(rings.get_offsets()) == np.count_nonzero(p.sensors["ase_hours"].value > 250)
    plt.close(fig)


def test_hours_heat_map_places_every_hour(year):
    a, g = year.annual, year.annual.grid("plane")
    s = annual_plot.typical_sensor(year, "plane")
    assert g.sensors["da"].value[s] == np.sort(g.sensors["da"].value)[(g.sensor_count - 1) // 2]
    image = annual_plot.hours_image(year, "plane", s)
    assert image.shape == (24, 365) and np.all(np.isfinite(image))
    k = 4000  # 16 June, 16:00-17:00
    assert image[int(a.hours.hour[k]), a.day_of_year()[k]] == g.illuminance_lx[k, s]
    assert image.sum() == pytest.approx(g.illuminance_lx[:, s].astype(float).sum())
    with pytest.raises(ValueError, match="outside grid"):
        annual_plot.hours_image(year, "plane", 16)


def test_pictures_and_command_line(year, annual_run, room_runs, out_dir, tmp_path):
    paths = annual_plot.annual_pictures(year, "pts", str(out_dir), sensor=2)
    assert sorted(os.path.basename(p) for p in paths) == ["pts_ase.png", "pts_da.png", "pts_hours.png"]
    for p in paths:
        assert plt.imread(p).shape[2] in (3, 4)
    cli = tmp_path / "cli"
    assert annual_plot.main([annual_run, "-o", str(cli)]) == 0
    assert sorted(os.listdir(cli)) == sorted(f"{g}_{k}.png" for g in ("plane", "pts") for k in ("da", "ase", "hours"))
    bad = tmp_path / "bad"
    for args in ([room_runs["random", 1]], [annual_run, "--grid", "desk"], [annual_run, "--sensor", "99"],
                 [str(tmp_path / "missing.h5")]):
        assert annual_plot.main([*args, "-o", str(bad)]) == 2, args
    assert not bad.exists(), "bad input writes nothing"


def test_a_checkpoint_draws_without_errors(annual_run, tmp_path, out_dir):
    def strip(f):
        for g in f["annual/detectors"].values():
            g.attrs["replicates"] = 0
            for k in [k for k in g.attrs if k.endswith(("_sigma", "_bias"))]:
                del g.attrs[k]
    r = luxtrace.open(edited_copy(annual_run, tmp_path / "ck.h5", strip), check=False)
    assert len(annual_plot.annual_pictures(r, "plane", str(out_dir))) == 3
