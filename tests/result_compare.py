"""Compares two luxtrace results: every dataset and attribute bit for bit, except what
records how a run went rather than what it computed (timings, the reductions' count and
cost, the history's times and forecasts). Used where a result written after a failure
must equal the one an undisturbed run wrote (tests/write_fault_test.sh, issue 35).

Usage: /usr/bin/python3 result_compare.py A.h5 B.h5   (exit 0 equal, 1 different)
"""
import sys

import h5py
import numpy as np

# Root attributes of the run's accounting (docs/REFERENCE.md §4): they differ between any
# two runs of the same photons, or with the ranks and threads that traced them.
RUN_ACCOUNTING = {"ranks", "threads_per_rank", "elapsed_s", "load_s", "bvh_build_s", "reductions", "reduction_stall_s", "reduction_wait_s",
                  "reduction_work_s", "reduction_message_words", "reduction_message_bytes", "gather_s",
                  "tracing_busy"}
# History columns of wall time: when each reduction came and what was forecast from the rate.
TIMED_HISTORY = {"/history/time_s", "/history/forecast_s", "/history/target_forecast_s",
                 "/history/target_forecast_photons"}


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        return bool(np.array_equal(np.atleast_1d(a).view(np.uint8), np.atleast_1d(b).view(np.uint8)))  # bits, NaN too
    return bool(np.array_equal(a, b))


def objects(f):
    names = ["/"]
    f.visit(lambda n: names.append("/" + n))
    return names


def main(pa, pb):
    differ = []
    with h5py.File(pa, "r") as a, h5py.File(pb, "r") as b:
        na, nb = objects(a), objects(b)
        if na != nb:
            differ.append(f"objects: {sorted(set(na) ^ set(nb))}")
        for name in (n for n in na if n in b):
            oa, ob = a[name], b[name]
            if set(oa.attrs) != set(ob.attrs):
                differ.append(f"{name}: attributes {sorted(set(oa.attrs) ^ set(ob.attrs))}")
            for k in oa.attrs:
                if name == "/" and k in RUN_ACCOUNTING or k not in ob.attrs:
                    continue
                if not same(oa.attrs[k], ob.attrs[k]):
                    differ.append(f"{name}@{k}")
            if isinstance(oa, h5py.Dataset) and name not in TIMED_HISTORY:
                if not same(oa[()], ob[()]):
                    differ.append(name)
    for d in differ:
        print("differs:", d)
    print(f"{len(differ)} difference(s)")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
