"""Valid inputs at the edges of their ranges stay cheap (issue 20, item 9): the work of an
analysis is bounded by counting it (eigen-solutions, tracker nodes, hump refinements, cluster
continuations), never by the clock.

* ``rayleigh_lambda_s = 1.0`` (its range maximum): every mode above 2/λ rad/s is over-damped
  and its slow root tends to −1/λ; the wing's modes leave a near-multiple root at −1 s⁻¹,
  split by rounding into real roots and pairs of |Im λ| ~ 1e-9 … 1e-3.  The tracker flagged
  every step there and refined towards ``min_step`` (690 s and 777 MB for the wingtip model).
* ``EI_chordwise_N_m2 = 1e14`` (its range maximum): in-plane modes of |λ| up to 1e8 1/s; the
  rounding noise of their finite-difference slopes (≈ 1 1/s in the trapezoidal mismatch) kept
  the hump check's uncertainty above their |Re λ| ≈ 3e-3 1/s, and it refined every step
  (586 nodes, 34 s and 2.3 GB).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import propwhirl.engine.clusters as clusters
from propwhirl.analysis import analyse
from propwhirl.engine.options import TrackingOptions
from propwhirl.io import load_model

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "wingtip.toml"


def _wingtip(tmp_path, n_elements: int, *, lam: float = 0.0, ei_chordwise: float | None = None,
             top: float = 350.0):
    """The wingtip example with fewer elements, Rayleigh λ, in-plane rigidity, a shorter range."""
    text = EXAMPLE.read_text()
    text = text.replace("n_elements = 25", f"n_elements = {n_elements}")
    text = text.replace("rayleigh_lambda_s = 0.0", f"rayleigh_lambda_s = {lam!r}")
    text = text.replace("    350.0,", f"    {top!r},")
    if ei_chordwise is not None:
        text = text.replace("EI_N_m2 = 700000.0",
                            f"EI_N_m2 = 700000.0\nEI_chordwise_N_m2 = {ei_chordwise!r}")
    path = tmp_path / f"wingtip_{n_elements}_{lam}_{ei_chordwise}_{top}.toml"
    path.write_text(text)
    return load_model(path)


@pytest.fixture
def cluster_trials(monkeypatch):
    """Counts the clusters the linking tries to follow as a set."""
    count = {"n": 0}
    original = clusters._try_cluster

    def counted(*args, **kwargs):
        count["n"] += 1
        return original(*args, **kwargs)

    monkeypatch.setattr(clusters, "_try_cluster", counted)
    return count


def _onsets(a):
    return [(e.kind, e.event, e.V) for e in a.events]


def test_sink_roots_are_the_overdamped_ones():
    from propwhirl.engine.linking import SINK_IM, _sink

    lam = np.array([-1.0 + 1e-9j, -1.0 - 1e-9j, -1.0, -0.997 + 0.0039j, -1.0 + 0.5j, 1.0,
                    1.0 + 1e-9j, -1e-3 + 1.0j, 0.0])
    assert _sink(lam).tolist() == [True, True, True, True, False, False, False, False, False]
    edge = -2.0 + 2.0 * SINK_IM * 1j
    assert bool(_sink(np.array([edge]))[0]) and not bool(_sink(np.array([edge * (1 - 1e-3j)]))[0])


def test_rayleigh_lambda_at_its_maximum_is_not_refined(tmp_path, cluster_trials):
    """λ = 1 s over 1–60 m/s, 12 elements: today 3 eigen-solutions like the undamped model;
    before, 63 and 510 cluster continuations (refinement down to min_step at −1 s⁻¹)."""
    plain = analyse(_wingtip(tmp_path, 12, top=60.0))
    cluster_trials["n"] = 0
    damped = analyse(_wingtip(tmp_path, 12, lam=1.0, top=60.0))
    assert damped.sweep.stats["eig"] <= plain.sweep.stats["eig"] + 2
    assert damped.sweep.stats.get("refined", 0) <= 2
    assert cluster_trials["n"] <= 4
    assert damped.sweep.unresolved == ()
    assert _onsets(damped) == _onsets(plain) == []


def test_rayleigh_damping_keeps_the_divergence_speed(tmp_path, cluster_trials):
    """Divergence is static: damping does not move it.  6 elements, 1–350 m/s: with λ = 1 s
    the divergence of the undamped model to the accuracy xtol, in fewer nodes than it."""
    plain = analyse(_wingtip(tmp_path, 6))
    plain_trials, cluster_trials["n"] = cluster_trials["n"], 0
    damped = analyse(_wingtip(tmp_path, 6, lam=1.0))
    div = [e.V for e in damped.events if e.kind == "divergence" and e.event == "onset"]
    ref = [e.V for e in plain.events if e.kind == "divergence" and e.event == "onset"]
    assert len(div) == 1 and div[0] == pytest.approx(ref[0], abs=0.02)
    assert damped.sweep.stats["nodes"] <= plain.sweep.stats["nodes"]
    assert cluster_trials["n"] <= plain_trials


def test_in_plane_rigidity_at_its_maximum_is_not_refined(tmp_path):
    """EI_chordwise = 1e14 N m² (|λ| up to 1e8 1/s), 12 elements: the events of the model
    rigid in its plane, to the accuracy xtol, in about as many nodes (before: 105 nodes, 93 of
    them hump refinements)."""
    rigid = analyse(_wingtip(tmp_path, 12), method="dense")      # the full order's |λ|
    stiff = analyse(_wingtip(tmp_path, 12, ei_chordwise=1e14), method="dense")
    assert np.abs(stiff.sweep.eigenvalues).max() > 1e7          # the case: in-plane |λ| ~ 1e8
    assert stiff.sweep.stats["hump_refined"] <= rigid.sweep.stats["hump_refined"] + 2
    assert stiff.sweep.stats["nodes"] <= rigid.sweep.stats["nodes"] + 5
    a, b = _onsets(stiff), _onsets(rigid)
    assert [x[:2] for x in a] == [x[:2] for x in b]
    assert np.allclose([x[2] for x in a], [x[2] for x in b], atol=0.01)


def test_the_hump_check_still_refines_a_hidden_crossing():
    """The noise allowance leaves the hump check working where it matters: a flutter hump
    between two stable samples (Re λ = −0.5 + 0.01 (V − 50)² ... ) is still found."""
    from propwhirl.engine import analyse as engine_analyse

    def state_matrix(V):            # ẍ + c(V) ẋ + 400 x = 0, c < 0 for 45 < V < 55 m/s
        V = np.asarray(V, dtype=float)
        A = np.zeros((V.size, 2, 2))
        A[:, 0, 1] = 1.0
        A[:, 1, 0] = -400.0
        A[:, 1, 1] = -(0.01 * (V - 50.0) ** 2 - 0.25)
        return A

    an = engine_analyse(state_matrix, np.array([1.0, 100.0]), n_dof=1,
                        options=TrackingOptions())
    V = sorted(p.V for p in an.criticals.points)
    assert len(V) == 2 and V[0] == pytest.approx(45.0, abs=0.02) \
        and V[1] == pytest.approx(55.0, abs=0.02)
