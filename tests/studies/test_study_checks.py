"""Issue 20 (items 5, 6, 8): the studies check their whole input before any analysis — a
huge index in a parameter path, a field varied with its alternative, values outside a path's
declared range, clearance and boundary speeds beyond what the model can analyse, the
OpenMDAO component's paths and factor, rpm with fixed-pitch operation.

"Before the work" is tested by replacing each study's analysis entry point with a counter:
a refused input must reach it 0 times."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import baseline_propeller, isolated_baseline_propeller
from propwhirl.cases.registry import case_model
from propwhirl.studies import boundary as B
from propwhirl.studies import clearance as C
from propwhirl.studies import continuation
from propwhirl.studies import gradients as G
from propwhirl.studies import paths as P
from propwhirl.studies import sweeps as S
from propwhirl.validate import InputError

F_THETA, K_THETA = "propeller.f_theta", "propeller.K_theta"


@pytest.fixture(scope="module")
def iso():
    return isolated_baseline_propeller()


@pytest.fixture(scope="module")
def two():
    return case_model("two-propeller")


@pytest.fixture
def calls(monkeypatch):
    """Counts of the analysis entry points of the studies (each call refused: nothing may
    reach them in these tests)."""
    count = {"analyse": 0, "eigenvalues": 0}

    def counted(name):
        def fn(*args, **kwargs):
            count[name] += 1
            raise RuntimeError(f"{name} reached")
        return fn

    for module in (S, C, G):
        monkeypatch.setattr(module, "analyse", counted("analyse"))
    monkeypatch.setattr(B, "eigenvalues", counted("eigenvalues"))
    return count


def _one_line(exc) -> str:
    msg = str(exc.value)
    assert "\n" not in msg and len(msg) < 400, msg
    return msg


# ----------------------------------------------------------------------------- item 5: index
def test_a_5000_digit_index_is_a_one_line_error(two):
    for path in ("propellers[" + "0" * 5000 + "2].propeller.f_theta",
                 "propellers[" + "9" * 5000 + "].propeller.f_theta",
                 "wing.rayleigh[" + "1" * 5000 + "]"):
        with pytest.raises(InputError, match="is invalid") as exc:
            P.resolve(two, path)
        msg = _one_line(exc)
        assert "characters" in msg and "nearest valid paths" in msg


def test_leading_zeros_of_an_index_are_read_and_dropped_from_the_path(two):
    p = P.resolve(two, "propellers[" + "0" * 5000 + "1].propeller.f_theta")
    assert p.path == "propellers[1].propeller.f_theta"


# ----------------------------------------------------------------------------- item 6: alternatives
def test_a_map_over_a_field_and_its_alternative_is_refused_before_any_analysis(iso, calls):
    with pytest.raises(InputError, match="K_theta is the alternative of f_theta") as exc:
        S.map2d(iso, (F_THETA, [4.0, 6.0]), (K_THETA, [1e4, 2e4]))
    assert F_THETA in _one_line(exc) and K_THETA in str(exc.value)
    assert calls["analyse"] == 0


def test_paths_reaching_the_same_value_are_refused(two, calls):
    with pytest.raises(InputError, match="set the same value"):
        S.map2d(two, ("propellers[*].propeller.f_psi", [4.0, 6.0]),
                ("propellers[0].propeller.f_psi", [4.0, 6.0]))
    with pytest.raises(InputError, match="set the same value"):
        P.set_values(two, {"propellers[0].propeller.K_psi": 1e4,
                           "propellers[*].propeller.K_psi": 2e4})
    with pytest.raises(InputError, match="alternative"):
        P.variants(two, {"propellers[*].propeller.f_theta": [5.0],
                         "propellers[1].propeller.K_theta": [1e4]})
    assert calls["analyse"] == 0
    # different installations are independent: f_theta of one, K_theta of the other
    vs = P.grid_variants(two, [("propellers[0].propeller.f_theta", [5.0]),
                               ("propellers[1].propeller.K_theta", [1e4])])
    assert vs[0].propellers[0].propeller.f_theta == 5.0
    assert vs[0].propellers[1].propeller.K_theta == 1e4


def test_a_boundary_over_a_field_and_its_alternative_is_refused(iso, calls):
    with pytest.raises(InputError, match="alternative"):
        B.neutral_curve(iso, (F_THETA, K_THETA), (3.0, 1e3), (12.0, 1e5), V=200.0)
    assert calls["eigenvalues"] == 0


# ----------------------------------------------------------------------------- item 6: ranges
def test_values_outside_the_declared_range_stop_the_study_before_any_analysis(iso, calls):
    with pytest.raises(InputError) as exc:
        S.sweep(iso, "propeller.f_psi", [3.0, -1.0, 2000.0, 5.0])
    msg = _one_line(exc)
    assert msg == ("propeller.f_psi: values = -1, 2000 Hz are outside the valid range "
                   "[1e-3, 1000] Hz"), msg
    with pytest.raises(InputError, match=r"propeller.f_theta: values = 1e\+06 Hz is outside"):
        S.map2d(iso, ("propeller.f_psi", [3.0, 4.0]), (F_THETA, [5.0, 1e6]))
    with pytest.raises(InputError, match=r"wing.EI\*: values = 0 is invalid: a factor must be > 0"):
        S.sweep(case_model("baseline-wing"), "wing.EI*", [1.0, 0.0])
    assert calls["analyse"] == 0


def test_a_study_every_point_of_which_the_model_refuses_stops_before_any_analysis(iso, calls):
    with pytest.raises(InputError, match="every point of the study is refused by the model.*rpm"):
        S.sweep(iso, "propeller.rpm", [1000.0, 2000.0])         # a fixed-pitch propeller
    assert calls["analyse"] == 0


# ----------------------------------------------------------------------------- item 6: rpm
def test_rpm_with_fixed_pitch_operation_is_refused_naming_the_key():
    with pytest.raises(InputError) as exc:
        baseline_propeller(rpm=2250.0)
    msg = _one_line(exc)
    assert msg.startswith("rpm = 2250.0 rev/min is invalid with operation = 'fixed-pitch'"), msg
    assert exc.value.path == ("rpm",)
    # constant speed honours it
    p = baseline_propeller(operation="constant-speed", rpm=2250.0)
    assert p.rotational_speed(np.array([100.0]))[0] == pytest.approx(2250.0 * np.pi / 30.0)


def test_rpm_with_fixed_pitch_operation_in_a_model_file_names_the_key():
    from propwhirl import io

    text = io.dumps(isolated_baseline_propeller())
    assert 'operation = "fixed-pitch"' in text
    bad = text.replace('operation = "fixed-pitch"', 'operation = "fixed-pitch"\nrpm = 2250.0')
    with pytest.raises(InputError, match=r"rpm = 2250.0 is invalid with operation = "
                                         r"'fixed-pitch'") as exc:
        io.loads(bad)
    _one_line(exc)


# ----------------------------------------------------------------------------- item 5: clearance
def test_clearance_beyond_what_the_model_can_analyse_is_one_line_before_any_analysis(iso, calls):
    with pytest.raises(InputError, match=r"factor x V_D = 1.15e\+300 m/s is invalid.*Mach") as exc:
        C.clearance(iso, 1e300)
    assert len(_one_line(exc)) < 300
    wing = case_model("baseline-wing").with_(wing_aero=False)       # no Mach limit: grid size
    with pytest.raises(InputError, match="speeds, at most 100,000"):
        C.clearance(wing, 1e300, minimum=False)
    assert calls["analyse"] == 0


@pytest.mark.parametrize("options, match", [
    ({"frequency_range": (1.0, 1e300)}, r"frequency_range = 1e\+300 Hz is outside the valid range"),
    ({"frequency_tol": 0.0}, "frequency_tol = 0.0 Hz is invalid: must be > 0"),
    ({"n_scan": 1}, "n_scan = 1 is invalid"),
    ({"frequency_range": (1.0, 2.0, 3.0)}, "give two frequencies"),
])
def test_the_minimum_frequency_search_is_checked_before_the_first_analysis(iso, calls, options,
                                                                           match):
    with pytest.raises(InputError, match=match) as exc:
        C.clearance(iso, 150.0, **options)
    _one_line(exc)
    assert calls["analyse"] == 0


# ----------------------------------------------------------------------------- item 8: boundary
def test_boundary_speed_1e300_is_one_short_line_before_any_eigen_solution(iso, calls):
    with pytest.raises(InputError, match=r"V = 1e\+300 m/s is invalid: Mach 3.02e\+297") as exc:
        B.neutral_curve(iso, (F_THETA, "propeller.f_psi"), (3.0, 3.0), (12.0, 12.0), V=1e300)
    assert len(_one_line(exc)) < 300
    assert calls["eigenvalues"] == 0


def test_the_model_states_a_huge_mach_number_in_a_few_digits(iso):
    from propwhirl.analysis import analyse

    with pytest.raises(InputError, match=r"is Mach 3.02e\+297 at a") as exc:
        analyse(iso, [1.0, 1e300])
    assert len(_one_line(exc)) < 300


def test_a_contour_target_outside_the_analysed_speeds_is_refused(iso, calls, monkeypatch):
    monkeypatch.setattr(S, "evaluate", lambda task: calls.__setitem__("analyse", 1))
    for V in (1e300, 350.0, 0.5):
        with pytest.raises(InputError, match="outside the analysed speeds"):
            B.speed_contour(iso, (F_THETA, "propeller.f_psi"), (3.0, 3.0), (12.0, 12.0), V)
    assert calls["analyse"] == 0


def test_boundary_bounds_outside_the_declared_range_are_one_line_without_a_warning(iso, calls):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError) as exc:
            B.neutral_curve(iso, (F_THETA, "propeller.f_psi"), (3.0, 3.0), (1e300, 12.0), V=200.0)
        assert _one_line(exc) == ("propeller.f_theta: bounds = 1e+300 Hz is outside the valid "
                                  "range [1e-3, 1000] Hz")
        with pytest.raises(InputError, match="overflows"):
            continuation.trace(lambda p: p[0], (-1e308, 0.0), (1e308, 1.0))
    assert calls["eigenvalues"] == 0


def test_points_of_huge_coordinates_keep_distinct_memo_keys_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        g = continuation.Counted(lambda p: float(p[0] > 2e300))
        g(np.array([1e300, 0.0]))
        g(np.array([3e300, 0.0]))
    assert g.calls == 2
    assert continuation.point_key(np.array([0.1 + 1e-14, 1.0])) == (0.1, 1.0)


# ----------------------------------------------------------------------------- item 5/6: OpenMDAO
@pytest.mark.parametrize("paths, match", [
    ((), "at least one parameter path"),
    (("propellers[0].propeller.K_theta",) * 2, "appears twice"),
    ("propellers[0].propeller.K_theta", "give a list of parameter paths"),
    (("propellers[0].propeller.K_theta", "propellers[0].propeller.f_theta"), "alternative"),
    ((3,), "each path must be a string"),
])
def test_openmdao_component_paths_are_checked(paths, match, calls):
    pytest.importorskip("openmdao.api")
    model = case_model("wingtip")
    with pytest.raises(InputError, match=match) as exc:
        G.openmdao_component(model, paths, vd=130.0)
    _one_line(exc)
    assert calls["analyse"] == 0


@pytest.mark.parametrize("factor", [0.0, -1.0, float("nan"), 0.5, 1e300, True])
def test_openmdao_component_factor_is_checked(factor, calls):
    pytest.importorskip("openmdao.api")
    with pytest.raises(InputError, match="factor") as exc:
        G.openmdao_component(case_model("wingtip"), ["propellers[0].propeller.K_theta"],
                             vd=130.0, factor=factor)
    _one_line(exc)
    assert calls["analyse"] == 0
