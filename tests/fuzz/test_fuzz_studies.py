"""Fuzz (issue 20, items 5, 6, 8): the inputs of the studies — parameter paths with any index,
sweep values, clearance speeds and options, boundary speeds and planes, the OpenMDAO
component's factor, rpm with either operation, the sensitivities' model and analysis.

Each case is held to the rule (a result or a one-line InputError, no warning) and to the
issue's: a refused input reaches no analysis (the studies' entry points are replaced by
counters that stop at the first call), and an input that reaches one is one the checks pass."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from propwhirl.cases.ch09_baseline import baseline_propeller, isolated_baseline_propeller
from propwhirl.cases.registry import case_model
from propwhirl.model.aerodynamics import validity
from propwhirl.studies import boundary as B
from propwhirl.studies import clearance as C
from propwhirl.studies import paths as P
from propwhirl.studies import sweeps as S
from propwhirl.validate import InputError

NUMBER = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -1.0, 1e-300, 1e300, -1e300, 1e12, 1e-3, 1e3, 2.0**63]),
    st.floats(1e-3, 1e3), st.integers(-10**6, 10**6))

ISO = isolated_baseline_propeller()
TWO = case_model("two-propeller")
SOUND = ISO.flight.speed_of_sound


class Reached(Exception):
    """The study got past its checks to its first analysis."""


def _stop(*args, **kwargs):
    raise Reached


def _short(fn):
    """Call `fn`; an InputError must also be short (a 5,000-digit path is not echoed)."""
    try:
        return fn()
    except InputError as exc:
        assert len(str(exc)) < 600, str(exc)[:200]
        raise


# ----------------------------------------------------------------------------- paths
@FUZZ
@given(template=st.sampled_from(["propellers[{}].propeller.f_theta", "wing.rayleigh[{}]",
                                 "propellers[0].propeller.masses[{}].mass", "wing.EI[{}]"]),
       index=st.one_of(st.text("0123456789", min_size=1, max_size=6000),
                       st.integers(0, 3).map(str),
                       st.integers(0, 6000).map(lambda n: "0" * n + "1")))
def test_parameter_paths_with_any_index(template, index):
    with held_to_the_rule("python: paths.resolve(index)"):
        p = _short(lambda: P.resolve(TWO, template.format(index)))
        assert len(p.path) < 60 and "[0" not in p.path.replace("[0]", "")


# ----------------------------------------------------------------------------- sweeps
@FUZZ
@given(path=st.sampled_from(["propeller.f_psi", "propeller.K_theta", "flight.density",
                             "propeller.n_blades", "propeller.damping_theta", "propeller.rpm",
                             "propeller.hub_radius"]),
       second=st.sampled_from([None, "propeller.f_theta", "propeller.K_psi", "propeller.f_psi"]),
       values=st.lists(NUMBER, min_size=1, max_size=5))
def test_study_grids_are_checked_whole_before_any_analysis(monkeypatch, path, second, values):
    calls = []
    monkeypatch.setattr(S, "analyse", lambda *a, **k: calls.append(1) or _stop())
    axes = [(path, values)] + ([] if second is None else [(second, [4.0, 5.0])])
    refused = []
    with held_to_the_rule("python: critical_map(values)"):
        try:
            r = S.critical_map(ISO, axes)
        except InputError:
            refused.append(1)
            raise
        assert len(calls) <= len(r)
    if refused:
        assert not calls                  # refused before the work
    else:                                 # what got through lies in the declared range
        p = P.resolve(ISO, path)
        assert np.all(p.range.contains(np.asarray(values, dtype=float)))
        assert P.resolve(ISO, second or path).path == (second or path)


# ----------------------------------------------------------------------------- clearance
@FUZZ
@given(V_D=NUMBER, factor=st.one_of(NUMBER, st.floats(1.0, 3.0)),
       lo=st.one_of(NUMBER, st.just(1.0)), hi=st.one_of(NUMBER, st.just(30.0)),
       tol=st.one_of(NUMBER, st.just(1e-3)), minimum=st.booleans())
def test_clearance_inputs_are_checked_before_the_analysis(monkeypatch, V_D, factor, lo, hi, tol,
                                                          minimum):
    monkeypatch.setattr(C, "analyse", _stop)
    with held_to_the_rule("python: clearance(V_D, factor)"):
        try:
            _short(lambda: C.clearance(ISO, V_D, factor, minimum=minimum,
                                       frequency_range=(lo, hi), frequency_tol=tol))
        except Reached:     # passed the checks: an analysable speed range, a valid search
            assert 1.05 * factor * V_D < validity.MACH_REFUSED * SOUND
            if minimum:
                assert 1e-3 <= lo < hi <= 1e3 and tol > 0


# ----------------------------------------------------------------------------- boundary
@FUZZ
@given(V=NUMBER, lower=st.tuples(NUMBER, NUMBER), upper=st.tuples(NUMBER, NUMBER),
       paths=st.sampled_from([("propeller.f_theta", "propeller.f_psi"),
                              ("propeller.f_theta", "propeller.K_theta"),
                              ("propeller.K_psi", "propeller.damping_psi")]),
       contour=st.booleans())
def test_boundary_inputs_are_checked_before_any_evaluation(monkeypatch, V, lower, upper, paths,
                                                           contour):
    monkeypatch.setattr(B, "eigenvalues", _stop)
    monkeypatch.setattr(S, "evaluate", _stop)
    with held_to_the_rule("python: boundary(V, bounds)"):
        try:
            if contour:
                _short(lambda: B.speed_contour(ISO, paths, lower, upper, V))
            else:
                _short(lambda: B.neutral_curve(ISO, paths, lower, upper, V=V))
        except Reached:
            assert paths[1] != "propeller.K_theta"
            first, last = ISO.flight.speed_range[:2]
            assert (first < V < last) if contour else V < validity.MACH_REFUSED * SOUND
            for k, path in enumerate(paths):
                r = P.resolve(ISO, path).range
                assert r.contains(np.array([lower[k], upper[k]], dtype=float)).all()


# ----------------------------------------------------------------------------- OpenMDAO
@FUZZ
@given(factor=st.one_of(NUMBER, st.booleans(), st.none()), vd=st.one_of(NUMBER, st.just(130.0)))
def test_openmdao_component_factor_and_speed(factor, vd):
    pytest.importorskip("openmdao.api")
    from propwhirl.studies.gradients import openmdao_component

    with held_to_the_rule("python: openmdao_component(factor)"):
        comp = openmdao_component(WINGTIP, ["propellers[0].propeller.K_theta"], vd=vd,
                                  factor=factor)
        assert 1.0 <= factor <= 3.0 and 0 < vd and np.isfinite(factor * vd)
        assert comp.propwhirl.analyses == 0


WINGTIP = case_model("wingtip")


# ----------------------------------------------------------------------------- rpm
@FUZZ
@given(rpm=st.one_of(st.none(), NUMBER),
       operation=st.sampled_from(["fixed-pitch", "constant-speed"]))
def test_rpm_is_honoured_or_refused(rpm, operation):
    with held_to_the_rule("python: Propeller(rpm, operation)"):
        try:
            p = baseline_propeller(operation=operation, rpm=rpm)
        except InputError as exc:
            if rpm is not None:
                assert str(exc).startswith("rpm = "), str(exc)
            raise
        assert (rpm is None) == (operation == "fixed-pitch")
        Omega = p.rotational_speed(np.array([50.0, 100.0]))
        if operation == "constant-speed":        # honoured: Omega is the rpm's
            assert np.allclose(Omega, rpm * np.pi / 30.0)


# ----------------------------------------------------------------------------- sensitivities
@pytest.fixture(scope="module")
def analyses():
    from propwhirl.analysis import analyse

    base = case_model("baseline-wing")
    variant = P.set_value(WINGTIP, "propellers[0].propeller.f_psi", 5.5)
    models = {"wingtip": WINGTIP, "baseline": base, "isolated": ISO, "variant": variant,
              "renamed": dataclasses.replace(base, name=WINGTIP.name)}
    return models, {k: analyse(models[k]) for k in ("wingtip", "baseline", "isolated")}


@settings(FUZZ, max_examples=25)
@given(model=st.sampled_from(["wingtip", "baseline", "isolated", "variant", "renamed"]),
       analysis=st.sampled_from(["wingtip", "baseline", "isolated"]))
def test_sensitivities_of_any_model_and_analysis(analyses, model, analysis):
    from propwhirl.analysis import critical_sensitivities

    models, results = analyses
    with held_to_the_rule("python: critical_sensitivities(model, analysis)"):
        cs = critical_sensitivities(models[model], results[analysis],
                                    params=["propellers[0].propeller.f_theta"]
                                    if model == "wingtip" else [])
        assert model == analysis == "wingtip" or (model == analysis == "baseline")
        assert np.isfinite(cs.V) and all(np.isfinite(s.dV_dp) for s in cs.sensitivities)
