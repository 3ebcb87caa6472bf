"""Studies whose cost is inherent tell the user before the work (issue 20, item 9): a 500 × 500
map (250,000 analyses) is estimated — time and memory, from the model's size and the method
its analyses run — and refused beyond ``PROPWHIRL_STUDY_TIME_LIMIT`` (default 12 h; since issue
26 the wingtip map's ≈ 5.4 h fit in it, so the tests set 2 h) or the memory limit, before a single
variant is built; a long study that is started prints its estimate first.  Work is bounded
by counting (variants built, analyses run) and by tracemalloc, never by the clock."""
from __future__ import annotations

import io
import tracemalloc

import numpy as np
import pytest

from propwhirl import limits
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.studies import paths as P
from propwhirl.studies import sweeps
from propwhirl.validate import InputError


class _Started(Exception):
    """Raised by the guard at the first variant: the study's work began."""


@pytest.fixture
def variants_built(monkeypatch):
    """Counts the variants the study builds; stops it at the first (the work began)."""
    count = {"n": 0}

    def guard(model, point):
        count["n"] += 1
        raise _Started

    monkeypatch.setattr(P, "set_values", guard)
    return count


AXES = (("wing.EI", np.linspace(5e5, 9e5, 500)), ("wing.GJ", np.linspace(1.5e5, 2.5e5, 500)))


def test_a_500_by_500_map_is_refused_before_any_work(monkeypatch, variants_built):
    # ≈ 5.4 h on one process by default since issue 26 (the reduced default analysis),
    # within the default 12 h: refused under a limit of 2 h
    monkeypatch.setenv(limits.STUDY_TIME_ENV, "2h")
    model = wingtip_propeller_wing()
    tracemalloc.start()
    try:
        with pytest.raises(InputError) as err:
            sweeps.map2d(model, *AXES)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    msg = str(err.value)
    assert "\n" not in msg
    assert "250,000 analyses of 204 states" in msg and limits.STUDY_TIME_ENV in msg
    assert variants_built["n"] == 0
    assert peak < 20 * 2 ** 20           # nothing of 250,000 variants or rows was allocated


def test_the_limit_is_lifted_by_the_environment(monkeypatch, variants_built):
    monkeypatch.setenv(limits.STUDY_TIME_ENV, "none")
    with pytest.raises(_Started):
        sweeps.map2d(wingtip_propeller_wing(), *AXES)
    assert variants_built["n"] == 1
    monkeypatch.setenv(limits.STUDY_TIME_ENV, "3d")          # 5.4 h on one process: within 3 d
    with pytest.raises(_Started):
        sweeps.map2d(wingtip_propeller_wing(), *AXES)
    monkeypatch.setenv(limits.STUDY_TIME_ENV, "2h")          # or on more processes
    with pytest.raises(InputError):
        sweeps.map2d(wingtip_propeller_wing(), *AXES)
    with pytest.raises(_Started):
        sweeps.map2d(wingtip_propeller_wing(), *AXES, processes=4)


def test_the_memory_of_a_study_is_checked(monkeypatch, variants_built):
    monkeypatch.setenv(limits.STUDY_TIME_ENV, "none")
    monkeypatch.setenv(limits.MEMORY_ENV, "1GiB")    # 250,000 points × 8 kB: ≈ 2 GiB
    with pytest.raises(InputError, match=r"memory limit 1\.0 GiB"):
        sweeps.map2d(wingtip_propeller_wing(), *AXES)
    assert variants_built["n"] == 0


@pytest.mark.parametrize("text", ["", "-1", "12 parsecs", "h"])
def test_a_bad_time_limit_is_one_line(monkeypatch, text):
    monkeypatch.setenv(limits.STUDY_TIME_ENV, text)
    if not text:
        assert limits.study_time_limit() == limits.DEFAULT_STUDY_SECONDS
        return
    with pytest.raises(InputError, match=limits.STUDY_TIME_ENV):
        limits.study_time_limit()


def test_the_estimate_scales_with_points_states_and_processes():
    small, wing = isolated_baseline_propeller(), wingtip_propeller_wing()
    a = limits.study_estimate(wing, 1000)
    assert a.cpu_seconds == pytest.approx(1000 * a.per_analysis)
    assert limits.study_estimate(wing, 2000).seconds == pytest.approx(2 * a.seconds)
    assert limits.study_estimate(wing, 1000, processes=4).seconds == pytest.approx(a.seconds / 4)
    assert limits.study_estimate(small, 1000).seconds < a.seconds / 4
    # "auto" reduces wings above 400 states: the estimate is capped there, "dense" is not
    assert limits.analysis_seconds(800, "dense") > 5 * limits.analysis_seconds(800, "auto")


def test_a_long_study_prints_its_estimate_first_and_a_short_one_nothing(monkeypatch):
    monkeypatch.delenv(limits.STUDY_TIME_ENV, raising=False)
    wing = wingtip_propeller_wing()
    out = io.StringIO()
    est = limits.check_study(wing, 2500, progress=True, stream=out)
    assert out.getvalue() == f"propwhirl: estimate: {est.text()}\n"
    assert "2,500 analyses of 204 states" in out.getvalue()
    quiet = io.StringIO()
    limits.check_study(wing, 2500, progress=None, stream=quiet)      # a library call: silent
    limits.check_study(wing, 4, progress=True, stream=quiet)          # short: silent
    assert quiet.getvalue() == ""


def test_a_small_study_still_runs(monkeypatch):
    monkeypatch.delenv(limits.STUDY_TIME_ENV, raising=False)
    r = sweeps.sweep(isolated_baseline_propeller(), "propeller.f_psi", [6.0, 8.0],
                     speeds=[100.0, 200.0, 300.0])
    assert list(r.kind) == ["flutter", "flutter"]


# ----------------------------------------------------------------------------- many propellers
def _propellers_on_wingtip(tmp_path, n: int, n_elements: int = 12):
    """The wingtip example with ``n`` equal propellers evenly spaced to the tip."""
    import re
    from pathlib import Path

    from propwhirl.io import load_model

    text = (Path(__file__).resolve().parents[2] / "examples" / "wingtip.toml").read_text()
    rows = "".join(f'    {{ propeller = "p1", y_m = {5.7 * (i + 1) / n!r}, mount = "flexible", '
                   'aero = true },\n' for i in range(n))
    text = re.sub(r"installations = \[\n.*?\n\]\n", f"installations = [\n{rows}]\n", text,
                  flags=re.S).replace("n_elements = 25", f"n_elements = {n_elements}")
    path = tmp_path / f"props_{n}.toml"
    path.write_text(text)
    return load_model(path)


def test_naming_many_equal_propellers_on_a_reduced_basis_is_bounded(tmp_path, monkeypatch):
    """16 equal propellers, the reduced basis of method="reduced": their mount modes are
    near-repeated, and the Campbell tracking that names them (from rpm 0 to a small rpm)
    bisected its unresolvable steps to its budget (69 eigen-solutions here; 240 for 64
    propellers: 16 s of a 37 s analysis).  Every thesis model needs 2."""
    import propwhirl.analysis.modes as modes
    from propwhirl.analysis.modes import label_modes
    from propwhirl.model.reduction import reduce

    solved = {"n": 0}
    original = modes._evaluate

    def counted(system, Omega, tol):
        solved["n"] += len(Omega)
        return original(system, Omega, tol)

    monkeypatch.setattr(modes, "_evaluate", counted)
    model = _propellers_on_wingtip(tmp_path, 16)
    basis = reduce(model, model.flight.speeds()).dof_basis
    labels = [name for name, _ in label_modes(model, basis=basis)]
    assert solved["n"] <= 32
    kinds = [x.split()[0] for x in labels]
    assert kinds.count("backward") == kinds.count("forward") == 16
    solved["n"] = 0
    label_modes(wingtip_propeller_wing())
    assert solved["n"] == 2


def test_a_long_analysis_is_announced_before_the_work(tmp_path, monkeypatch, capsys):
    """Issue 20.9: 64 propellers (the limit) is an analysis of ~20 s CPU; the command says so,
    with its size, before it starts (nothing is analysed here: the analysis is stubbed), and
    says nothing before a short one."""
    import propwhirl.analysis.stability as stability
    from propwhirl.app import cli

    class Stop(Exception):
        pass

    def stop(*args, **kwargs):
        raise Stop

    big = _propellers_on_wingtip(tmp_path, 64, n_elements=25)
    assert limits.analysis_notice(big) is not None
    assert limits.analysis_notice(wingtip_propeller_wing()) is None
    from propwhirl.io import save_model

    path = tmp_path / "big.toml"
    save_model(big, path)
    monkeypatch.setattr(stability, "analyse", stop)
    with pytest.raises(Stop):
        cli.main(["analyse", str(path)])
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: estimate: an analysis of 768 states: ≈ ") and err.count("\n") == 1
    with pytest.raises(Stop):
        cli.main(["analyse", str(path), "--quiet"])
    assert capsys.readouterr().err == ""


def test_a_study_of_a_wing_is_estimated_as_the_default_analyses_it():
    """Since issue 26 "auto" analyses every strip-theory wing reduced: a study of the wingtip
    model (204 states, below the old 400-state threshold) is estimated at the reduced size
    when the studies pass the resolved method, within 2x of its measured default analysis
    (≈ 0.065 s on one thread, docs/performance.md) rather than the dense one (≈ 0.28 s)."""
    from propwhirl.analysis.reduced import choose_method

    wing = wingtip_propeller_wing()
    resolved = limits.study_estimate(wing, 1000, method=choose_method(wing, "auto"))
    assert resolved.per_analysis == pytest.approx(limits.analysis_seconds(204, "reduced", 1))
    assert resolved.per_analysis < 0.5 * limits.study_estimate(wing, 1000, method="dense").per_analysis
    assert 0.065 / 2 < resolved.per_analysis < 2 * 0.065
