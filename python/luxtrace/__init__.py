"""Reading, combining, exporting and drawing luxtrace results (the role of openmc.StatePoint).

    import luxtrace
    r = luxtrace.open("office.h5")              # a result or checkpoint, format 1 or 2
    desk = r.detectors["desk"]                  # values, errors, counts, every attribute
    both = luxtrace.combine([r, luxtrace.open("office-seed2.h5")])
    both.detectors["desk"].to_csv("desk.csv")
    luxtrace.write(both, "office-merged.h5")    # a sealed result: luxtrace info/render read it

Annual daylight: ``r.annual`` (``luxtrace.annual``: the hours, each grid's hourly values and
metrics with their errors), pictures ``luxtrace.annual_plot``.

Radiance sensor grids: ``luxtrace.sensor_table(r.detector("grid"))`` or
``luxtrace.read_sensor_table("office.grid.txt")``: positions, E and sigma_E per sensor.

Pictures: ``luxtrace.plot`` (matplotlib), also ``python3 -m luxtrace.plot RESULT --detector NAME``.
Needs numpy and h5py (Debian: python3-numpy, python3-h5py); pictures need matplotlib.
"""
from .combine import MismatchError, combine
from .result_file import write
from .sensor_table import SensorTable, read_sensor_table, sensor_table, sensor_table_path
from .result import (BACK, FRONT, NEWEST_FORMAT_VERSION, Detector, Group, History, Mesh, Result, ResultError,
                     SurfaceMap, TargetHistory, check_seal, open)
from . import annual  # noqa: F401  (luxtrace.annual without an import of its own)
from ._version import __version__  # noqa: F401  (luxtrace's, CMakeLists.txt's project())

__all__ = ["open", "combine", "write", "check_seal", "Result", "Mesh", "SurfaceMap", "Detector", "Group", "History",
           "TargetHistory", "ResultError", "MismatchError", "FRONT", "BACK", "NEWEST_FORMAT_VERSION", "SensorTable",
           "sensor_table", "read_sensor_table", "sensor_table_path"]
