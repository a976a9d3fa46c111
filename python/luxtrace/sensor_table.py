"""Per-sensor illuminance of a ``points`` detector (a Radiance .pts grid): from a result's
detector, or from the plain table ``luxtrace run`` writes beside the result
(docs/REFERENCE.md §4, "Sensor tables"). Both give the same numbers: the table holds the
result's band-summed cells and their errors, printed to 9 significant digits.

    r = luxtrace.open("office.h5")
    t = luxtrace.sensor_table(r.detector("grid"))              # from the result
    t = luxtrace.read_sensor_table("office.grid.txt")          # from the table beside it
    t.positions, t.E_lx, t.sigma_E_lx                          # [n,3] m, [n] lx, [n] lx
"""
import os
from collections import namedtuple

import numpy as np

#: positions [n,3] (m, as read from the .pts file), E_lx [n] (illuminance summed over the
#: bands) and sigma_E_lx [n] (its one-sigma standard error; NaN where no photon arrived),
#: one row per sensor in the .pts file's order.
SensorTable = namedtuple("SensorTable", "positions E_lx sigma_E_lx")


def sensor_table(detector):
    """The :class:`SensorTable` of a points detector of a result (``result.detector(name)``),
    its band sum as ``Detector.band_sum`` gives it. ValueError for any other detector."""
    if not detector.is_points:
        raise ValueError(f"detector {detector.name} is of type {detector.type}, not points: it has no sensors")
    value, rel = detector.band_sum()
    e = np.asarray(value, dtype=float)[0]
    return SensorTable(np.asarray(detector.positions, dtype=float), e, e * np.asarray(rel, dtype=float)[0])


def sensor_table_path(result_path, detector_name):
    """Where ``luxtrace run`` writes a points detector's table: beside the result, the
    result's name without its extension, then ``.NAME.txt`` (office.h5 -> office.grid.txt)."""
    folder, name = os.path.split(os.fspath(result_path))
    return os.path.join(folder, os.path.splitext(name)[0] + "." + detector_name + ".txt")


def read_sensor_table(path):
    """The :class:`SensorTable` in a table ``luxtrace run`` wrote ('#' lines skipped, five
    columns x y z E sigma_E). ValueError for a file that is not such a table."""
    rows = np.loadtxt(path, dtype=float, comments="#", ndmin=2)
    if rows.shape[1] != 5:
        raise ValueError(f"{path}: expected five columns x y z E sigma_E, found {rows.shape[1]}")
    return SensorTable(rows[:, 0:3], rows[:, 3], rows[:, 4])
