"""Reads a Ladybug Tools annual daylight results folder step by step as
honeybee-radiance-postprocess does, and prints what it read (for ladybug_results_test).

The steps mirror, in that package's module results/results.py:
  _ResultsFolder.__init__ -> _get_study_info, the grids_info setter, _get_grids_info,
      _get_sun_up_hours, _get_sun_up_hours_mask, _get_light_paths, _get_grid_states;
  Results._get_valid_states, _filter_grid_states (no states given: each light path's
      default state 0), _state_identifier, _get_file, _load_array and the static branch
      of _array_from_states (the sum over the grid's light paths).
The ladybug library's AnalysisPeriod().hoys (the study hours when there is no
study_info.json) is replaced by its value for an hourly 365-day year: 0.0 ... 8759.0.

Usage: ladybug_results_reader.py FOLDER. Prints, a line each:
  timestep N
  study_hours N
  sun_up_hours H H ...            (as the reader holds them: whole hours for timestep 1)
  sun_up_hours_mask_size N
  light_paths P ...
  valid_states P S ...            (per light path: its valid state numbers)
  grid FULL_ID keys K ... | name NAME
  array FULL_ID RES_TYPE FILE DTYPE C_ORDER ROWS COLS V V ...   (every value, repr)
Any step that fails the way the package would fail raises.
"""
import json
import sys
from pathlib import Path

import numpy as np

STATIC = '__static_apertures__'


def study_info(folder):
    study_info_file = Path(folder).joinpath('study_info.json')
    if study_info_file.exists():
        with open(study_info_file) as file:
            info = json.load(file)
        if info['timestep'] == 1:
            info['study_hours'] = list(map(int, info['study_hours']))
    else:
        info = {'timestep': 1, 'study_hours': [float(h) for h in range(8760)]}
    return info['timestep'], info['study_hours']


def grids_info(folder):
    with open(Path(folder, 'grids_info.json')) as data_f:
        grids = json.load(data_f)
    assert isinstance(grids, list)
    for grid_info in grids:
        assert isinstance(grid_info, dict)
        if not grid_info.get('light_path', None):
            grid_info['light_path'] = [[STATIC]]
    return grids


def sun_up_hours(folder, timestep):
    hours = np.loadtxt(Path(folder, 'sun-up-hours.txt'), dtype=float).tolist()
    if timestep == 1:
        hours = list(map(int, hours))
    assert isinstance(hours, list)
    return hours


def light_paths(grids):
    lp = []
    for grid_info in grids:
        paths = grid_info['light_path']
        for light_path in paths:
            for elem in light_path:
                if elem in lp:
                    continue
                if elem == STATIC:
                    lp.insert(0, elem)
                else:
                    lp.append(elem)
        if not paths and STATIC not in lp:
            lp.insert(0, STATIC)
    return lp


def grid_states(folder):
    info = Path(folder, 'grid_states.json')
    if info.is_file():
        with open(info) as data_f:
            return json.load(data_f)
    return {}


def valid_states(paths, states):
    valid = {}
    if STATIC in paths:
        valid[STATIC] = [0]
    for grid_paths in states.values():
        for light_path, s in grid_paths.items():
            if light_path not in valid:
                valid[light_path] = list(range(len(s)))
    return valid


def state_identifier(valid, states, grid_id, light_path, state=0):
    if state in valid[light_path]:
        if light_path == STATIC:
            return 'default'
        return states[grid_id][light_path][state]
    raise ValueError('state %s of %s is not valid' % (state, light_path))


def load_array(folder, valid, states, grid_info, light_path, res_type):
    grid_id = grid_info['full_id']
    ident = state_identifier(valid, states, grid_id, light_path)
    file = Path(folder, light_path, ident, res_type, grid_id + '.npy')
    if not file.is_file():
        raise FileNotFoundError('File %s not found in the results folder.' % file)
    return file, np.load(file)


def grid_light_paths(grid_info):
    paths = []
    for lp in grid_info['light_path']:
        for _lp in lp:
            if not (_lp == STATIC and len(lp) > 1):
                paths.append(_lp)
    return paths


def main(folder):
    timestep, study_hours = study_info(folder)
    grids = grids_info(folder)
    hours = sun_up_hours(folder, timestep)
    mask = np.where(np.isin(np.array(study_hours), np.array(hours)))[0]
    paths = light_paths(grids)
    states = grid_states(folder)
    valid = valid_states(paths, states)
    print('timestep', timestep)
    print('study_hours', len(study_hours))
    print('sun_up_hours', *hours)
    print('sun_up_hours_mask_size', len(mask))
    print('light_paths', *paths)
    for path, s in valid.items():
        print('valid_states', path, *s)
    for grid_info in grids:
        print('grid', grid_info['full_id'], 'keys', *grid_info.keys(), '| name', grid_info['name'])
        for res_type in ('total', 'direct'):
            arrays = []
            for light_path in grid_light_paths(grid_info):
                file, array = load_array(folder, valid, states, grid_info, light_path, res_type)
                arrays.append(array)
                rel = file.relative_to(Path(folder)).as_posix()
                print('array', grid_info['full_id'], res_type, rel, array.dtype.name,
                      bool(array.flags['C_CONTIGUOUS']), *array.shape,
                      *(repr(float(v)) for v in array.ravel()))
            summed = np.sum(np.stack(arrays, axis=0), axis=0)
            assert summed.shape == (grid_info['count'], len(hours)), summed.shape


if __name__ == '__main__':
    main(sys.argv[1])
