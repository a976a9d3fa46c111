#!/usr/bin/python3
"""Detector pictures of a luxtrace result, drawn by the luxtrace Python package
(python/luxtrace, matplotlib; Debian's /usr/bin/python3 has what it needs).

usage: /usr/bin/python3 scripts/plot_detector.py RESULT.h5 --detector NAME... [--cell I,J]
           [--scene LIGHT_SCENE] [-o DIR] [--convergence]

Writes NAME_value.png (value map with colour bar), NAME_error.png (relative error per
cell, eq. 8, cells without hits marked), NAME_error_hist.png (histogram of those errors
with the eq. 9 values) and NAME_sections.png (row and column through cell I,J, default
the brightest, with +-1 sigma bands), and for a daylight_factor detector NAME_df.png (the
daylight factor map in %, with its median, 95 % value and EN 17037 verdict), into DIR
(default: beside the result); with --scene, the detectors as that [[light_scene]] of the
run has them. The same as
`python3 -m luxtrace.plot` once the package is installed.
"""
import os
import sys

# The package of this checkout, also when another version of it is installed.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import luxtrace.plot  # noqa: E402


if __name__ == "__main__":
    sys.exit(luxtrace.plot.main(prog="plot_detector.py"))
