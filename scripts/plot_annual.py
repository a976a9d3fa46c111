#!/usr/bin/python3
"""Annual daylight pictures of a luxtrace result, drawn by the luxtrace Python package
(python/luxtrace, matplotlib; Debian's /usr/bin/python3 has what it needs).

usage: /usr/bin/python3 scripts/plot_annual.py RESULT.h5 [--grid NAME]... [--sensor C] [-o DIR]

Writes, per sensor grid of the run's [annual] (default: every grid), NAME_da.png (DA300
per sensor with the 50 % line of sDA300/50%), NAME_ase.png (hours of direct sun >= 1000 lx
per sensor with the 250 h line of ASE1000,250h) and NAME_hours.png (sensor C's illuminance,
hour of the day x day of the year; default the sensor with the median DA) into DIR
(default: beside the result). The same as `python3 -m luxtrace.annual_plot` once the
package is installed; docs/REFERENCE.md §1.5.
"""
import os
import sys

# The package of this checkout, also when another version of it is installed.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import luxtrace.annual_plot  # noqa: E402


if __name__ == "__main__":
    sys.exit(luxtrace.annual_plot.main(prog="plot_annual.py"))
