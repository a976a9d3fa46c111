"""CSV export of a detector: one row per cell, in the file's numbers."""
import csv

import numpy as np
import pytest

import luxtrace
from conftest import simulate, write_v2


def test_csv_rows_hold_each_cell(room_runs, tmp_path):
    t = luxtrace.open(room_runs["random", 1]).detectors["table"]
    path = t.to_csv(tmp_path / "table.csv", ["Y"])
    rows = list(csv.DictReader(open(path)))
    assert len(rows) == 80
    by_cell = {(int(r["i"]), int(r["j"])): r for r in rows}
    for (i, j), r in by_cell.items():
        assert float(r["value_Y [lx]"]) == t.value[j, i, 0]
        assert int(r["count_Y"]) == t.count[j, i, 0]
        s = float(r["sigma_rel_Y"])
        assert s == t.sigma_rel[j, i, 0] or (np.isnan(s) and np.isnan(t.sigma_rel[j, i, 0]))
    # Cell (9, 7): the corner at +u, +up: centre (2.8 + 0.45, 1.5 + 0.35, 0.75).
    r = by_cell[9, 7]
    assert [float(r[k]) for k in ("x_m", "y_m", "z_m")] == pytest.approx([3.25, 1.85, 0.75])
    assert (float(r["u_m"]), float(r["v_m"])) == pytest.approx((0.45, 0.35))


def test_csv_of_several_bands_has_the_sum(tmp_path):
    d = luxtrace.open(write_v2(tmp_path / "v2.h5", [(1, simulate(1, 500))])).detectors["grid"]
    rows = list(csv.DictReader(open(d.to_csv(tmp_path / "grid.csv", ["R", "G"]))))
    value, _ = d.band_sum()
    for r in rows:
        i, j = int(r["i"]), int(r["j"])
        assert float(r["value_sum [lx]"]) == pytest.approx(float(r["value_R [lx]"]) + float(r["value_G [lx]"]))
        assert float(r["value_sum [lx]"]) == pytest.approx(value[j, i])
