"""A whole analysis runs with BLAS at one thread — its naming, content and participation too,
not only the engine's eigen-solutions (issue 26, item 2: small matrix products under several
OpenBLAS threads on a loaded machine cost up to a thousand times their work; measured in
docs/performance.md, "The reduced analysis's overhead").  Checked as state, not time: the
post-processing steps record whether they run inside the one-thread limit."""
from __future__ import annotations

import contextlib

import numpy as np
import pytest

import propwhirl.analysis.runners as runners
import propwhirl.analysis.stability as stability
from propwhirl.analysis import analyse
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.engine import eigensolve


@pytest.fixture
def limited(monkeypatch):
    """Depth of the one-thread limit (:func:`eigensolve.single_thread_blas` as the analysis's
    decorator enters it) and, per post-processing step, whether it ran inside it."""
    depth, seen = [0], {}
    real = eigensolve.single_thread_blas

    @contextlib.contextmanager
    def counted():
        with real():
            depth[0] += 1
            try:
                yield
            finally:
                depth[0] -= 1

    monkeypatch.setattr(eigensolve, "single_thread_blas", counted)
    for module, name in ((stability, "named_modes"), (stability, "mode_content"),
                         (stability, "with_participation"),
                         (runners, "frequency_zero_points")):    # the tracking's, since 38.7
        f = getattr(module, name)

        def spy(*args, _f=f, _name=name, **kwargs):
            seen[_name] = depth[0] > 0
            return _f(*args, **kwargs)

        monkeypatch.setattr(module, name, spy)
    return seen


def test_naming_content_and_participation_run_with_one_blas_thread(limited):
    a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    assert a.critical is not None and np.isfinite(a.critical.V)
    assert limited == {"named_modes": True, "mode_content": True, "with_participation": True,
                       "frequency_zero_points": True}


def test_the_limit_is_released_after_the_analysis():
    """The decorator restores the caller's BLAS threads (threadpoolctl's limit is a context)."""
    ctl = eigensolve._blas_controller()
    before = [p["num_threads"] for p in ctl.info()]
    analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0])
    assert [p["num_threads"] for p in ctl.info()] == before
