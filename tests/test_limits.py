"""limits.py: the memory limit, the memory estimate of a sweep, bounds on sizes, printable()."""
from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest

from propwhirl import limits
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.model import FlightCondition, Wing
from propwhirl.model.propellers.propeller_aero import AeroSettings
from propwhirl.validate import InputError


# ----------------------------------------------------------------------------- memory limit
def test_memory_limit_from_the_environment(monkeypatch):
    monkeypatch.setenv(limits.MEMORY_ENV, "512MiB")
    assert limits.memory_limit() == 512 * 2 ** 20
    monkeypatch.setenv(limits.MEMORY_ENV, "2GB")
    assert limits.memory_limit() == 2 * 10 ** 9
    monkeypatch.setenv(limits.MEMORY_ENV, "3000000000")
    assert limits.memory_limit() == 3_000_000_000
    for bad in ("lots", "-1GiB", "4 parsecs", "1e400", "10"):
        monkeypatch.setenv(limits.MEMORY_ENV, bad)
        with pytest.raises(InputError, match=limits.MEMORY_ENV):
            limits.memory_limit()


def test_default_memory_limit_follows_the_machine(monkeypatch):
    monkeypatch.delenv(limits.MEMORY_ENV, raising=False)
    phys = limits.physical_memory()
    expect = (limits.FALLBACK_LIMIT if phys is None else
              min(max(0.5 * phys, 256 * 2 ** 20), limits.DEFAULT_LIMIT_CAP))
    assert limits.memory_limit() == int(expect)
    monkeypatch.setattr(limits, "physical_memory", lambda: 4 * limits.GiB)
    assert limits.memory_limit() == 2 * limits.GiB
    monkeypatch.setattr(limits, "physical_memory", lambda: 256 * limits.GiB)
    assert limits.memory_limit() == limits.DEFAULT_LIMIT_CAP


def _tip_model():
    from propwhirl.model.systems import Installation, PropellerWing
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing

    return PropellerWing(baseline_wing(10), baseline_flight(),
                         (Installation(baseline_propeller(), 5.7),))


@pytest.mark.parametrize("make, n_speeds", [(_tip_model, 60),
                                            (isolated_baseline_propeller, 600)],
                         ids=["wing-propeller-84-states", "isolated-propeller-4-states"])
def test_the_estimate_bounds_the_measured_peak(make, n_speeds):
    """sweep_bytes is at least the traced peak of a real V-g-f sweep, and not 3× more (a
    large model: eigenvectors dominate; a small one: the batches' Houbolt–Reed integrals)."""
    model = make()
    n = model.dof_map().n_states
    speeds = np.linspace(1.0, 350.0, n_speeds)
    analyse(model, speeds[:3], vgf=True, method="dense")  # warm-up (imports, caches)
    tracemalloc.start()
    try:                                                  # an n-state sweep: dense
        a = analyse(model, speeds, vgf=True, method="dense")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    est = limits.sweep_bytes(a.sweep.V.size, n)
    assert peak <= est <= 3 * peak, (peak, est)


def test_an_analysis_beyond_the_memory_limit_is_refused_before_allocating(monkeypatch):
    """The issue's --speeds 1 350 0.0035 on the 204-state wingtip model: ≈ 124 GiB."""
    from propwhirl.cases.registry import case_model

    monkeypatch.setenv(limits.MEMORY_ENV, "2GiB")
    model = case_model("wingtip")
    grid = 1.0 + 0.0035 * np.arange(99_715)
    tracemalloc.start()
    try:
        with pytest.raises(InputError) as exc:            # dense: the 204 states
            analyse(model, grid, vgf=True, method="dense")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    msg = str(exc.value)
    assert "the analysis needs ≈ 124 GiB for 99,715 speeds × 204 states (limit 2.0 GiB, set " \
           "PROPWHIRL_MEMORY_LIMIT or pass fewer speeds)" == msg
    assert peak < 100 * 2 ** 20                            # refused, not attempted
    monkeypatch.setenv(limits.MEMORY_ENV, "4MiB")          # a small model under a tiny limit
    with pytest.raises(InputError, match="the analysis needs ≈ 17.0 MiB for 2,000 speeds × 4 "
                                         "states .limit 4.0 MiB"):
        analyse(isolated_baseline_propeller(), np.linspace(100.0, 300.0, 2000), vgf=True)


# ----------------------------------------------------------------------------- sizes
@pytest.mark.parametrize("rng, count", [((1.0, 350.0, 1e-9), "349,000,000,001"),
                                        ((1.0, 350.0, 0.001), "349,001")])
def test_a_speed_range_too_fine_or_infinite_is_refused_at_construction(rng, count):
    with pytest.raises(InputError, match=f"speed_range = .* gives {count} speeds: must be at "
                                         "most 100,000"):
        FlightCondition(1.225, speed_range=rng)
    assert FlightCondition(1.225, speed_range=(1.0, 350.0, 0.01)).speeds().size == 34_901


def test_an_infinite_speed_range_is_refused_at_construction():
    """The field's range refuses it before the count: no grid without end is attempted."""
    with pytest.raises(InputError, match=r"speed_range\[1\] = inf m/s is invalid: must be finite"):
        FlightCondition(1.225, speed_range=(1.0, math.inf, 10.0))


def test_grid_count_matches_the_grid():
    for rng in ((1.0, 350.0, 10.0), (1.0, 351.0, 10.0), (0.5, 2.0, 0.25), (1.0, 2.0, 3.0)):
        assert limits.grid_count(*rng) == FlightCondition(1.0, speed_range=rng).speeds().size


def test_model_sizes_are_bounded():
    kw = dict(semi_span=6.0, mass_per_length=35.0, polar_inertia=8.6, EI=1e7, GJ=1e6)
    with pytest.raises(InputError, match="n_elements = 10000 is invalid: must be at most 200"):
        Wing(**kw, n_elements=10_000)
    assert Wing(**kw, n_elements=200).n_nodes == 201
    with pytest.raises(InputError, match="quadrature_order = 100000 is invalid: must be at "
                                         "most 256"):
        AeroSettings(quadrature_order=100_000)
    assert AeroSettings(quadrature_order=256).quadrature_order == 256


def test_the_number_of_propellers_is_bounded():
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    from propwhirl.model.systems import Installation, PropellerWing

    inst = Installation(baseline_propeller(), 5.7)
    with pytest.raises(InputError, match="number of propellers = 65 is invalid: must be at "
                                         "most 64"):
        PropellerWing(baseline_wing(5), baseline_flight(), (inst,) * 65)


def test_node_budget_is_bounded_absolutely_and_by_memory(monkeypatch):
    monkeypatch.setenv(limits.MEMORY_ENV, "8GiB")
    assert limits.node_budget(36, 36, 204) == 36 * 20 + 200
    assert limits.node_budget(100_000, 8, 4) == 8 + limits.MAX_REFINED_NODES
    monkeypatch.setenv(limits.MEMORY_ENV, "512MiB")
    per_node = 32 * 204 ** 2 + limits.NODE_OVERHEAD_BYTES
    b = limits.node_budget(100_000, 8, 204)
    assert 8 < b < 512 * 2 ** 20 / per_node and limits.sweep_bytes(b, 204) <= 512 * 2 ** 20
    assert limits.sweep_bytes(b + 10, 204) > 512 * 2 ** 20 - 10 * per_node
    assert limits.node_budget(100_000, 8, 204, requested=10 ** 9) == b
    assert limits.node_budget(10, 50, 10_000) == 50        # never fewer than the first nodes


# ----------------------------------------------------------------------------- printable
@pytest.mark.parametrize("text, shown", [
    ("wing", "wing"), ("Flügel ½", "Flügel ½"),
    ("evil\x1b[2J\x1b]0;pwn\x07", "evil\\x1b[2J\\x1b]0;pwn\\x07"),
    ("a\x9b31mb", "a\\x9b31mb"), ("tab\there\nline", "tab\\x09here\\x0aline"),
    ("\u202egnp.exe", "\\u202egnp.exe"), ("x\x00y\x7f", "x\\x00y\\x7f"),
    ("sep\u2028", "sep\\u2028")])
def test_printable_escapes_control_characters(text, shown):
    out = limits.printable(text)
    assert out == shown
    assert out.isprintable()
