"""The Mach number of a doublet-lattice wing (issue 23, item 4): ``dlm_mach = "speed"`` (V/a at
each analysed speed, matched) or one fixed number for every speed (non-matched), in Python and
in the model file, used by the p-k method and the Roger state space; and the validity warnings
of a DLM wing (propwhirl.model.aerodynamics.validity)."""
import dataclasses

import numpy as np
import pytest

from propwhirl.io import dumps, loads
from propwhirl.model import FlightCondition, PropellerWing, Wing
from propwhirl.model.aerodynamics import validity
from propwhirl.validate import InputError

SOUND = 100.0       # m/s: Mach numbers of tens of m/s cross several table columns


def small_wing(**kw) -> Wing:
    base = dict(semi_span=4.0, root_chord=1.0, mass_per_length=5.0, radius_of_gyration=0.25,
                EI=2e4, GJ=1e4, elastic_axis=0.35, centre_of_gravity=0.45, n_elements=4,
                aero="dlm", dlm_chordwise_panels=2, dlm_spanwise_panels=4)
    base.update(kw)
    return Wing(**base)


def small_model(**kw) -> PropellerWing:
    return PropellerWing(small_wing(**kw), FlightCondition(1.0, speed_of_sound=SOUND),
                         name="small")


# ----------------------------------------------------------------------------- the key
def test_the_default_is_matched_mach():
    assert small_wing().dlm_mach == "speed"


@pytest.mark.parametrize("bad", ["fast", "Speed", -0.1, 0.95, 1.2, float("nan"), float("inf"),
                                 True, None, [0.3], lambda y: y])
def test_bad_dlm_mach_is_a_one_line_error(bad):
    with pytest.raises(InputError) as e:
        small_wing(dlm_mach=bad)
    text = str(e.value)
    assert "\n" not in text and text.startswith("dlm_mach = ")
    assert '"speed"' in text and "[0, 0.9]" in text


@pytest.mark.parametrize("good", [0, 0.0, 0.3, 0.33, 0.9, np.float64(0.5)])
def test_numbers_in_range_are_kept(good):
    assert small_wing(dlm_mach=good).dlm_mach == good


def test_model_file_round_trip_and_old_files():
    pytest.importorskip("tomli_w")
    fixed = small_model(dlm_mach=0.3)
    text = dumps(fixed)
    assert "dlm_mach = 0.3\n" in text
    assert loads(text).wing.dlm_mach == 0.3
    matched = dumps(small_model())
    assert 'dlm_mach = "speed"' in matched and loads(matched).wing.dlm_mach == "speed"
    old = text.replace("dlm_mach = 0.3\n", "")           # a file written before the key
    assert "dlm_mach" not in old and loads(old).wing.dlm_mach == "speed"
    for bad, said in (('"fast"', "speed"), ("1.2", "0.9"), ("-0.5", "0.9")):
        with pytest.raises(InputError) as e:
            loads(text.replace("dlm_mach = 0.3", f"dlm_mach = {bad}"), "m.toml")
        msg = str(e.value)
        assert msg.startswith("m.toml") and "dlm_mach" in msg and said in msg
        assert len(msg.splitlines()) <= 2                 # the file's one error (and header)


# ----------------------------------------------------------------------------- the AICs
def test_fixed_mach_uses_one_column_of_aics():
    """The p-k matrices of three speeds (Mach 0.12, 0.33, 0.47 at a = 100 m/s): matched, the
    tables fill the two Mach columns around each (interpolated linearly), 24 AICs; with
    dlm_mach = 0.2 only the column of Mach 0.2 (the four k nodes around each k)."""
    pytest.importorskip("panelaero")
    from propwhirl.model.aerodynamics import dlm

    def run(model):
        tables = dlm.DlmTables()
        for V in (12.0, 33.0, 47.0):
            dlm.pk_system_dlm(model, V, 1e-3, tables)(2 * np.pi * 3.0)   # k = 0.4-0.08
        return tables.aero(model.wing)

    matched = run(small_model())
    fixed = run(small_model(dlm_mach=0.2))
    assert len(matched.columns) == 6                      # two per speed
    assert matched.evaluations == 3 * 2 * 4               # 4 k nodes in each: 24 AICs
    assert fixed.columns == (pytest.approx(0.2),)
    assert fixed.evaluations <= 3 * 4                     # 9: neighbouring k nodes shared
    # the fixed Mach is a table node: its column is the matched analysis's at V = 0.2 a
    Q = fixed.gaf(0.2, 0.3, exact_mach=True)
    assert np.array_equal(Q, fixed.gaf(0.2, 0.3))


def test_off_node_fixed_mach_is_its_own_column():
    """dlm_mach = 0.33 (between the nodes 0.30 and 0.35): Q of the Mach 0.33 AICs, within the
    linear interpolation's error of the nodes' value, and no node column computed."""
    pytest.importorskip("panelaero")
    from propwhirl.model.aerodynamics import dlm

    aero = dlm.DlmAerodynamics(small_wing(dlm_mach=0.33))
    Q = aero.gaf(0.33, 0.25, exact_mach=True)
    assert aero.columns == (0.33,)
    Qi = aero.gaf(0.33, 0.25)
    assert set(aero.columns) == {0.33, 6 * dlm.MACH_STEP, 7 * dlm.MACH_STEP}
    assert not np.array_equal(Q, Qi)
    assert np.abs(Q - Qi).max() < 0.01 * np.abs(Q).max()


def test_fixed_mach_lifts_the_speed_refusal_and_matched_keeps_it():
    pytest.importorskip("panelaero")
    from propwhirl.analysis.pk import pk_sweep
    from propwhirl.model.aerodynamics import dlm

    with pytest.raises(InputError, match="V = 95 m/s"):
        dlm.check_speed_mach(small_model(), [50.0, 95.0])
    with pytest.raises(InputError, match="Mach = 0.95"):
        pk_sweep(small_model(), [50.0, 95.0])
    dlm.check_speed_mach(small_model(dlm_mach=0.0), [50.0, 95.0, 120.0])   # no error


def test_roger_state_space_at_a_fixed_mach():
    """The Roger coefficients of a fixed Mach are those of its one column at every speed (the
    matched ones change with V/a), and the analysis note says which Mach."""
    pytest.importorskip("panelaero")
    from propwhirl.model.aerodynamics import dlm, dlm_rfa

    tables = dlm.DlmTables()
    fixed = small_model(dlm_mach=0.2)
    V = np.array([10.0, 30.0, 60.0])
    A = dlm_rfa.coefficients(fixed, V, tables=tables)
    assert np.array_equal(A[0], A[1]) and np.array_equal(A[0], A[2])
    assert tables.aero(fixed.wing).columns == (pytest.approx(0.2),)
    assert np.array_equal(A[1], dlm_rfa.coefficients(small_model(), np.array([20.0]))[0])
    matched = dlm_rfa.coefficients(small_model(), V)
    assert not np.allclose(matched[0], matched[2])
    note = dlm_rfa.rfa_note(fixed, V)
    assert "fixed Mach 0.2 (dlm_mach)" in note and "Mach 0.20" in note


# ----------------------------------------------------------------------------- warnings
def test_dlm_wing_warnings_name_no_strip_theory():
    """Events above Mach 0.7 on a matched DLM wing without Houbolt-Reed propellers: the panels
    are compressible there (up to the refused 0.9), so no warning; the strip wing's says the
    incompressible strips are not valid."""
    events = [(80.0, "flutter onset of wing 1")]           # Mach 0.80
    strip = small_model(aero="strip")
    dlm_model = small_model()
    assert any("incompressible strip" in w
               for w in validity.analysis_warnings(strip, (10.0, 85.0), events, True))
    assert validity.analysis_warnings(dlm_model, (10.0, 85.0), events, True) == ()
    assert validity.analysis_warnings(dlm_model, (10.0, 85.0), [], False) == ()


def test_dlm_wing_with_propellers_names_only_their_correction():
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    m = wingtip_propeller_wing()
    m = m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=2,
                                         dlm_spanwise_panels=6))
    a = m.flight.speed_of_sound
    out = validity.analysis_warnings(m, (10.0, 0.85 * a), [(0.8 * a, "flutter onset of x")],
                                     True)
    mach = [w for w in out if "beyond Mach 0.7" in w]
    assert len(mach) == 1 and "Prandtl-Glauert" in mach[0] and "strip" not in mach[0]
    none = validity.analysis_warnings(m, (10.0, 0.85 * a), [], False)
    assert any("no instability" in w and "Prandtl-Glauert" in w for w in none)
    assert not any("strip" in w or "subsonic aerodynamics" in w for w in none)


def test_fixed_mach_far_from_the_event_is_flagged_as_non_matched():
    events = [(60.0, "flutter onset of wing 1")]           # Mach 0.60
    far = validity.analysis_warnings(small_model(dlm_mach=0.0), (10.0, 70.0), events, True)
    assert len(far) == 1 and "fixed Mach 0 (dlm_mach)" in far[0] and "Mach 0.60" in far[0]
    near = validity.analysis_warnings(small_model(dlm_mach=0.6), (10.0, 70.0), events, True)
    assert near == ()
    later = events + [(85.0, "flutter onset of wing 2"), (90.0, "flutter onset of wing 3")]
    (one,) = validity.analysis_warnings(small_model(dlm_mach=0.6), (10.0, 95.0), later, True)
    assert one.startswith("V = 85.00 m/s (flutter onset of wing 2) is Mach 0.85 (1 more such")
