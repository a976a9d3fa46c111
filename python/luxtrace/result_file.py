"""Writing a Result (above all a combination of seeds) as a luxtrace result file.

The layout is SPEC §4's, in the result's own format_version: format 1 stores the maps
[T,B] (the front side of the Result's [T,2,B], where format 1 keeps everything), format 2
[T,2,B] with sumsq and sigma_lx. Like the binary, the file is written beside its target
and renamed, and sealed: a 512-byte user block holding the CRC-32 and length of the rest,
so ``luxtrace info``, ``render`` and ``export-xdmf`` read it like one of theirs.
"""
import os

import h5py
import numpy as np

from .result import FRONT, crc32_and_length

_SEAL_BYTES = 512
# Integer attributes the binary writes as uint64 (every other number is float64). Values
# that are integers already (read from a file as such, or counted here) stay uint64 too,
# so attributes added to the binary later keep their type without a change here.
_U64 = {"format_version", "seed", "ranks", "threads_per_rank", "photons", "replicates", "replicate_photons",
        "photon_layout", "reductions", "maintenance_factor_uniform", "seeds", "photons_escaped",
        "photons_absorbed", "photons_truncated", "cells", "photons_received", "error_dof", "replicate_total",
        "budget", "layout_size", "triangles", "bands"}


def _is_integer(v):
    a = np.asarray(v)
    return a.dtype.kind in "iu" and not isinstance(v, bool)


def _set_attrs(obj, attrs):
    for k, v in attrs.items():
        if isinstance(v, str):
            obj.attrs[k] = v
        elif isinstance(v, (list, tuple)) and v and all(isinstance(x, str) for x in v):
            obj.attrs.create(k, list(v), dtype=h5py.string_dtype())
        elif k in _U64 or _is_integer(v):
            obj.attrs[k] = np.asarray(v, dtype=np.uint64)
        else:
            obj.attrs[k] = np.asarray(v, dtype=float)


def _front(a):
    return np.ascontiguousarray(a[:, FRONT])


def write(result, path):
    """Write ``result`` to ``path`` as a sealed luxtrace result file; returns the path.

    A combination has no single run, so the attributes of one run are written as what
    they are for it: ``ranks`` and ``threads_per_rank`` 0, ``stop_reason`` "combined",
    ``elapsed_s`` the sum over the runs, ``seeds`` and ``combined_from`` naming the runs;
    its /history has no rows.
    """
    path = os.fspath(path)
    tmp = os.path.join(os.path.dirname(path) or ".", f".{os.path.basename(path)}.tmp.{os.getpid()}")
    attrs = dict(result.attrs)
    attrs["format"] = "luxtrace-result"
    attrs.setdefault("ranks", 0)
    attrs.setdefault("threads_per_rank", 0)
    attrs.setdefault("luxtrace_version", "several")
    attrs.setdefault("scene_name", "")
    v = result.format_version
    try:
        with h5py.File(tmp, "w", userblock_size=_SEAL_BYTES, libver=("v108", "latest")) as f:
            _set_attrs(f, attrs)
            m = f.create_group("mesh")
            m["vertices"] = result.mesh.vertices
            m["triangles"] = result.mesh.triangles.astype(np.uint32)
            m["area"] = result.mesh.area_m2
            m["material"] = result.mesh.material.astype(np.uint32)
            m.attrs.create("material_names", result.mesh.material_names, dtype=h5py.string_dtype())
            m.create_dataset("material_names", data=result.mesh.material_names, dtype=h5py.string_dtype())
            g = f.create_group("global")
            for k, a in result.surface.datasets.items():
                if v == 1:
                    if k == "sigma_lx":
                        continue  # format 1 has no second moment
                    a = _front(a)
                g[k] = a
            _set_attrs(g, result.surface.attrs)
            dets = f.create_group("detectors")
            for name, d in result.detectors.items():
                dg = dets.create_group(name)
                for k, a in d.datasets.items():
                    dg[k] = a
                _set_attrs(dg, d.attrs)
                for area, t in d.task_areas.items():
                    _set_attrs(dg.require_group("task_areas").create_group(area), t.attrs)
            for name, o in result.observers.items():
                og = f.require_group("observers").create_group(name)
                for k, a in o.datasets.items():
                    og[k] = a
                _set_attrs(og, o.attrs)
            h = f.create_group("history")
            hist = result.history
            if hist is not None:
                for k, a in hist.datasets.items():
                    h[k] = a
                _set_attrs(h, hist.attrs)
            else:
                for k, dtype in (("time_s", float), ("photons", np.uint64), ("sigma_rel_global", float),
                                 ("forecast_s", float)):
                    h[k] = np.zeros(0, dtype=dtype)
        _seal(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def _seal(path):
    """The seal of SPEC §4: 'luxtrace-seal v1 crc32 XXXXXXXX length N\\n' in the first 512
    bytes (zero-padded), over everything after them."""
    with open(path, "r+b") as f:
        f.seek(_SEAL_BYTES)
        crc, length = crc32_and_length(f)
        line = f"luxtrace-seal v1 crc32 {crc:08x} length {length}\n".encode()
        f.seek(0)
        f.write(line + bytes(_SEAL_BYTES - len(line)))
