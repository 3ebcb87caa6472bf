"""The Dask back end (issue 12, item 5), on a small in-process LocalCluster: the same results
as serial and local processes — for plain tasks, a study, the reproduction — with BLAS at one
thread on the workers, failing points recorded, a scheduler address accepted."""
from __future__ import annotations

from dataclasses import replace

import pytest

distributed = pytest.importorskip("distributed", reason="the [distributed] extra is not installed")

from propwhirl.cases.ch09_baseline import baseline_propeller  # noqa: E402
from propwhirl.studies import runner  # noqa: E402
from propwhirl.studies.execution import Checkpoint, TaskError, map_analyses  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                       dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def cube(x: float) -> float:
    if x < 0:
        raise InputError(f"x = {x!r} is invalid: must be >= 0")
    return x ** 3 / 7.0


def blas_threads(_: object) -> list[int]:
    from threadpoolctl import threadpool_info

    return [d["num_threads"] for d in threadpool_info() if d.get("user_api") == "blas"]


TASKS = [0.5, 1.0, 2.5, 3.0, -1.0, 4.0]


def test_dask_gives_the_serial_list(client):
    serial = map_analyses(cube, TASKS, errors="record")
    on_dask = map_analyses(cube, TASKS, client=client, errors="record")
    assert on_dask == serial
    assert on_dask[4] == TaskError("InputError", "x = -1.0 is invalid: must be >= 0")
    with pytest.raises(InputError, match="x = -1.0"):
        map_analyses(cube, TASKS, client=client)


def test_dask_workers_run_blas_at_one_thread(client):
    assert all(t and set(t) == {1} for t in map_analyses(blas_threads, [0, 1, 2], client=client))
    assert "propwhirl-one-blas-thread" in client.run(lambda dask_worker: list(dask_worker.plugins))[
        next(iter(client.scheduler_info()["workers"]))]


def test_a_scheduler_address_connects_and_closes_its_own_client(client):
    address = client.scheduler.address
    assert map_analyses(cube, [1.0, 2.0], client=address) == [cube(1.0), cube(2.0)]
    with pytest.raises(InputError, match="scheduler"):
        map_analyses(cube, [1.0], client="")


def test_dask_resumes_a_partial_file(client, tmp_path):
    path = tmp_path / "p.partial"
    map_analyses(cube, TASKS[:3], errors="record", checkpoint=Checkpoint(path))
    import json

    data = json.loads(path.read_text())
    data["fingerprint"]["total"] = len(TASKS)
    path.write_text(json.dumps(data))
    out = map_analyses(cube, TASKS, client=client, errors="record",
                       checkpoint=Checkpoint(path, resume=True))
    assert out == map_analyses(cube, TASKS, errors="record")


def test_a_study_is_identical_serial_on_processes_and_on_dask(client):
    """The same table (every column, the failing point's error included) from each back end."""
    base = baseline_propeller()
    props = [base, replace(base, n_blades=8, blade_chord=1.5),  # blades overfill the disc
             replace(base, f_psi=5.0, K_psi=None), replace(base, f_theta=4.0, K_theta=None)]
    params = {"case": [1.0, 2.0, 3.0, 4.0]}
    tables = [runner.propeller_study("back ends", "case", "", params, props, models=("isolated",),
                                     **kw).to_dict()
              for kw in ({}, {"processes": 2}, {"client": client})]
    assert tables[0] == tables[1] == tables[2]
    cols = tables[0]["columns"]
    assert cols["kind"][1] == "error" and "solidity" in cols["error"][1]
    assert [e for i, e in enumerate(cols["error"]) if i != 1] == ["", "", ""]
    assert all(v is not None for i, v in enumerate(cols["critical_speed"]) if i != 1)


def test_the_reproduction_is_identical_on_dask(client):
    from propwhirl.reproduce import harness

    serial = harness.to_json(harness.run(["t4.1", "t7.2"]))
    assert harness.to_json(harness.run(["t4.1", "t7.2"], client=client)) == serial
    assert harness.to_json(harness.run(["t4.1", "t7.2"], processes=2)) == serial
