"""The doublet-lattice wing in the time domain (issue 23, item 3b): Roger's rational-function
state space (propwhirl.model.aerodynamics.dlm_rfa) assembled by PropellerWing.second_order and analysed by
``analyse(model)`` ("auto" / "dense"), against the p-k method on the same Q(k)."""
import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

pytest.importorskip("panelaero")

from propwhirl.analysis import analyse, critical_sensitivities  # noqa: E402
from propwhirl.analysis.pk import pk_sweep  # noqa: E402
from propwhirl.analysis.stability import ModelAnalysis  # noqa: E402
from propwhirl.engine import XTOL  # noqa: E402
from propwhirl.cases.ch07_patil import patil_model  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.model.aerodynamics import dlm, dlm_cache, dlm_rfa  # noqa: E402
from propwhirl.studies.gradients import CriticalSpeed  # noqa: E402
from propwhirl.studies import sweeps as sweeps_module  # noqa: E402
from propwhirl.studies.sweeps import sweep  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

PATIL_SPEEDS = np.arange(20.0, 36.0, 4.0)
WINGTIP_SPEEDS = np.arange(120.0, 241.0, 20.0)


def patil_dlm(nc=4, ns=16):
    m = patil_model(10)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=nc,
                                            dlm_spanwise_panels=ns))


def small_wingtip(nc=3, ns=8):
    """The thesis's wingtip model (§10.1) on 6 elements and coarse panels (112 states)."""
    m = wingtip_propeller_wing()
    return m.with_(wing=dataclasses.replace(m.wing, n_elements=6, aero="dlm",
                                            dlm_chordwise_panels=nc, dlm_spanwise_panels=ns))


def test_state_space_is_the_roger_fit_of_the_tables_at_mach_v_over_a():
    """Between two Mach nodes the runtime's A(V) (fits at the nodes, linear in Mach) is
    dlm_rfa.state_matrix of roger_fit at V / a itself: the least squares is linear in Q and
    the tables' Q linear in Mach."""
    m = patil_dlm(2, 8)                   # an identity: the coarsest panels will do
    mach = 0.0737
    V = mach * m.flight.speed_of_sound
    fit = dlm_rfa.roger_fit(m, mach, dlm_rfa.fit_ks())
    want = dlm_rfa.state_matrix(m, fit, [V])[0]
    got = m.state_matrix([V])[0]
    assert got.shape == want.shape
    assert np.allclose(got, want, rtol=1e-9, atol=1e-9 * np.abs(want).max())
    dm = m.dof_map()
    nw = 3 * (m.wing.n_nodes - 1)
    assert dm.n_states == got.shape[0] == 2 * dm.n_dof + len(dlm_rfa.DEFAULT_LAGS) * nw
    assert dm.w_labels[0] == "node 1 h lag 1" and dm.w_labels[-1].endswith("alpha lag 4")
    assert fit.entry_error.shape == (nw, nw) and np.nanmax(fit.entry_error) >= fit.error


def test_state_space_roots_are_the_pk_roots_near_the_axis():
    """Every p-k root with damping ratio < 0.1 has an eigenvalue of A(V) within 1 % of it.
    On the axis the p-k is exact and the two differ by the fit's error (0.5 % of max |Q|)
    times the aerodynamic share of the root (computed: <= 0.5 %); away from it the p-k's
    harmonic Q(ik) is not the Laplace-domain Q(s), so heavily damped roots are not compared."""
    m = patil_dlm()
    for V in (15.0, 27.0):
        lam = np.linalg.eigvals(m.state_matrix([V])[0])
        roots = pk_sweep(m, [V, V + 1.0], n_modes=4).roots[0]
        near = [p for p in roots if -p.real < 0.1 * abs(p)]
        assert len(near) >= 2
        for p in near:
            assert np.min(np.abs(lam - p)) < 0.01 * abs(p)


def test_analyse_dlm_auto_is_the_roger_state_space_with_pk_events(tmp_path):
    """The flutter of the Patil wing on panels: the full Roger state space ("dense") 26.89 m/s,
    the p-k 27.21 m/s.  Tolerance 2 % on V, 1 % on f for the state space: the flutter root of
    A(V) is 0.2 % from the p-k root at 27 m/s, and the slow damping slope of this mode turns
    that into ~1 % in V.  The default (the modal state space, its crossings converged by the
    p-k, issue 37) is the p-k's speed within the two analyses' xtol."""
    m = patil_dlm()
    a = analyse(m, speeds=PATIL_SPEEDS)
    assert a.doublet_lattice and a.finite_state is None
    note = a.warnings[0]
    assert note.startswith(dlm_rfa.RFA_NOTE) and "4 chordwise x 16 spanwise" in note
    assert "(Roger state space of doublet-lattice wing aerodynamics)" in a.summary().splitlines()[0]
    back = ModelAnalysis.load(a.save(tmp_path / "a.json"))
    assert back.doublet_lattice and back.summary() == a.summary()
    pk = analyse(m, speeds=PATIL_SPEEDS, method="pk")
    (e,), (p,) = ([x for x in an.events if x.kind == "flutter" and x.event == "onset"]
                  for an in (a, pk))
    assert e.label == p.label == "wing 3"
    assert e.V == pytest.approx(p.V, abs=2 * XTOL)
    assert e.frequency_hz == pytest.approx(p.frequency_hz, rel=1e-4)
    (d,) = [x for x in analyse(m, speeds=PATIL_SPEEDS, method="dense").events
            if x.kind == "flutter" and x.event == "onset"]
    assert d.label == "wing 3"
    assert d.V == pytest.approx(p.V, rel=0.02)
    assert d.frequency_hz == pytest.approx(p.frequency_hz, rel=0.01)


def test_wingtip_events_close_to_pk():
    """Divergence, backward and forward whirl flutter of the (small) wingtip model: every
    event of the default (the modal Roger state space, its crossings converged by the p-k,
    issue 37) at the p-k's speed and frequency; before, the state space's own were within 2 %
    in V and 1 % in f of them (+0.2 %, +0.2 %, -1.0 % in V); the same whirl senses and
    propeller participation."""
    m = small_wingtip()
    a = analyse(m, speeds=WINGTIP_SPEEDS)
    assert a.doublet_lattice and a.finite_state is None           # the state space, not p-k
    pk = analyse(m, speeds=WINGTIP_SPEEDS, method="pk")

    def onsets(an):
        return {(e.kind, e.whirl): e for e in an.events if e.event == "onset"}

    got, want = onsets(a), onsets(pk)
    assert set(got) == set(want) == {("divergence", None), ("flutter", "backward"),
                                     ("flutter", "forward")}
    for key, p in want.items():
        e = got[key]
        assert e.V == pytest.approx(p.V, abs=2 * XTOL)
        assert e.frequency_hz == pytest.approx(p.frequency_hz, rel=1e-4, abs=1e-9)
        if e.kind == "flutter":
            assert e.participation.leading.share == pytest.approx(
                p.participation.leading.share, abs=0.05)


def test_study_reuses_the_aics_across_variants(monkeypatch):
    """A mount-frequency sweep of three variants (same planform) on the state space computes
    the table AICs of about one analysis: one fit per Mach node it spans, each on the tracking
    fit's k (dlm_rfa.tracking_ks), and the AICs the p-k convergence of the crossings adds, all
    within those columns' tables (at most fit_ks().size each) — not three times the fits'
    AICs.  Each crossing is then converged at its own Mach (issue 37 item 5): on the fine
    columns 0.001 of Mach apart around it, the cubic's four k nodes around the crossing's k
    (two crossings share the column at Mach 0.46 here: eight)."""
    monkeypatch.delenv(dlm_cache.CACHE_ENV, raising=False)
    m = small_wingtip(3, 9)
    speeds = np.arange(140.0, 201.0, 20.0)
    made = []                              # the study's tables: the one DlmTables it makes
    monkeypatch.setattr(sweeps_module, "DlmTables",
                        lambda: made.append(dlm.DlmTables()) or made[-1])
    seen = []                              # and the tables each of its analyses was given
    real = sweeps_module.analyse
    monkeypatch.setattr(sweeps_module, "analyse",
                        lambda *a, **kw: seen.append(kw["dlm_tables"]) or real(*a, **kw))
    r = sweep(m, "propellers[0].propeller.f_theta", [4.0, 5.5, 7.0], speeds=speeds)
    assert list(r.kind) == ["divergence"] * 3
    (tables,) = made
    assert len(seen) == 3 and all(t is tables for t in seen)
    aero = tables.aero(m.wing)
    on_node = [key for key in aero.table_nodes
               if abs(key[0] / dlm.MACH_STEP - round(key[0] / dlm.MACH_STEP)) < 1e-9]
    own = [key for key in aero.table_nodes if key not in on_node]
    assert aero.evaluations == len(on_node) + len(own)
    nodes = len(dlm_rfa.fits_used(m, speeds))
    assert nodes == 6                                       # Mach 0.40 to 0.65
    fits = nodes * dlm_rfa.tracking_ks().size               # 6 Mach nodes x 8 k
    assert fits <= len(on_node) <= nodes * dlm_rfa.fit_ks().size < 3 * fits
    per_column = {}
    for mach, _ in own:
        per_column[mach] = per_column.get(mach, 0) + 1
    assert own and max(per_column.values()) <= 8
    fine = np.array(sorted(per_column)) / dlm.MACH_FINE
    assert np.allclose(fine, np.round(fine), rtol=0, atol=1e-6)


def test_a_dlm_wings_sensitivities_are_central_differences_and_gradients_refused():
    """Issue 34 item 2: a doublet-lattice wing's sensitivities are central differences of its
    crossing's p-k root, said so on every row (was: refused, R5); the gradients for
    optimisation stay exact-only and refuse it in one line naming the paths and why."""
    m = patil_dlm()
    a = analyse(m, speeds=PATIL_SPEEDS)
    s = critical_sensitivities(m, a)
    assert s.sensitivities and {x.derivative for x in s.sensitivities} == {
        "central difference (p-k)"}
    with pytest.raises(InputError, match=r"^paths \['wing.GJ\[0\]'\] have no exact "
                                         r"derivatives \(the doublet-lattice[^\n]*$"):
        CriticalSpeed(m, ["wing.GJ[0]"])


def test_mach_beyond_the_tables_refused_before_any_aic():
    m = patil_dlm(3, 11)
    tables = dlm.DlmTables()
    top = 0.95 * m.flight.speed_of_sound
    with pytest.raises(InputError, match=r"Mach = 0.95 \(V = .* m/s\) is invalid for aero = 'dlm'"):
        analyse(m, speeds=[10.0, 20.0, top], dlm_tables=tables)
    assert len(tables) == 0


@settings(max_examples=12, deadline=None, derandomize=True)
@given(st.floats(0.5, 1.2 * dlm.MACH_MAX * 330.8027446243564))
def test_any_speed_gives_a_finite_state_matrix_or_one_line_error(V):
    """Any airspeed: A(V) finite with its lag roots -(V/b) beta_l on the lag states' diagonal,
    or (above Mach 0.9) a one-line InputError naming the Mach number."""
    m = patil_dlm(2, 8)
    try:
        A = m.state_matrix([V])[0]
    except InputError as exc:
        assert "\n" not in str(exc) and "is invalid for aero = 'dlm'" in str(exc)
        assert V > dlm.MACH_MAX * m.flight.speed_of_sound
        return
    assert V <= dlm.MACH_MAX * m.flight.speed_of_sound * (1 + 1e-12)
    assert np.all(np.isfinite(A))
    dm = m.dof_map()
    lagdiag = np.diag(A)[2 * dm.n_dof:]
    b = dlm.DlmAerodynamics(m.wing).b_ref
    want = -np.repeat(np.asarray(dlm_rfa.DEFAULT_LAGS) * V / b, 3 * (m.wing.n_nodes - 1))
    assert np.allclose(lagdiag, want)


def test_events_beyond_the_fitted_k_are_flagged():
    """A 49 Hz event at 2 m/s has k = 2 pi f b / V = 96 on b_ref = 0.625 m, far beyond the
    fitted k <= 1.78: noted; the same mode at 200 m/s (k = 0.96) is not."""
    from types import SimpleNamespace

    m = small_wingtip()
    low, high = (SimpleNamespace(kind="flutter", event="onset", label="wing 4", V=V,
                                 frequency_hz=49.0) for V in (2.0, 200.0))
    (note,) = dlm_rfa.extrapolation_notes(m, [low, high])
    assert note.startswith("V = 2.00 m/s (flutter onset of wing 4): reduced frequency k = 96.2 "
                           "beyond the Roger fit's k <= 1.78")
    assert "\n" not in note


def test_the_fit_note_is_of_the_fits_the_analysis_used():
    """Issue 33, item 8: the fit-quality note reported whatever fits the tables held (the Patil
    wing's 'worst fit error 0.52 %' became '0.73 %' after an unrelated column_fit call); it
    is now that of the fits over the analysis's own speeds and reduced frequencies."""
    m = patil_dlm()
    for method in ("dense", "auto"):
        tables = dlm.DlmTables()
        before = analyse(m, speeds=PATIL_SPEEDS, method=method, dlm_tables=tables).warnings[0]
        aero = tables.aero(m.wing)
        # unrelated fits at the analysis's own Mach nodes (0.05-0.15), over other k (to 5)
        for mach in (0.05, 0.1, 0.15):
            dlm_rfa.column_fit(aero, mach, ks=dlm_rfa.fit_ks(5.0))
        after = analyse(m, speeds=PATIL_SPEEDS, method=method, dlm_tables=tables).warnings[0]
        assert after == before and "worst fit error" in after
