"""Execution of independent analyses (issue 12, item 5): serial and local processes give the
same list; failing points are recorded; finished points are kept in an atomically rewritten
partial-results file; an interrupted run resumes to the same result."""
from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest

from propwhirl.studies import execution as X
from propwhirl.studies.execution import Checkpoint, Interrupted, TaskError, map_analyses
from propwhirl.validate import InputError


def square_or_fail(x: float) -> dict:
    """A picklable task: {"x", "y"}; x < 0 is an invalid model."""
    if x < 0:
        raise InputError(f"x = {x!r} is invalid: must be >= 0")
    return {"x": x, "y": x * x, "root": math.sqrt(x), "label": f"p{x:g}"}


def blas_threads(_: object) -> list[int]:
    from threadpoolctl import threadpool_info

    return [d["num_threads"] for d in threadpool_info() if d.get("user_api") == "blas"]


TASKS = [0.0, 1.5, 2.0, 3.25, 4.0, 7.0]


def test_serial_and_processes_give_the_same_list_in_order():
    serial = map_analyses(square_or_fail, TASKS)
    pooled = map_analyses(square_or_fail, TASKS, processes=2)
    assert serial == pooled == [square_or_fail(x) for x in TASKS]


def test_pool_workers_run_blas_at_one_thread():
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one CPU: no pool")
    threads = map_analyses(blas_threads, [0, 1], processes=2)
    assert all(t and set(t) == {1} for t in threads), threads


def test_a_failing_point_is_recorded_and_the_others_go_on():
    tasks = [1.0, -2.0, 3.0]
    for processes in (1, 2):
        out = map_analyses(square_or_fail, tasks, processes, errors="record")
        assert out[0] == square_or_fail(1.0) and out[2] == square_or_fail(3.0)
        assert out[1] == TaskError("InputError", "x = -2.0 is invalid: must be >= 0")
        assert X.failures(out) == [(1, out[1])]
    with pytest.raises(InputError, match="x = -2.0"):
        map_analyses(square_or_fail, tasks)


def test_progress_is_reported_after_every_point():
    seen = []
    map_analyses(square_or_fail, TASKS, progress=lambda done, total: seen.append((done, total)))
    assert seen == [(k, len(TASKS)) for k in range(len(TASKS) + 1)]


def _interrupt_after(k: int):
    def report(done, total):
        if done == k:
            raise KeyboardInterrupt
    return report


@pytest.mark.parametrize("processes", [1, 2])
def test_an_interrupted_run_keeps_its_points_and_resumes_to_the_same_result(tmp_path, processes):
    path = tmp_path / "study.json.partial"
    full = map_analyses(square_or_fail, TASKS + [-1.0], errors="record")
    cp = Checkpoint(path, fingerprint="squares", interval=60.0)
    with pytest.raises(Interrupted) as info:
        map_analyses(square_or_fail, TASKS + [-1.0], processes, errors="record", checkpoint=cp,
                     progress=_interrupt_after(3))
    assert isinstance(info.value, KeyboardInterrupt)
    assert (info.value.done, info.value.total, info.value.path) == (3, 7, path)
    assert "3 of 7 points finished" in str(info.value) and str(path) in str(info.value)
    data = json.loads(path.read_text())
    assert data["done"] == 3 and len(data["points"]) == 3 and data["fingerprint"]["total"] == 7
    kept = {p["index"] for p in data["points"]}

    calls = []

    def counted(report_done, total):
        calls.append(report_done)

    resumed = map_analyses(square_or_fail, TASKS + [-1.0], processes, errors="record",
                           checkpoint=Checkpoint(path, resume=True, fingerprint="squares"),
                           progress=counted)
    assert resumed == full
    assert calls[0] == 3                  # resumed with the 3 points kept, 4 computed
    assert len(calls) == 1 + 7 - 3
    assert set(range(7)) - kept           # (something was left to do)
    assert json.loads(path.read_text())["done"] == 7
    Checkpoint(path).discard()
    assert not path.exists()
    Checkpoint(path).discard()            # absent: nothing to do


def test_a_task_raising_keyboard_interrupt_keeps_the_points_before_it(tmp_path):
    path = tmp_path / "p.partial"
    calls, armed = [], [True]

    def stop_at_four(x):
        calls.append(x)
        if x == 4.0 and armed[0]:
            raise KeyboardInterrupt
        return square_or_fail(x)

    with pytest.raises(Interrupted):
        map_analyses(stop_at_four, TASKS, errors="record", checkpoint=Checkpoint(path))
    assert [p["key"] for p in json.loads(path.read_text())["points"]] == ["0", "1", "2", "3"]
    calls.clear()
    armed[0] = False
    out = map_analyses(stop_at_four, TASKS, errors="record", checkpoint=Checkpoint(path, resume=True))
    assert out == map_analyses(square_or_fail, TASKS)
    assert calls == [4.0, 7.0]            # the four finished points were not computed again


def test_the_partial_file_is_complete_after_every_write(tmp_path):
    """interval 0: rewritten after every point; each state read back is a whole JSON file
    holding exactly the points finished so far (written through fileio: atomic)."""
    path = tmp_path / "p.partial"
    states = []

    def read_back(done, total):
        if done:
            states.append(json.loads(path.read_text())["done"])

    map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, interval=0.0), progress=read_back)
    assert states == list(range(1, len(TASKS) + 1))
    assert not list(tmp_path.glob(".*.tmp"))


def test_plain_results_round_trip_and_others_are_refused_at_their_first_point(tmp_path):
    """Issue 20.1: results were pickled when not plain data (and unpickled from the file);
    now the file holds plain JSON only: a result that is not is refused when it finishes."""
    path = tmp_path / "p.partial"
    nan = map_analyses(lambda x: {"v": float("nan"), "w": -0.1 + 0.2, "n": [1, None, "s"]}, [0],
                       checkpoint=Checkpoint(path, fingerprint="nan"))
    back = map_analyses(lambda x: pytest.fail("resumed points are not recomputed"), [0],
                        checkpoint=Checkpoint(path, resume=True, fingerprint="nan"))
    assert math.isnan(back[0]["v"]) and back[0]["w"] == nan[0]["w"] and back[0]["n"] == [1, None, "s"]
    calls = []

    def odd(x):
        calls.append(x)
        return (x, np.arange(3) * x)

    with pytest.raises(InputError, match=r"point '0' cannot be kept .*tuple is not plain data"):
        map_analyses(odd, [1.0, 2.0], checkpoint=Checkpoint(tmp_path / "q.partial"))
    assert calls == [1.0]


def test_a_file_of_another_study_is_refused(tmp_path):
    path = tmp_path / "p.partial"
    map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, fingerprint="A"),
                 keys=[f"x={x}" for x in TASKS])
    with pytest.raises(InputError, match="was written for another study"):
        map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, resume=True, fingerprint="B"),
                     keys=[f"x={x}" for x in TASKS])
    with pytest.raises(InputError, match="was written for another study"):
        map_analyses(square_or_fail, TASKS[:3], checkpoint=Checkpoint(path, resume=True, fingerprint="A"),
                     keys=[f"x={x}" for x in TASKS[:3]])
    with pytest.raises(InputError, match="is not point 0 of this study"):
        map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, resume=True, fingerprint="A"),
                     keys=[f"y={x}" for x in TASKS])
    path.write_text('{"points": [')
    with pytest.raises(InputError, match="is not valid JSON"):
        map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, resume=True))
    path.write_text('{"format": "something else"}')
    with pytest.raises(InputError, match="not a propwhirl partial results file"):
        map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, resume=True))


def test_resume_without_a_partial_file_runs_everything(tmp_path):
    path = tmp_path / "none.partial"
    assert map_analyses(square_or_fail, TASKS, checkpoint=Checkpoint(path, resume=True)) == \
        map_analyses(square_or_fail, TASKS)
    assert json.loads(path.read_text())["done"] == len(TASKS)


@pytest.mark.parametrize("call, match", [
    (lambda: map_analyses(square_or_fail, TASKS, processes=0), "processes"),
    (lambda: map_analyses(square_or_fail, TASKS, errors="ignore"), "errors"),
    (lambda: map_analyses(square_or_fail, TASKS, client=object()), "client"),
    (lambda: map_analyses(square_or_fail, TASKS, checkpoint="file.json"), "checkpoint"),
    (lambda: map_analyses(square_or_fail, TASKS, keys=["a"]), "keys"),
    (lambda: map_analyses(square_or_fail, [1.0, 2.0], keys=["a", "a"]), "keys"),
    (lambda: map_analyses(square_or_fail, TASKS, progress="yes"), "progress"),
    (lambda: Checkpoint("f", interval=-1.0), "interval"),
])
def test_bad_arguments_are_one_line_errors(call, match):
    with pytest.raises(InputError, match=match):
        call()


def test_without_dask_a_scheduler_names_the_extra(monkeypatch):
    monkeypatch.setitem(__import__("sys").modules, "distributed", None)
    with pytest.raises(InputError, match=r"pip install propwhirl\[distributed\]"):
        map_analyses(square_or_fail, TASKS, client="tcp://127.0.0.1:8786")


def test_the_runner_keeps_its_signature():
    from propwhirl.studies import runner

    assert runner.map_analyses(square_or_fail, TASKS, 2) == [square_or_fail(x) for x in TASKS]
    assert runner.map_analyses(square_or_fail, [-1.0], 1, errors="record")[0].kind == "InputError"
