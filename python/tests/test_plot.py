"""Detector pictures show the detector's data: the map's pixels are the cells' values, the
colour scale spans the data, the histogram counts every cell with hits, the sections
read the asked row and column; the PNGs are written, and bad input writes nothing."""
import os
import subprocess
import sys

import h5py
import matplotlib.image
import numpy as np
import pytest

import luxtrace
from luxtrace import plot
from conftest import HERE, REPO, copy, points_scene, run_luxtrace, simulate, write_v2

import matplotlib.pyplot as plt


@pytest.fixture
def grid(tmp_path):
    """The hand-made 3 x 2 detector of two bands with one cell never hit."""
    return luxtrace.open(write_v2(tmp_path / "v2.h5", [(4, simulate(4, 3000))]))


def test_value_map_is_the_data_with_its_range(grid):
    d = grid.detectors["grid"]
    value, _ = d.band_sum()
    fig = plot.value_figure(d)
    im = fig.axes[0].images[0]
    assert np.array_equal(im.get_array(), value), "one pixel per cell, the band sum, row 0 first"
    assert im.origin == "lower" and im.get_clim() == (0.0, value.max())
    assert im.get_extent() == [-0.3, 0.3, -0.2, 0.2]
    plt.close(fig)


def test_error_map_masks_the_cells_without_hits(grid):
    d = grid.detectors["grid"]
    _, rel = d.band_sum()
    fig = plot.error_figure(d)
    im = fig.axes[0].images[0]
    a = im.get_array()
    assert a.mask[1, 2] and a.mask.sum() == 1, "exactly the cell without hits"
    assert im.get_clim() == (0.0, pytest.approx(100 * np.nanmax(rel)))
    (marks,) = fig.axes[0].lines
    assert marks.get_xdata() == pytest.approx([0.2]) and marks.get_ydata() == pytest.approx([0.1])
    plt.close(fig)


def test_histogram_counts_every_cell_with_hits(room_runs):
    d = luxtrace.open(room_runs["random", 1]).detectors["wall"]
    _, rel = d.band_sum()
    fig = plot.error_histogram_figure(d)
    bars = fig.axes[0].patches
    assert sum(b.get_height() for b in bars) == np.isfinite(rel).sum()
    lo = min(b.get_x() for b in bars)
    hi = max(b.get_x() + b.get_width() for b in bars)
    assert lo == pytest.approx(100 * np.nanmin(rel)) and hi == pytest.approx(100 * np.nanmax(rel))
    xs = sorted(line.get_xdata()[0] for line in fig.axes[0].lines)
    assert xs == pytest.approx(sorted([100 * d.sigma_rel_arithmetic, 100 * d.sigma_rel_quadratic]))
    plt.close(fig)


def _steps(ax):
    """The value staircase of a section panel: the stairs drawn without a fill."""
    for p in ax.patches:
        if not p.get_fill():
            v = p.get_path().vertices
            return v[1:-1:2, 1] if len(v) > 2 else v[:, 1]
    raise AssertionError("no staircase")


def test_sections_read_the_asked_row_and_column(room_runs):
    d = luxtrace.open(room_runs["random", 1]).detectors["table"]
    value, _ = d.band_sum()
    fig = plot.sections_figure(d, 3, 5)
    row, col = _steps(fig.axes[0]), _steps(fig.axes[1])
    np.testing.assert_allclose(row, value[5, :])
    np.testing.assert_allclose(col, value[:, 3])
    plt.close(fig)
    assert plot.brightest_cell(d) == tuple(int(x) for x in np.unravel_index(np.argmax(value), value.shape))[::-1]
    with pytest.raises(ValueError, match="outside"):
        plot.sections_figure(d, 10, 0)


def test_detector_pictures_are_written(room_runs, out_dir):
    r = luxtrace.open(room_runs["random", 1])
    paths = plot.detector_pictures(r, "wall", str(out_dir), cell=(2, 1))
    assert [os.path.basename(p) for p in paths] == ["wall_value.png", "wall_error.png", "wall_error_hist.png",
                                                    "wall_sections.png"]
    for p in paths:
        img = matplotlib.image.imread(p)
        assert img.ndim == 3 and min(img.shape[:2]) > 200
    assert sorted(os.listdir(out_dir)) == sorted(os.path.basename(p) for p in paths), "no temporary files left"


def test_command_line(room_runs, out_dir):
    env = dict(os.environ, PYTHONPATH=os.path.dirname(HERE))
    cmd = [sys.executable, "-m", "luxtrace.plot", room_runs["random", 1], "-o", str(out_dir)]
    bad = subprocess.run(cmd + ["--detector", "table", "--detector", "ceiling"], env=env, capture_output=True,
                         text=True)
    assert bad.returncode == 2 and "ceiling" in bad.stderr and "table, wall" in bad.stderr
    bad = subprocess.run(cmd + ["--detector", "table", "--cell", "10,0"], env=env, capture_output=True, text=True)
    assert bad.returncode == 2 and "--cell" in bad.stderr
    assert os.listdir(out_dir) == [], "bad input writes nothing"
    ok = subprocess.run(cmd + ["--detector", "table", "--convergence"], env=env, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert sorted(os.listdir(out_dir)) == ["convergence.png", "table_error.png", "table_error_hist.png",
                                           "table_sections.png", "table_value.png"]


def test_plot_convergence_script_uses_the_package(room_runs, out_dir):
    script = os.path.join(REPO, "scripts", "plot_convergence.py")
    p = subprocess.run([sys.executable, script, room_runs["random", 2], "-o", str(out_dir), "--detector", "wall"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert {"convergence.png", "wall_value.png", "wall_sections.png"} <= set(os.listdir(out_dir))


def _with_daylight_factor(src, dst, reference_lx=250.0):
    """A copy of a room run whose detector 'table' carries daylight factors as the binary
    writes them for a daylight_factor detector (the scene's lamp standing in for the sky;
    the quantile figures and verdicts are stated here, the reader only has to pass them on)."""
    from luxtrace.result_file import _seal
    path = copy(src, dst)
    with h5py.File(path, "r+") as f:
        g = f["detectors/table"]
        value = g["value"][()].sum(axis=2)
        g["daylight_factor"] = 100 * value / reference_lx
        g["daylight_factor_sigma"] = 100 * value * g["sigma_rel"][()][:, :, 0] / reference_lx
        g.attrs["daylight_reference_lx"] = reference_lx
        for k, v in {"DF_cells_without_photons": np.uint64(0), "DF_mean_pct": 2.0, "DF_mean_sigma_pct": 0.01,
                     "DF_median_pct": 1.9, "DF_median_sigma_pct": 0.05, "DF_median_bias_pct": -0.02,
                     "DF_95_pct": 0.6, "DF_95_sigma_pct": 0.04, "DF_95_bias_pct": -0.03,
                     "en17037_target_df_pct": 2.0, "en17037_minimum_df_pct": 0.7,
                     "en17037_target_verdict": "undecided", "en17037_target_photons_factor": 3.5,
                     "en17037_minimum_verdict": "fail", "en17037_minimum_photons_factor": 0.0,
                     "en17037_verdict": "fail", "en17037_photons_factor": 0.0}.items():
            g.attrs[k] = v
    _seal(path)
    return path


def test_daylight_factor_map_figures_and_picture(room_runs, tmp_path, out_dir):
    path = _with_daylight_factor(room_runs["random", 1], tmp_path / "df.h5")
    r = luxtrace.open(path)
    d = r.detector("table")
    assert d.is_daylight and not r.detector("wall").is_daylight
    assert d.daylight_reference_lx == 250.0
    value, rel = d.band_sum()
    np.testing.assert_allclose(d.daylight_factor, 100 * value / 250.0, rtol=1e-12)
    np.testing.assert_allclose(d.daylight_factor_sigma, d.daylight_factor * rel, rtol=1e-12)
    f = d.daylight_figures()
    assert f["median"]["corrected"] == pytest.approx(1.92) and f["df_95"]["corrected"] == pytest.approx(0.63)
    assert f["en17037"]["verdict"] == "fail" and f["en17037"]["target_photons_factor"] == 3.5
    assert r.detector("wall").daylight_figures() is None
    paths = plot.detector_pictures(r, "table", str(out_dir))
    assert os.path.basename(paths[-1]) == "table_df.png"
    img = matplotlib.image.imread(paths[-1])
    assert img.ndim == 3 and min(img.shape[:2]) > 200


def test_pictures_of_a_stored_light_scene(binary, tmp_path):
    """--scene draws a detector as the run's [[light_scene]] left it: the stored scene's
    values and daylight factors (half the daylight of tests/data/reference/daylight_keys.toml),
    with the detector's geometry; an unknown scene writes nothing and exits 2."""
    from conftest import run_luxtrace
    scene = os.path.join(REPO, "tests", "data", "reference", "daylight_keys.toml")
    path = run_luxtrace(binary, scene, tmp_path / "day.h5", "--photons", "100k")
    r = luxtrace.open(path)
    d = r.scene_detector("half_daylight", "roof_df")
    with h5py.File(path, "r") as f:
        g = f["light_scenes/half_daylight/detectors/roof_df"]
        np.testing.assert_array_equal(d.value, g["value"][()])
        np.testing.assert_array_equal(d.daylight_factor, g["daylight_factor"][()])
    assert (d.nx, d.ny) == (r.detector("roof_df").nx, r.detector("roof_df").ny)
    # /daylight: the site's time, and E_h,ext = the sum over the daylight sources.
    day = r.daylight
    assert day.attrs["time"] == "2026-06-21T14:30"
    assert list(day.datasets["model"][:2]) in ([b"sun", b"CIE type 12"], ["sun", "CIE type 12"])
    assert day.attrs["unobstructed_horizontal_lx"] == pytest.approx(day.datasets["unobstructed_horizontal_lx"].sum())
    assert d.daylight_reference_lx == pytest.approx(0.5 * day.attrs["unobstructed_horizontal_lx"])
    # Half of every light: the same daylight factors as the whole run, half the values.
    np.testing.assert_allclose(d.value, 0.5 * r.detector("roof_df").value, rtol=1e-12)
    np.testing.assert_allclose(d.daylight_factor, r.detector("roof_df").daylight_factor, rtol=1e-12)
    out = tmp_path / "pics"
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "plot_detector.py"), path, "--detector",
                        "roof_df", "--scene", "half_daylight", "-o", str(out)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert (out / "roof_df_df.png").exists()
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "plot_detector.py"), path, "--detector",
                        "roof_df", "--scene", "nope", "-o", str(tmp_path / "none")], capture_output=True, text=True)
    assert p.returncode == 2 and "no light scene 'nope'" in p.stderr and not (tmp_path / "none").exists()


def test_points_detector_pictures(binary, tmp_path, out_dir):
    """A points detector (.pts sensors) is drawn as dots at the sensors coloured by their
    values, and its sections as every sensor in file order; all pictures are written."""
    scene = points_scene(tmp_path, "".join(f"{x} {y} 0.8 0 0 1\n" for y in range(3) for x in range(4)),
                         (1.5, 1, 2), floor_m=8)
    r = luxtrace.open(run_luxtrace(binary, scene, tmp_path / "r.h5", "--photons", "40k"))
    d = r.detector("sensors")
    fig = plot.value_figure(d)
    dots = fig.axes[0].collections[0]
    np.testing.assert_allclose(dots.get_offsets(), d.positions[:, :2])  # seen from above: x, y
    np.testing.assert_allclose(dots.get_array(), d.value[0, :, 0])
    plt.close(fig)
    fig = plot.sections_figure(d, 5, 0)
    assert "sensor 5 at (1, 1, 0.8)" in fig.axes[0].get_title()
    plt.close(fig)
    paths = plot.detector_pictures(r, "sensors", str(out_dir))
    assert [os.path.basename(p) for p in paths] == ["sensors_value.png", "sensors_error.png",
                                                    "sensors_error_hist.png", "sensors_sections.png"]
