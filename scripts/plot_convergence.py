#!/usr/bin/python3
"""Convergence (and detector) figures of a luxtrace result, drawn by the luxtrace Python
package (python/luxtrace; Debian's /usr/bin/python3 with python3-h5py and
python3-matplotlib; Agg backend, no display needed).

usage: /usr/bin/python3 scripts/plot_convergence.py RESULT.h5 [-o DIR]
           [--detector NAME]... [--cell I,J]

Writes into DIR (default: the result's folder):
  convergence.png          error against wall time, log-log, one panel per target of the
                           run (/history/target_value) with its goal, the forecast made at
                           the last reduction and the time the goal was met; the global
                           map's relative error (eq. 5, quadratic) is drawn in every
                           relative-error panel
  NAME_value.png, NAME_error.png, NAME_error_hist.png, NAME_sections.png
                           per --detector: the pictures of luxtrace.plot (as
                           scripts/plot_detector.py draws them)
"""
import os
import sys

# The package of this checkout, also when another version of it is installed.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import luxtrace.plot  # noqa: E402


if __name__ == "__main__":
    sys.exit(luxtrace.plot.main(["--convergence"] + sys.argv[1:], prog="plot_convergence.py"))
