"""The sensor tables luxtrace run writes beside a result with points detectors: read back with
numpy they are the result's band-summed sensors in the .pts order, and the package gives the same
from the result itself."""
import numpy as np
import pytest

import luxtrace
from conftest import points_scene, run_luxtrace


@pytest.fixture(scope="module")
def sensor_run(binary, tmp_path_factory):
    """Nine upward sensors in a scrambled order under a point light 2 m above (one sensor far
    out, where few photons arrive), 200k photons; (result path, positions as written)."""
    d = tmp_path_factory.mktemp("sensors")
    xy = [((5 * k) % 9 % 3 * 0.5 - 0.5, (5 * k) % 9 // 3 * 0.5 - 0.5) for k in range(9)]
    xy[4] = (1.9, 1.9)
    scene = points_scene(d, "".join(f"{x} {y} 0.8 0 0 1\n" for x, y in xy), (0, 0, 2))
    return run_luxtrace(binary, scene, d / "run.h5", "--photons", "200k"), np.array([[x, y, 0.8] for x, y in xy])


def test_table_beside_the_result_holds_the_results_sensors(sensor_run):
    path, positions = sensor_run
    table_path = luxtrace.sensor_table_path(path, "sensors")
    assert table_path.endswith("run.sensors.txt")
    table = luxtrace.read_sensor_table(table_path)
    r = luxtrace.open(path)
    mine = r.detector("sensors").sensor_table()
    np.testing.assert_array_equal(table.positions, positions)
    np.testing.assert_array_equal(mine.positions, positions)
    np.testing.assert_allclose(table.E_lx, mine.E_lx, rtol=1e-8)
    np.testing.assert_allclose(table.sigma_E_lx, mine.sigma_E_lx, rtol=1e-8)
    # One band: E and sigma_E are the stored value and value x sigma_rel.
    d = r.detector("sensors")
    np.testing.assert_array_equal(mine.E_lx, d.value[0, :, 0])
    np.testing.assert_array_equal(mine.sigma_E_lx, d.sigma[0, :, 0])
    with open(table_path) as f:
        header = [line for line in f if line.startswith("#")]
    assert any(f"photons traced: {r.photons}" in line for line in header), header


def test_sensor_table_of_a_grid_detector_is_refused(room_runs):
    with pytest.raises(ValueError, match="not points"):
        luxtrace.open(room_runs["random", 1]).detector("table").sensor_table()


def test_reading_a_file_of_other_columns_is_refused(tmp_path):
    (tmp_path / "four.txt").write_text("# x y z E\n0 0 0 1\n")
    with pytest.raises(ValueError, match="five columns"):
        luxtrace.read_sensor_table(tmp_path / "four.txt")
