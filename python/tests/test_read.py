"""Reading results: both formats in one shape, values that match hand computations from
the stored counts, every attribute exposed, damaged and foreign files refused."""
import glob
import os

import h5py
import numpy as np
import pytest

import luxtrace
from conftest import AREA, BANDS, CELL_AREA, FLUX_LM, REPO, copy, points_scene, run_luxtrace, simulate, write_v2


V1_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "room_v1.h5")


def test_format1_in_format2_shape():
    """room_v1.h5: room.toml, 20k photons, seed 7, written by luxtrace 0.2 in format 1
    (kept so that format 1 stays tested: the binary writes format 2)."""
    r = luxtrace.open(V1_FILE)
    assert r.format == "luxtrace-result" and r.format_version == 1 and r.photons == 20000 and r.seed == 7
    s = r.surface
    with h5py.File(V1_FILE) as f:
        raw_odd = f["global/count_odd"][()]
        T, B = raw_odd.shape
        assert s.count_odd.shape == (T, 2, B)
        assert np.array_equal(s.count_odd[:, luxtrace.FRONT], raw_odd)
        assert not s.count_odd[:, luxtrace.BACK].any(), "format 1 has no back side: zeros"
        assert s.sumsq is None and np.isnan(s.sigma_lx).all() and s.sigma_lx.shape == (T, 2)
        assert np.array_equal(s.odd_even_difference_lx[:, 0], f["global/odd_even_difference_lx"][()])
        # Every attribute of every group is there, also those no property names.
        assert set(r.attrs) == set(f.attrs) and set(s.attrs) == set(f["global"].attrs)
        for name in f["detectors"]:
            assert set(r.detectors[name].attrs) == set(f["detectors"][name].attrs)
    # E = (n_odd + n_even) E0 / A (SPEC §3), E0 = 2000 lm / 20000 photons.
    assert r.flux_per_photon_lm == pytest.approx(0.1, rel=1e-15)
    n = (s.count_odd + s.count_even).astype(float)
    np.testing.assert_allclose(s.illuminance_lx, n * 0.1 / r.mesh.area_m2[:, None, None], rtol=1e-12)
    assert (s.illuminance_secondary_lx >= -1e-9).all(), "direct arrivals are a part of all arrivals"
    assert s.error_estimator == "odd_even" and np.isnan(s.moment_sigma_lx)


def test_the_binarys_format_reads(room_runs):
    """Whatever format the binary writes: maps [T,2,B] equal to the stored counts,
    E = (n_odd + n_even) E0 / A, every attribute there."""
    path = room_runs["random", 1]
    r = luxtrace.open(path)
    assert r.format_version in (1, 2) and r.photons == 200000 and r.seed == 1
    s = r.surface
    with h5py.File(path) as f:
        raw = f["global/count_odd"][()]
        front = raw if r.format_version == 1 else raw[:, luxtrace.FRONT]
        assert np.array_equal(s.count_odd[:, luxtrace.FRONT], front)
        assert set(r.attrs) == set(f.attrs) and set(s.attrs) == set(f["global"].attrs)
    e0 = 2000.0 / 200000
    n = (s.count_odd + s.count_even).astype(float)
    np.testing.assert_allclose(s.illuminance_lx, n * e0 / r.mesh.area_m2[:, None, None], rtol=1e-12)
    if r.format_version >= 2:
        lit = n.sum(axis=2) > 0
        assert np.isfinite(s.sigma_lx[lit]).all() and s.sumsq.shape == s.count_odd.shape


def test_detector_values_and_errors_by_hand(room_runs):
    r = luxtrace.open(room_runs["random", 1])
    t = r.detectors["table"]
    # room.toml: table 1.0 m x 0.8 m in 10 x 8 cells of 0.01 m^2, centre (2.8, 1.5, 0.75), normal +z, up +y.
    assert (t.nx, t.ny, t.size_m, t.units, t.type) == (10, 8, (1.0, 0.8), "lx", "illuminance")
    assert t.value.shape == (8, 10, 1)
    np.testing.assert_allclose(t.value, t.count * 0.01 / 0.01, rtol=1e-12)
    n, q = t.count.astype(float), t.sumsq.astype(float)
    np.testing.assert_allclose(t.sigma_rel, np.sqrt(q / n**2 - 1 / 200000), rtol=1e-12)  # eq. (8)
    np.testing.assert_allclose(t.sigma, t.value * t.sigma_rel)
    assert t.mean_value == pytest.approx(t.value.mean(), rel=1e-12)
    assert np.allclose(t.u, [1, 0, 0]) and np.allclose(t.cell_centres()[0, 0], [2.35, 1.15, 0.75])
    w = r.detector("wall")
    assert w.units == "cd/m^2" and w.attrs["half_angle_deg"] == 15.0
    with pytest.raises(KeyError, match="table, wall"):
        r.detector("ceiling")


def test_history_and_summary(room_runs):
    r = luxtrace.open(room_runs["random", 1])
    assert len(r.history) >= 1 and r.history.photons[-1] == r.photons
    assert r.history.target_labels == [] and r.history.target_value is None
    assert "table" in r.summary() and "200000" in r.summary()


def test_format2_by_hand(tmp_path):
    path = write_v2(tmp_path / "v2.h5", [(3, simulate(3, 2000))], extra_detector_attrs={"E_min": 1.25})
    with h5py.File(path, "r+") as f:  # a dataset a newer luxtrace might add passes through
        f["global/side_flags"] = np.ones((2, 2), dtype=np.uint8)
    r = luxtrace.open(path)
    assert r.format_version == 2 and r.bands == BANDS and r.photons == 2000
    s = r.surface
    assert s.count_odd.shape == (2, 2, 2) and s.sumsq.shape == (2, 2, 2) and s.sigma_lx.shape == (2, 2)
    assert not s.count_odd[1, luxtrace.BACK].any() and s.count_odd[0, luxtrace.BACK].any()
    # Triangle 1's back side is dark, so the lit area is three sides of 0.5 m^2.
    assert s.lit_area_m2 == pytest.approx(1.5) and s.error_estimator == "second_moment"
    assert np.isfinite(s.moment_sigma_lx) and s.moment_sigma_lx > 0
    e0 = FLUX_LM / 2000
    np.testing.assert_allclose(s.illuminance_lx, (s.count_odd + s.count_even) * e0 / AREA[:, None, None])
    d = r.detectors["grid"]
    assert d.attrs["E_min"] == 1.25 and d.E_min == 1.25, "attributes this package does not know are there"
    with pytest.raises(AttributeError, match="E_max"):
        d.E_max
    assert np.isnan(d.sigma_rel[1, 2]).all() and d.count[1, 2].sum() == 0
    value, rel = d.band_sum()
    np.testing.assert_allclose(value, d.count.sum(axis=2) * e0 / CELL_AREA)
    # One band at a time or summed: eq. (8) on the summed n and q.
    n, q = d.count.sum(axis=2).astype(float), d.sumsq.sum(axis=2).astype(float)
    with np.errstate(invalid="ignore", divide="ignore"):
        np.testing.assert_allclose(rel, np.sqrt(q / n**2 - 1 / 2000))
    assert r.surface.datasets["side_flags"].shape == (2, 2)
    eye = r.observers["eye"]
    assert eye.attrs["ugr"] == 17.5 and eye["background_cd_m2"][0] == 12.0


def test_damaged_files_are_refused(room_runs, tmp_path):
    src = room_runs["random", 1]
    assert luxtrace.check_seal(src) is True
    flipped = copy(src, tmp_path / "flipped.h5")
    with open(flipped, "r+b") as f:
        f.seek(5000)
        b = f.read(1)
        f.seek(5000)
        f.write(bytes([b[0] ^ 1]))
    with pytest.raises(luxtrace.ResultError, match="changed"):
        luxtrace.open(flipped)
    cut = copy(src, tmp_path / "cut.h5")
    with open(cut, "r+b") as f:
        f.truncate(20000)
    with pytest.raises(luxtrace.ResultError, match="cut short"):
        luxtrace.open(cut)
    text = tmp_path / "text.h5"
    text.write_text("not a result")
    with pytest.raises(luxtrace.ResultError, match="damaged"):
        luxtrace.open(text)
    with pytest.raises(FileNotFoundError):
        luxtrace.open(tmp_path / "missing.h5")


def test_foreign_and_future_files_are_refused(tmp_path):
    with h5py.File(tmp_path / "other.h5", "w") as f:
        f.attrs["format"] = "something-else"
    with pytest.raises(luxtrace.ResultError, match="not a luxtrace result"):
        luxtrace.open(tmp_path / "other.h5")
    path = write_v2(tmp_path / "v3.h5", [(1, simulate(1, 100))])
    with h5py.File(path, "r+") as f:
        f.attrs["format_version"] = np.uint64(3)
    with pytest.raises(luxtrace.ResultError, match="format_version 3"):
        luxtrace.open(path)


def test_fuzz_corpus_opens_or_is_refused(tmp_path):
    """The result fuzzer's corpus and crashers (bit flips, truncations, unsealed 0.1 files,
    absurd attributes): a file is read or refused with ResultError, never another error,
    and the pictures of every detector of every file that opens are drawn. (What
    tests/fuzz/cli_exit_codes.sh does for the binary's commands, in one process.)"""
    from luxtrace import plot
    root = os.path.join(REPO, "tests", "fuzz")
    files = sorted(glob.glob(os.path.join(root, "corpus", "result", "*")) +
                   glob.glob(os.path.join(root, "crashers", "result", "*")))
    files = [f for f in files if os.path.isfile(f) and not os.path.basename(f).startswith("README")]
    assert len(files) > 10
    opened = 0
    for f in files:
        try:
            r = luxtrace.open(f)
        except luxtrace.ResultError:
            continue
        opened += 1
        for name in r.detectors:
            plot.detector_pictures(r, name, str(tmp_path / os.path.basename(f)))
    assert opened > 0


def test_checkpoint_reads_like_a_result():
    """A checkpoint of the fuzz corpus (luxtrace 0.2, sealed): the result's groups are
    there, and its summaries are those of its counts."""
    r = luxtrace.open(os.path.join(REPO, "tests", "fuzz", "corpus", "result", "checkpoint_y"))
    assert r.is_checkpoint and r.photons > 0 and r.detectors
    c = luxtrace.combine([r])
    for name, d in r.detectors.items():
        np.testing.assert_allclose(c.detectors[name].sigma_rel, d.sigma_rel, rtol=1e-10)
        assert c.detectors[name].mean_sigma_rel == pytest.approx(d.mean_sigma_rel, rel=1e-10)
    assert c.surface.sigma_rel_quadratic == pytest.approx(r.surface.sigma_rel_quadratic, rel=1e-10)


def test_history_target_columns(target_run):
    """A run stopped by a global target: its column in the history fell to the goal at the
    last reduction and not before, and the last row is the state the file ends in."""
    r = luxtrace.open(target_run)
    h = r.history
    t = h.target(0)
    assert h.target(t.label).label == t.label == h.target_labels[0] and t.goal == 0.05
    assert r.stop_reason == f"target {t.label}"
    assert len(t.value) == len(t.forecast_s) == len(t.forecast_photons) == len(h) >= 2
    assert t.value[-1] <= t.goal and (t.value[:-1] > t.goal).all()
    assert h.photons[-1] == r.photons
    assert t.value[-1] == pytest.approx(r.surface.moment_sigma_rel_quadratic, rel=1e-12)
    with pytest.raises(KeyError, match="global rel"):
        h.target("desk abs")
    with pytest.raises(KeyError):
        h.target(1)


def test_side_maps_give_the_global_figures(tmp_path):
    """The global figures are area-weighted over the lit triangle sides (SPEC §3): computed
    again from side_illuminance_lx, side_area_m2 and the per-side sigmas, they are the
    stored ones."""
    r = luxtrace.open(write_v2(tmp_path / "v2.h5", [(4, simulate(4, 3000))]))
    s = r.surface
    e, a = s.side_illuminance_lx, s.side_area_m2
    assert e.shape == a.shape == (2, 2) and np.array_equal(a[:, luxtrace.BACK], AREA)
    np.testing.assert_allclose(e, s.illuminance_lx[:, :, 0] + s.illuminance_lx[:, :, 1])
    lit = e > 0
    area = a[lit].sum()
    assert area == pytest.approx(s.lit_area_m2)
    assert (a[lit] * e[lit]).sum() / area == pytest.approx(s.mean_arithmetic_lx, rel=1e-12)
    assert np.sqrt((a[lit] * s.sigma_lx[lit] ** 2).sum() / area) == pytest.approx(s.moment_sigma_lx, rel=1e-12)
    d = s.odd_even_difference_lx[lit]
    assert np.sqrt((a[lit] * d * d).sum() / area) / 2 == pytest.approx(s.odd_even_sigma_lx, rel=1e-12)


def test_task_areas(binary, tmp_path):
    """point_floor_metrics.toml's task area "side" (cells 6 <= i < 10, 2 <= j < 5): its
    Eavg, Emin and Emax are the mean, least and largest band-summed value of those cells of
    the detector; written again by luxtrace.write it reads back the same; a combination
    leaves it out and says so."""
    from conftest import run_luxtrace
    scene = os.path.join(REPO, "tests", "data", "validation", "point_floor_metrics.toml")
    runs = [luxtrace.open(run_luxtrace(binary, scene, tmp_path / f"m{seed}.h5", "--photons", "20k", "--seed",
                                       str(seed))) for seed in (1, 2)]
    d = runs[0].detector("floor_E")
    assert list(d.task_areas) == ["side"]
    side = d.task_areas["side"]
    i0, i1, j0, j1 = (int(x) for x in side.cell_range)
    assert (i0, i1, j0, j1) == (6, 10, 2, 5)
    cells = d.band_sum()[0][j0:j1, i0:i1]
    assert side.E_avg_lx == pytest.approx(cells.mean(), rel=1e-12)
    assert side.E_min_lx == pytest.approx(cells.min(), rel=1e-12)
    assert side.E_max_lx == pytest.approx(cells.max(), rel=1e-12)
    assert d.E_avg_lx == pytest.approx(d.band_sum()[0].mean(), rel=1e-12), "the grid's own metrics"
    again = luxtrace.open(luxtrace.write(runs[0], str(tmp_path / "again.h5")))
    assert again.detector("floor_E").task_areas["side"].attrs.keys() == side.attrs.keys()
    assert again.detector("floor_E").task_areas["side"].E_min_lx == side.E_min_lx
    both = luxtrace.combine(runs)
    assert not both.detector("floor_E").task_areas and any("task areas" in n for n in both.notes)


def test_points_detector(binary, tmp_path):
    """A points detector (.pts sensors) reads with its sensors as cells: positions and
    directions as written, cell centres at the sensors, a CSV row per sensor."""
    scene = points_scene(tmp_path, "# two sensors up, one facing +x\n0 0 0.8 0 0 1\n1 0 0.8 0 0 2\n\n3 0 1 1 0 0\n",
                         (0, 0, 2))
    r = luxtrace.open(run_luxtrace(binary, scene, tmp_path / "r.h5", "--photons", "20k"))
    d = r.detector("sensors")
    assert d.is_points and (d.nx, d.ny, d.type, d.units) == (3, 1, "points", "lx")
    np.testing.assert_array_equal(d.positions, [[0, 0, 0.8], [1, 0, 0.8], [3, 0, 1]])
    np.testing.assert_array_equal(d.directions, [[0, 0, 1], [0, 0, 1], [1, 0, 0]])
    np.testing.assert_array_equal(d.cell_centres()[0], d.positions)
    assert d.attrs["radius_m"] == 0.5 and d.attrs["points_file"] == "grid.pts"
    assert np.isnan(d.center).all() and np.isnan(d.size_m).all()
    d.to_csv(tmp_path / "s.csv")
    with open(tmp_path / "s.csv") as f:
        rows = f.read().splitlines()
    assert len(rows) == 4 and rows[3].split(",")[4:7] == ["3.0", "0.0", "1.0"]
    # Two seeds combine: counts add, the sensors stay; another grid is refused.
    r2 = luxtrace.open(run_luxtrace(binary, scene, tmp_path / "r2.h5", "--photons", "20k", "--seed", "2"))
    c = luxtrace.combine([r, r2]).detector("sensors")
    np.testing.assert_array_equal(c.count, d.count + r2.detector("sensors").count)
    np.testing.assert_array_equal(c.positions, d.positions)
    np.testing.assert_array_equal(c.cell_centres()[0], d.positions)
    (tmp_path / "grid.pts").write_text("0 0 0.8 0 0 1\n1 0 0.8 0 0 1\n3 0 1.5 1 0 0\n")
    r3 = luxtrace.open(run_luxtrace(binary, scene, tmp_path / "r3.h5", "--photons", "20k", "--seed", "3"))
    with pytest.raises(luxtrace.MismatchError, match="other sensor positions"):
        luxtrace.combine([r, r3])


def test_a_tally_checkpoint_says_what_it_is(binary, tmp_path):
    """A run whose result and whole checkpoint both failed keeps the tallies alone (issue
    35): the package refuses such a file with the command that writes its result, rather
    than calling it damaged."""
    import subprocess
    scene = os.path.join(REPO, "tests", "data", "run", "room.toml")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out = tmp_path / "r.h5"
    p = subprocess.run([binary, "run", scene, "--output", str(out), "--quiet", "--threads", "1", "--photons", "20k",
                        "--inject-fault", "result:image,checkpoint:estimates"], env=env, capture_output=True,
                       text=True, timeout=120)
    assert p.returncode == 1, p.stdout + p.stderr
    kept = str(out) + ".checkpoint.h5"
    with pytest.raises(luxtrace.ResultError, match="a tally checkpoint .* --restart " + kept):
        luxtrace.open(kept)
