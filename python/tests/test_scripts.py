"""The scripts in scripts/ read results through this checkout's package: they run from
any directory without PYTHONPATH, and a different luxtrace package earlier on the path
(an installed one) is not the one they import."""
import os
import subprocess
import sys

from conftest import REPO


def run_script(name, args, tmp_path):
    decoy = tmp_path / "decoy" / "luxtrace"
    decoy.mkdir(parents=True)
    (decoy / "__init__.py").write_text('raise SystemExit("imported a luxtrace package from elsewhere")\n')
    env = dict(os.environ, PYTHONPATH=str(decoy.parent))
    return subprocess.run([sys.executable, os.path.join(REPO, "scripts", name), *args], cwd=tmp_path, env=env,
                          capture_output=True, text=True)


def test_forecast_accuracy(target_run, tmp_path):
    p = run_script("forecast_accuracy.py", [target_run], tmp_path)
    assert p.returncode == 0, p.stderr
    first = p.stdout.splitlines()[0]
    assert "target global rel(quad), stopped by target global rel(quad)" in first
    assert "reductions" in first and len(p.stdout.splitlines()) == 5, "a line per fraction of the run"


def test_plot_detector(room_runs, tmp_path):
    out = tmp_path / "pictures"
    p = run_script("plot_detector.py", [room_runs["random", 1], "--detector", "table", "-o", str(out)], tmp_path)
    assert p.returncode == 0, p.stderr
    assert sorted(os.listdir(out)) == ["table_error.png", "table_error_hist.png", "table_sections.png",
                                       "table_value.png"]


def test_plot_annual(annual_run, tmp_path):
    out = tmp_path / "pictures"
    p = run_script("plot_annual.py", [annual_run, "--grid", "pts", "-o", str(out)], tmp_path)
    assert p.returncode == 0, p.stderr
    assert sorted(os.listdir(out)) == ["pts_ase.png", "pts_da.png", "pts_hours.png"]
