"""Fixtures: result files made by the real luxtrace binary (in the format it writes), and
format-2 files written here with h5py from simulated per-photon arrivals, whose statistics are
computed from their definitions (per-photon variances), not from the package's formulas."""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))  # the package without installing it


def _binary():
    b = os.environ.get("LUXTRACE_BINARY") or os.path.join(REPO, "build", "src", "luxtrace")
    return b if os.path.isfile(b) and os.access(b, os.X_OK) else None


@pytest.fixture(scope="session")
def binary():
    b = _binary()
    if b is None:
        pytest.skip("no luxtrace binary (set LUXTRACE_BINARY or build build/src/luxtrace)")
    return b


def run_luxtrace(binary, scene, out, *args):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([binary, "run", str(scene), "--output", str(out), "--quiet", "--threads", "1", *args],
                       env=env, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    return str(out)


ROOM = os.path.join(REPO, "tests", "data", "run", "room.toml")


def points_scene(folder, pts_text, light_position, floor_m=4):
    """A scene in ``folder`` with a points detector "sensors" reading ``pts_text`` as
    grid.pts, a 1000 lm point light and a grey floor; returns the scene's path."""
    (folder / "grid.pts").write_text(pts_text)
    scene = folder / "s.toml"
    scene.write_text(f'[[material]]\nname = "m"\nreflectance = 0.5\n\n[[shape]]\ntype = "rectangle"\n'
                     f'size = [{floor_m}, {floor_m}]\nmaterial = "m"\n\n[[light]]\ntype = "point"\n'
                     f'position = {list(light_position)}\nflux_lm = 1000\n\n[[detector]]\nname = "sensors"\n'
                     f'type = "points"\npoints = "grid.pts"\n')
    return scene


@pytest.fixture(scope="session")
def room_runs(binary, tmp_path_factory):
    """room.toml (an illuminance and a luminance detector) with seeds 1 and 2 (200k photons
    each) and 3 (400k), sampler random and sobol (about 0.2 s per run)."""
    d = tmp_path_factory.mktemp("room")
    runs = {}
    for sampler in ("random", "sobol"):
        for seed in (1, 2):
            runs[sampler, seed] = run_luxtrace(binary, ROOM, d / f"{sampler}{seed}.h5", "--photons", "200k",
                                               "--seed", str(seed), "--sampler", sampler)
        # An independent reference with as many photons as seeds 1 and 2 together.
        runs[sampler, 3] = run_luxtrace(binary, ROOM, d / f"{sampler}3.h5", "--photons", "400k", "--seed", "3",
                                        "--sampler", sampler)
    return runs


@pytest.fixture(scope="session")
def target_run(binary, tmp_path_factory):
    """room.toml stopped by a global target of 5 %, reduced every 20k photons (a history of
    a few rows, the same on any machine)."""
    d = tmp_path_factory.mktemp("target")
    return run_luxtrace(binary, ROOM, d / "target.h5", "--photons", "10M", "--target", "0.05",
                        "--report-every-photons", "20k")


@pytest.fixture(scope="session")
def room_variant(binary, tmp_path_factory):
    """Build a changed copy of room.toml and run it: variant(old, new) -> result path."""
    d = tmp_path_factory.mktemp("variant")
    text = open(ROOM).read()

    def make(old, new, seed=5):
        assert old in text
        scene = d / f"room_{abs(hash(new))}.toml"
        scene.write_text(text.replace(old, new))
        return run_luxtrace(binary, scene, d / f"{scene.stem}.h5", "--photons", "20k", "--seed", str(seed))
    return make


# ------------------------------------------------------------------ format 2 by hand
# Two triangles (a unit square split along its diagonal, area 0.5 m^2 each), two bands,
# a 3 x 2 detector of 0.6 m x 0.4 m (cell 0.04 m^2) whose cell i = 2, j = 1 is never hit.
VERTICES = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
TRIANGLES = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
AREA = np.array([0.5, 0.5])
FLUX_LM = 100.0
BANDS = ["R", "G"]
NX, NY = 3, 2
CELL_AREA = 0.6 * 0.4 / (NX * NY)
# Mean arrivals per photon on (triangle, side): triangle 1's back side is never lit.
SURFACE_RATE = np.array([[0.8, 0.1], [0.3, 0.0]])
DETECTOR_RATE = np.array([[0.5, 0.2, 0.1], [0.3, 0.05, 0.0]])


def simulate(seed, photons):
    """Per-photon arrivals: band [N], surface [N,T,2], direct [N,T,2], detector [N,ny,nx]."""
    rng = np.random.default_rng(seed)
    surface = rng.poisson(SURFACE_RATE, size=(photons, 2, 2))
    return {"band": rng.integers(0, len(BANDS), photons), "surface": surface,
            "direct": rng.binomial(surface, 0.6), "detector": rng.poisson(DETECTOR_RATE, size=(photons, NY, NX))}


def write_v2(path, runs, extra_detector_attrs=None):
    """A format-2 result holding the photons of `runs` (a list of (seed, simulate(...))):
    odd and even by each run's own photon index. Every number is computed from the
    per-photon data by its definition."""
    seeds = [s for s, _ in runs]
    band = np.concatenate([r["band"] for _, r in runs])
    surface = np.concatenate([r["surface"] for _, r in runs])
    direct = np.concatenate([r["direct"] for _, r in runs])
    det = np.concatenate([r["detector"] for _, r in runs])
    odd = np.concatenate([np.arange(len(r["band"])) % 2 == 1 for _, r in runs])
    n = len(band)
    e0 = FLUX_LM / n
    B = len(BANDS)
    with h5py.File(path, "w") as f:
        f.attrs.update(format="luxtrace-result", format_version=np.uint64(2), luxtrace_version="hand-made",
                       scene_file="square.toml", scene_name="square", seed=np.uint64(seeds[0]),
                       photons=np.uint64(n), flux_per_photon_lm=e0, total_flux_lm=FLUX_LM, elapsed_s=1.5,
                       stop_reason="photons", sampler="random", replicates=np.uint64(0), maintenance_factor=1.0)
        f.attrs.create("bands", BANDS, dtype=h5py.string_dtype())
        m = f.create_group("mesh")
        m["vertices"], m["triangles"], m["area"] = VERTICES, TRIANGLES, AREA
        m["material"] = np.zeros(2, dtype=np.uint32)
        m.attrs.create("material_names", ["floor"], dtype=h5py.string_dtype())
        g = f.create_group("global")
        per_band = lambda a, sel: np.stack([a[sel & (band == b)].sum(axis=0) for b in range(B)], axis=-1)  # noqa
        everyone = np.ones(n, dtype=bool)
        g["count_odd"] = per_band(surface, odd).astype(np.uint64)
        g["count_even"] = per_band(surface, ~odd).astype(np.uint64)
        g["direct_odd"] = per_band(direct, odd).astype(np.uint64)
        g["direct_even"] = per_band(direct, ~odd).astype(np.uint64)
        g["sumsq"] = per_band(surface ** 2, everyone).astype(np.uint64)
        g["illuminance"] = per_band(surface, everyone) * e0 / AREA[:, None, None]
        g["illuminance_direct"] = per_band(direct, everyone) * e0 / AREA[:, None, None]
        # Standard error of a sum of N independent contributions x_k: sqrt(N var(x)).
        x = surface * e0 / AREA[None, :, None]
        sigma = np.sqrt(n * x.var(axis=0))
        g["sigma_lx"] = sigma
        e_odd = 2 * surface[odd].sum(axis=0) * e0 / AREA[:, None]
        e_even = 2 * surface[~odd].sum(axis=0) * e0 / AREA[:, None]
        g["odd_even_difference_lx"] = e_odd - e_even
        lit = surface.sum(axis=0) > 0
        a = np.where(lit, AREA[:, None], 0.0)
        e = surface.sum(axis=0) * e0 / AREA[:, None]
        mean_a, mean_q = (a * e).sum() / a.sum(), np.sqrt((a * e * e).sum() / a.sum())
        d = np.sqrt((a * (e_odd - e_even) ** 2).sum() / a.sum())
        m2 = np.sqrt((a * sigma ** 2).sum() / a.sum())
        g.attrs.update(sigma_lx=d / 2, odd_even_rms_lx=d, sigma_rel_arithmetic=d / 2 / mean_a,
                       sigma_rel_quadratic=d / 2 / mean_q, mean_arithmetic_lx=mean_a, mean_quadratic_lx=mean_q,
                       moment_sigma_lx=m2, moment_sigma_rel_arithmetic=m2 / mean_a,
                       moment_sigma_rel_quadratic=m2 / mean_q, error_estimator="second_moment",
                       lit_area_m2=a.sum(), photons_escaped=np.uint64(7 * len(runs)),
                       photons_absorbed=np.uint64(n - 7 * len(runs)), photons_truncated=np.uint64(0))
        dg = f.create_group("detectors").create_group("grid")
        count = np.stack([det[band == b].sum(axis=0) for b in range(B)], axis=-1)
        dg["count"] = count.astype(np.uint64)
        dg["sumsq"] = np.stack([(det[band == b] ** 2).sum(axis=0) for b in range(B)], axis=-1).astype(np.uint64)
        dg["value"] = count * e0 / CELL_AREA
        y = np.stack([np.where(band[:, None, None] == b, det, 0) for b in range(B)], axis=-1) * e0 / CELL_AREA
        with np.errstate(invalid="ignore", divide="ignore"):
            dg["sigma_rel"] = np.sqrt(n * y.var(axis=0)) / y.sum(axis=0)
        cells = det.sum(axis=0) * e0 / CELL_AREA  # band sum
        cell_sigma = np.sqrt(n * (det * e0 / CELL_AREA).var(axis=0))
        grid = det.sum(axis=(1, 2)) * e0 / CELL_AREA / (NX * NY)  # each photon's share of the grid mean
        sig9 = np.sqrt((cell_sigma ** 2).mean())
        dg.attrs.update(type="illuminance", units="lx", center=[0.5, 0.5, 0.8], normal=[0.0, 0.0, 1.0],
                        up=[0.0, 1.0, 0.0], size=[0.6, 0.4], cells=np.array([NX, NY], dtype=np.uint64),
                        mean_value=cells.mean(), mean_sigma_rel=np.sqrt(n * grid.var()) / grid.sum(),
                        mean_arithmetic=cells.mean(), mean_quadratic=np.sqrt((cells ** 2).mean()),
                        sigma_rel_arithmetic=sig9 / cells.mean(),
                        sigma_rel_quadratic=sig9 / np.sqrt((cells ** 2).mean()),
                        photons_received=np.uint64((det.sum(axis=(1, 2)) > 0).sum()),
                        error_estimator="independent_photons_eq8", error_dof=np.uint64(0),
                        **(extra_detector_attrs or {}))
        o = f.create_group("observers").create_group("eye")
        o.attrs.update(ugr=17.5, position=[0.5, 0.5, 1.2])
        o["background_cd_m2"] = np.array([12.0])
        h = f.create_group("history")
        h["time_s"], h["photons"] = np.array([0.5, 1.5]), np.array([n // 2, n], dtype=np.uint64)
        h["sigma_rel_global"], h["forecast_s"] = np.array([0.2, 0.14]), np.array([np.nan, np.nan])
    return str(path)


@pytest.fixture
def v2_pair(tmp_path):
    """Two format-2 runs (seeds 11 and 12) and the reference file of their photons together."""
    a, b = (11, simulate(11, 3000)), (12, simulate(12, 5000))
    return (write_v2(tmp_path / "a.h5", [a]), write_v2(tmp_path / "b.h5", [b]),
            write_v2(tmp_path / "both.h5", [a, b]))


@pytest.fixture
def out_dir(tmp_path):
    p = tmp_path / "out"
    p.mkdir()
    return p


def copy(src, dst):
    shutil.copyfile(src, dst)
    return str(dst)


def edited_copy(src_path, dst_path, edit):
    """A copy of the result changed by edit(h5py file) (its seal no longer matches)."""
    shutil.copyfile(src_path, dst_path)
    with h5py.File(dst_path, "r+") as f:
        edit(f)
    return dst_path


# ------------------------------------------------------------------ annual daylight
WEATHER = os.path.join(REPO, "tests", "data", "weather", "chicago.epw")


@pytest.fixture(scope="session")
def annual_run(binary, tmp_path_factory):
    """A year in Chicago (the weather file's Perez skies and 3925 suns) over a grey ground,
    with a grey roof over the left half of an 8 x 2 grid "plane" (2 m x 4 m at 0.5 m) and a
    closed box over its two leftmost columns (no daylight: DA 0 there), and a points grid
    "pts" of four sensors from a .pts file (the last one facing +x under the roof).
    300k photons."""
    d = tmp_path_factory.mktemp("annual")
    (d / "grid.pts").write_text("0 0 0.5 0 0 1\n-1.5 0 0.5 0 0 1\n1.5 0 0.5 0 0 1\n-1.5 0 0.5 1 0 0\n")
    scene = d / "year.toml"
    scene.write_text(f'[site]\nlatitude_deg = 41.98\nlongitude_deg = -87.92\nutc_offset_h = -6\n\n'
                     f'[annual]\nweather = "{WEATHER}"\n\n'
                     '[[material]]\nname = "grey"\nreflectance = 0.3\n\n'
                     '[[shape]]\ntype = "rectangle"\ncenter = [0, 0, 0]\nsize = [6, 6]\nmaterial = "grey"\n\n'
                     '[[shape]]\ntype = "rectangle"\ncenter = [-1.5, 0, 1.0]\nnormal = [0, 0, -1]\nsize = [3, 6]\n'
                     'material = "grey"\n\n'
                     '[[shape]]\ntype = "box"\ncenter = [-1.5, 0, 0.5]\nsize = [1.0, 3.0, 0.8]\nmaterial = "grey"\n\n'
                     '[[detector]]\nname = "plane"\ncenter = [0, 0, 0.5]\nup = [0, 1, 0]\nsize = [4, 2]\n'
                     'cells = [8, 2]\n\n'
                     '[[detector]]\nname = "pts"\ntype = "points"\npoints = "grid.pts"\n')
    return run_luxtrace(binary, scene, d / "year.h5", "--photons", "300k")
