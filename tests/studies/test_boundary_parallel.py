"""Boundaries on the study's processes (issue 26.3): the samples of a start search line and
the grid map under a plot are batches of independent evaluations that go through
:func:`propwhirl.studies.execution.map_analyses` (processes, a Dask cluster, progress); the
traced curves do not depend on the back end."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.app import cli
from propwhirl.cases.registry import case_model
from propwhirl.studies import boundary as B
from propwhirl.studies import execution
from propwhirl.studies.continuation import ContinuationOptions

PLANE = (("propeller.f_theta", "propeller.f_psi"), (3.0, 3.0), (12.0, 12.0))


def spy_on(monkeypatch, run_processes: bool):
    """Record every batch map_analyses runs: (number of tasks, processes, desc); run it on
    the processes asked for, or (run_processes False: the routing only) in this process."""
    seen = []
    real = execution.map_analyses

    def spy(func, tasks, processes=1, **kw):
        seen.append((len(tasks), processes, kw.get("desc")))
        return real(func, tasks, processes if run_processes else 1, **kw)

    monkeypatch.setattr(execution, "map_analyses", spy)
    return seen


@pytest.fixture
def batches(monkeypatch):
    return spy_on(monkeypatch, True)


@pytest.fixture
def routed(monkeypatch):
    return spy_on(monkeypatch, False)


def test_the_start_search_is_one_batch_on_the_processes(batches):
    model = case_model("isolated-propeller")
    serial = B.neutral_curve(model, *PLANE, V=220.0)
    n_serial = len(batches)
    ticks = []
    par = B.neutral_curve(model, *PLANE, V=220.0, processes=2,
                          progress=lambda done, total: ticks.append((done, total)))
    n_search = ContinuationOptions().n_search
    assert batches[n_serial:] == [(n_search, 2, "boundary points")]   # the first line's samples
    assert ticks[-1] == (n_search, n_search)
    assert par.evaluations == serial.evaluations
    assert len(par.curves) == len(serial.curves) == 1
    np.testing.assert_array_equal(par.curves[0], serial.curves[0])
    assert par.info == serial.info


def test_the_grid_map_is_one_batch_and_equals_the_serial_one(routed):
    model = case_model("isolated-propeller")
    b = B.neutral_curve(model, *PLANE, V=220.0)
    serial = B.grid_map(B.level_of(b, model), PLANE[1], PLANE[2], 5)
    par = B.grid_map(B.level_of(b, model, processes=2), PLANE[1], PLANE[2], 5)
    assert (25, 2, "grid map") in routed
    np.testing.assert_array_equal(par.values, serial.values)
    one_by_one = B.grid_map(lambda p: B.level_of(b, model)(p), PLANE[1], PLANE[2], 5)
    np.testing.assert_array_equal(one_by_one.values, serial.values)


def test_the_contour_start_search_runs_its_analyses_as_one_batch(routed):
    model = case_model("isolated-propeller")
    speeds = np.arange(100.0, 351.0, 50.0)
    b = B.speed_contour(model, *PLANE, 240.0, speeds=speeds, processes=2,
                        options=ContinuationOptions(tol=2e-3, max_points=4))
    n_search = ContinuationOptions().n_search
    assert routed[0] == (n_search, 2, "boundary points")
    assert b.evaluations >= n_search


def test_boundary_command_takes_the_execution_options(capsys, routed):
    args = ["boundary", "isolated-propeller", "--params", "propeller.f_theta", "propeller.f_psi",
            "--speed", "220", "--bounds", "3", "12", "3", "12", "--quiet"]
    assert cli.main(args + ["--processes", "0"]) == 2
    assert "--processes" in capsys.readouterr().err
    assert cli.main(args + ["--resume"]) == 2            # keeps no partial results
    assert "unrecognized arguments: --resume" in capsys.readouterr().err
    assert cli.main(args + ["--processes", "2"]) == 0
    assert "neutral-stability curve at V = 220 m/s" in capsys.readouterr().out
    assert routed[0][1] == 2
