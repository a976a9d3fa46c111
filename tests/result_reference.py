#!/usr/bin/python3
"""Compares the result layout documented in docs/REFERENCE.md section 4 with HDF5 files.

    result_reference.py REFERENCE.md FILE.h5...

Every group, dataset and attribute in the files must be documented, and every documented
one must occur in at least one of the files (so give a result and a checkpoint of a run
with a sobol sampler, targets, every detector type, a task area and an observer). The
groups named by the scene are matched as /detectors/NAME, /detectors/NAME/task_areas/AREA
and /observers/NAME. Exit 1 listing the differences. The files are read with h5py, not
through python/luxtrace: the raw layout is what is checked.
"""
import re
import sys

import h5py


def documented(reference):
    """{(object, name, kind)} from the tables of section 4: headings "### `/path`", rows
    "| `name` | kind | ..."."""
    out, in_result, obj = set(), False, None
    with open(reference, encoding="utf-8") as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("## "):
                in_result = line.startswith("## 4.")
            if not in_result:
                continue
            m = re.match(r"### `(/[^`]*)`", line)
            if m:
                obj = m.group(1)
                continue
            m = re.match(r"\| `([^`]+)` \| (attribute|dataset|group) \|", line)
            if m and obj is not None:
                out.add((obj, m.group(1), m.group(2)))
    return out


def written(path):
    out = set()

    def generic(name):
        parts = name.split("/")
        if len(parts) >= 3 and parts[1] in ("detectors", "observers", "light_groups", "light_scenes"):
            parts[2] = "NAME"
        if len(parts) >= 4 and parts[1] == "annual" and parts[2] == "detectors":
            parts[3] = "NAME"
        if len(parts) >= 5 and parts[1] == "detectors" and parts[3] == "task_areas":
            parts[4] = "AREA"
        # A light group's or light scene's detectors and observers: DET, OBS, AREA.
        if len(parts) >= 5 and parts[1] in ("light_groups", "light_scenes"):
            if parts[3] == "detectors":
                parts[4] = "DET"
                if len(parts) >= 7 and parts[5] == "task_areas":
                    parts[6] = "AREA"
            elif parts[3] == "observers":
                parts[4] = "OBS"
        return "/".join(parts) or "/"

    # Groups named by the scene are documented as NAME / AREA tables, not as rows.
    named_by_scene = ("/detectors", "/observers", "/annual/detectors", "/detectors/NAME/task_areas", "/light_groups", "/light_scenes",
                      "/light_groups/NAME/detectors", "/light_scenes/NAME/detectors",
                      "/light_scenes/NAME/observers", "/light_scenes/NAME/detectors/DET/task_areas")

    def attrs(obj, where):
        for a in obj.attrs:
            out.add((where, a, "attribute"))

    with h5py.File(path, "r") as f:
        attrs(f, "/")

        def visit(name, item):
            full = "/" + name
            parent, _, leaf = full.rpartition("/")
            parent = generic(parent or "/")
            if isinstance(item, h5py.Dataset):
                out.add((parent, leaf, "dataset"))
            elif parent not in named_by_scene:
                out.add((parent, leaf, "group"))
            attrs(item, generic(full))

        f.visititems(visit)
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    doc = documented(sys.argv[1])
    if len(doc) < 50:
        sys.exit(f"{sys.argv[1]}: found only {len(doc)} documented result entries")
    seen = set()
    for p in sys.argv[2:]:
        seen |= written(p)
    missing = sorted(seen - doc)
    unused = sorted(doc - seen)
    for o, n, k in missing:
        print(f"not documented in docs/REFERENCE.md section 4: {k} {n} of {o}")
    for o, n, k in unused:
        print(f"documented but not written by these runs: {k} {n} of {o}")
    print(f"{len(doc)} documented entries, {len(seen)} written")
    sys.exit(1 if missing or unused else 0)


if __name__ == "__main__":
    main()
