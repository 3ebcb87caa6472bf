"""The default analysis of a doublet-lattice wing (issue 37, item 1): the modal Roger state
space tracks, the p-k method converges every crossing, so the default reports the p-k's
critical speed and no critical the p-k does not have.

Before: ``analyse(model)`` on Goland's wing (4 x 7, 8 x 14 panels; 10 and 20 elements) said
"unstable from V = 120 m/s, the start of the range" on bending modes of 150 Hz to 2.1 kHz
(k = 7 to 100, far beyond the fit's k <= 1.78); the full Roger state space ("dense") still
does, and is kept as the fit's own reference."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla

pytest.importorskip("panelaero")

from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.analysis import modal_dlm  # noqa: E402
from propwhirl.analysis.modes import InVacuo  # noqa: E402
from propwhirl.analysis.pk import PKCrossing, pk_crossing, pk_sweep  # noqa: E402
from propwhirl.engine import XTOL  # noqa: E402
from propwhirl.model import FlightCondition, PropellerWing, Wing  # noqa: E402
from propwhirl.model.aerodynamics import dlm, dlm_rfa  # noqa: E402
from propwhirl.model.dlm_modal import ModalRoger, modal_roger  # noqa: E402

RHO = 1.02                                   # SHARPy's Goland case (tests/model/test_dlm_goland)
RANGE = (120.0, 200.0, 10.0)


def goland(nc: int, ns: int, n_elements: int = 10, **flight) -> PropellerWing:
    """Goland's wing (benchmarks/dlm_goland.py) on nc x ns panels at Mach 0."""
    wing = Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71, polar_inertia=8.64,
                EI=9.77e6, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43,
                n_elements=n_elements, aero="dlm", dlm_mach=0.0, dlm_chordwise_panels=nc,
                dlm_spanwise_panels=ns)
    return PropellerWing(wing, FlightCondition(RHO, speed_range=flight.get("range", RANGE)),
                         name=f"goland {nc}x{ns}")


@pytest.fixture(scope="module")
def goland_4x7():
    return goland(4, 7)


@pytest.mark.parametrize("nc, ns, n_elements", [(4, 7, 10), (8, 14, 10), (8, 14, 20)])
def test_default_critical_is_the_pk_critical(nc, ns, n_elements):
    """The issue's meshes: the default's critical is the p-k's (computed 159.39, 165.67,
    165.48 m/s; 11.58, 11.20, 11.19 Hz), within the two analyses' xtol, and no event of the
    default is unstable at the start of the range."""
    m = goland(nc, ns, n_elements)
    a, pk = analyse(m), analyse(m, method="pk")
    assert a.critical is not None and pk.critical is not None
    assert (a.critical.kind, a.critical.event) == (pk.critical.kind, pk.critical.event) \
        == ("flutter", "onset")
    assert a.critical.V == pytest.approx(pk.critical.V, abs=2 * XTOL)
    assert a.critical.frequency_hz == pytest.approx(pk.critical.frequency_hz, rel=1e-4)
    assert not [e for e in a.events if e.event == "unstable-at-start"]
    assert all(e.V >= a.critical.V - 2 * XTOL for e in a.events)
    assert "every crossing converged by the p-k method" in a.warnings[0]


def test_the_full_roger_state_space_has_the_false_criticals(goland_4x7):
    """What the default was: the Roger state space on every DOF finds modes of 150 Hz and more
    unstable at 120 m/s (their k = 7-100 lies beyond the fit and the panels)."""
    dense = analyse(goland_4x7, method="dense")
    start = [e for e in dense.events if e.event == "unstable-at-start"]
    assert start and min(e.frequency_hz for e in start) > 100.0
    assert dense.critical.event == "unstable-at-start"


def test_default_speed_range_from_1_m_s_has_no_false_critical():
    """From 1 m/s (the model's default range starts there: every kept mode's k is far beyond the
    fit at the lowest speeds) the first event is still the flutter onset of the p-k."""
    m = goland(4, 7, range=(1.0, 350.0, 10.0))
    a = analyse(m)
    pk = analyse(goland(4, 7), method="pk")
    assert a.critical.event == "onset" and a.critical.kind == "flutter"
    assert a.critical.V == pytest.approx(pk.critical.V, abs=2 * XTOL)


def test_modal_state_space_with_every_mode_is_the_full_one(goland_4x7):
    """Lift exactness: on a complete modal basis (every in-vacuo mode) the modal Roger system is
    a similarity transform of the full Roger system (x_l = Phi_w z_l solves the full lag
    equation), so the eigenvalues agree."""
    m = goland_4x7
    V = np.array([150.0])
    R = modal_roger(m, V)
    iv = InVacuo.of(m.assembly().without_aerodynamics())
    _, shapes = sla.eigh(iv.K, iv.M)
    full = dataclasses.replace(R, Phi=shapes, frequencies_hz=np.zeros(shapes.shape[1]),
                               ks=tuple(dlm_rfa.fit_ks()))          # the full model's fit
    want = np.sort_complex(np.linalg.eigvals(m.state_matrix(V)[0]))
    got = np.sort_complex(np.linalg.eigvals(full.state_matrix(V)[0]))
    assert got.shape == want.shape
    scale = np.abs(want).max()
    assert np.max(np.abs(got - want)) < 1e-7 * scale
    # and the lift maps a modal eigenvector to a full one
    lam, X = np.linalg.eig(full.state_matrix(V)[0])
    x = full.lift @ X[:, 0]
    A = m.state_matrix(V)[0]
    assert np.linalg.norm(A @ x - lam[0] * x) < 1e-7 * abs(lam[0]) * np.linalg.norm(x)


def test_cut_off_keeps_the_modes_within_the_fit_at_the_top_speed(goland_4x7):
    """The kept modes: those below 3 x f_ref and below the frequency whose k at the top speed is
    the fit's largest (at least six, the p-k's count): 6 of 30 on Goland at 200 m/s."""
    R = modal_roger(goland_4x7, np.array([120.0, 200.0]))
    assert isinstance(R, ModalRoger)
    assert R.r == 6 and R.n_states == 2 * 6 + 4 * 6
    assert np.all(R.frequencies_hz <= max(R.cutoff_hz, R.frequencies_hz[5]) + 1e-9)
    assert R.in_vacuo_hz.size == 30


def test_pk_crossing_none_where_the_pk_keeps_its_sign(goland_4x7):
    """pk_crossing converges a crossing near a start root, and says None where the p-k root
    keeps its sign over the widest bracket (the bending mode at 7.7 Hz, stable throughout)."""
    a = analyse(goland_4x7)
    e = a.critical
    c = pk_crossing(goland_4x7, e.V + 3.0, complex(0.0, 2 * np.pi * e.frequency_hz),
                    lo=120.0, hi=200.0)
    assert isinstance(c, PKCrossing) and c.direction == "onset"
    assert c.V == pytest.approx(e.V, abs=2 * XTOL)
    assert pk_crossing(goland_4x7, 160.0, complex(-1.0, 2 * np.pi * 7.7), lo=120.0,
                       hi=200.0) is None


def test_a_crossing_the_pk_does_not_have_is_noted_not_reported(goland_4x7, monkeypatch):
    """When the p-k finds no crossing near a state-space crossing, the event is not reported
    and a one-line note gives the state space's speed."""
    monkeypatch.setattr(modal_dlm, "pk_crossing", lambda *a, **k: None)
    a = analyse(goland_4x7)
    assert a.critical is None and not a.events
    (note,) = [w for w in a.warnings if "is not a crossing of the p-k method" in w]
    assert note.startswith("V = 15") and "(flutter onset of state-space mode" in note
    assert "\n" not in note


@pytest.mark.parametrize("vgf, columns", [(True, 6), (False, 5)])
def test_the_counted_aics_are_those_the_analysis_computes(monkeypatch, vgf, columns):
    """analyse(model, progress=report) on a wing at Mach V/a (issue 37, item 3): report(done,
    total) from 0 to a total known before the first AIC — the modal state space's fit's 8
    reduced frequencies (dlm_rfa.tracking_ks) in each Mach column of the engine's first speeds (vgf: 140-200 m/s, Mach 0.43-0.61, columns
    0.40-0.65; else 140, 160 and 200 m/s, columns 0.40-0.50 and 0.60-0.65) — each AIC once;
    with or without it the analysis computes the same AICs and finds the same events, bit for
    bit."""
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    from propwhirl.model.aerodynamics import dlm, dlm_cache

    monkeypatch.delenv(dlm_cache.CACHE_ENV, raising=False)
    m = wingtip_propeller_wing()
    m = m.with_(wing=dataclasses.replace(m.wing, n_elements=6, aero="dlm",
                                         dlm_chordwise_panels=3, dlm_spanwise_panels=7))
    speeds = np.arange(140.0, 201.0, 20.0)
    seen: list[tuple[int, int]] = []
    runs = []
    for progress in (None, lambda done, total: seen.append((done, total))):
        tables = dlm.DlmTables()                              # every AIC computed again
        a = analyse(m, speeds, vgf=vgf, progress=progress, dlm_tables=tables)
        runs.append((a, tables.aero(m.wing).evaluations))
    (plain, computed), (counted, computed_counted) = runs
    n = len(dlm_rfa.TRACKING_K_NODES)
    assert seen == [(k, columns * n) for k in range(columns * n + 1)]
    assert computed_counted == computed >= columns * n
    assert [(e.kind, e.event, e.label, e.V, e.frequency_hz) for e in counted.events] == \
        [(e.kind, e.event, e.label, e.V, e.frequency_hz) for e in plain.events]
    assert counted.events and np.array_equal(counted.sweep.eigenvalues, plain.sweep.eigenvalues)


def test_two_state_space_crossings_on_one_pk_root_are_one_event():
    """x57_like on panels (six near-identical propellers): two of the Roger state space's
    whirl-flutter crossings (80.2 and 80.8 m/s) converged onto one p-k root at 79.952 m/s and
    were reported as two events, one named after a mode whose own crossing was 0.8 m/s away;
    then (merged into one, with a note) three others converged onto hops between members,
    "onsets" at 80.34, 80.38 and 80.39 m/s (Re p = +0.0034 1/s there) that the p-k does not
    have, and two of its onsets were missing. Now each crossing follows its own member by
    the state-space mode's shape: one event per p-k root, and the cluster's onsets are the
    p-k sweep's, one to one (measured: within 0.0011 m/s)."""
    from propwhirl.io import load_model

    m = load_model(Path(__file__).resolve().parents[2] / "examples" / "x57_like.toml")
    m = m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_mach=0.24))
    speeds = np.arange(60.0, 100.1, 5.0)
    tables = dlm.DlmTables()
    a = analyse(m, speeds, dlm_tables=tables)
    flutter = [e for e in a.events if e.kind == "flutter" and e.event == "onset"]
    for i, e in enumerate(flutter):
        for f in flutter[i + 1:]:
            assert not (abs(e.V - f.V) <= 2 * XTOL
                        and abs(e.frequency_hz - f.frequency_hz) <= 1e-5 * e.frequency_hz), (e, f)
    assert a.critical.V == pytest.approx(79.952, abs=0.01)
    pk = [f for f in pk_sweep(m, speeds, tables=tables).flutter
          if f.kind == "flutter" and f.event == "onset"]
    assert len(pk) == len(flutter) == 6
    for e, f in zip(flutter, pk):
        assert e.V == pytest.approx(f.V, abs=XTOL)
        assert e.frequency_hz == pytest.approx(f.frequency / (2 * np.pi), rel=1e-4)


def test_a_crossing_converged_onto_another_cluster_members_root_is_named_by_its_shape():
    """x57_like on 4 × 37 panels, Mach-matched over 1-148 m/s: the Roger state space's
    crossing of the mode named "forward whirl, propeller 7" (at the first speed) converges
    onto the p-k root of the backward collective whirl of propellers 1-6 at 79.955 m/s
    (shape and participation: MAC 1.00 with that mode, 0.00 with its own); the critical was
    named after the mode it was found from. Now after the mode of its branch its shape is, and
    never two events under one name."""
    from propwhirl.io import load_model

    m = load_model(Path(__file__).resolve().parents[2] / "examples" / "x57_like.toml")
    m = m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=4))
    a = analyse(m, np.arange(1.0, 150.0, 7.0))
    c = a.critical
    assert c.V == pytest.approx(79.955, abs=0.01)
    assert c.whirl == "backward"
    assert c.label == "backward whirl, propellers 1–6 (1 of 6, collective)"
    labels = [e.label for e in a.events if e.kind == "flutter" and e.event == "onset"]
    assert len(labels) == len(set(labels))
