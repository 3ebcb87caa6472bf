"""Per-propeller participation (issue 11, item 1): each propeller's share of a mode's kinetic
energy, whirl sense, relative amplitude and position, numbered from 1 — checked on a hand
example and on the four-propeller distributed wing."""
from __future__ import annotations

import json

import numpy as np
import pytest

from propwhirl.analysis import analyse, load
from propwhirl.analysis.participation import (ModeParticipation, mass_matrices,
                                              mode_participation, participation)
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller, propeller_wing
from propwhirl.engine import eigen
from propwhirl.model.protocol import DofMap, PropellerDofs

POSITIONS = (1.5, 3.0, 4.5, 5.7)


@pytest.fixture(scope="module")
def four():
    return propeller_wing(POSITIONS, name="four propellers")


@pytest.fixture(scope="module")
def four_analysis(four):
    return analyse(four, vgf=True)


def modes_at(model, V):
    """Every eigen-solution of the model at V with Im λ >= 0 (full-state vectors in columns)."""
    lam, X = eigen(model.state_matrix(np.array([V])))
    keep = lam[0].imag >= 0
    return lam[0][keep], X[0][:, keep]


def test_hand_example():
    """Two wing DOFs and one propeller: the shares are the block energies q_Jᴴ M_JJ q_J over
    their sum; the whirl sense and amplitude those of the θ–ψ orbit."""
    dm = DofMap(q_labels=("node 1 h", "node 1 alpha", "propeller 1 theta", "propeller 1 psi"),
                q_kinds=("h", "alpha", "theta", "psi"), q_node=(1, 1, -1, -1),
                q_propeller=(-1, -1, 0, 0),
                propellers=(PropellerDofs(0, 2, 3, rotation=1, spinning=True, y=2.0, node=1),),
                node_y=(0.0, 2.0))
    M = np.array([[4.0, 0.5, 1.0, 0.0], [0.5, 2.0, 0.0, 0.3], [1.0, 0.0, 3.0, 0.0],
                  [0.0, 0.3, 0.0, 3.0]])
    q = np.array([1.0, 0.5j, 0.4, -0.4j])
    lam = -0.1 + 10j
    p = participation(dm, q, M, [lam], 100.0).mode(0)
    e_wing = (4 * 1 + 2 * 0.25 + 2 * 0.5 * np.real(np.conj(1.0) * 0.5j)).real
    e_prop = 3 * 0.16 + 3 * 0.16
    assert p.wing == pytest.approx(e_wing / (e_wing + e_prop), rel=1e-14)
    (s,) = p.propellers
    assert s.share == pytest.approx(e_prop / (e_wing + e_prop), rel=1e-14)
    assert (s.propeller, s.y, s.amplitude, p.V) == (1, 2.0, 1.0, 100.0)
    assert s.whirl == whirl_sense(0.4, -0.4j, 1, lam)
    assert p.describe() == (f"propeller 1 (y = 2.00 m): {round(100 * s.share)} %, {s.whirl} "
                            f"whirl; wing {100 - round(100 * s.share)} %")
    # the scale and phase of a mode shape change nothing
    p2 = participation(dm, (3 - 2j) * q, M, [lam], 100.0).mode(0)
    assert p2.propellers[0].share == pytest.approx(s.share, rel=1e-13)


def test_shares_of_every_mode_add_to_one(four):
    lam, X = modes_at(four, 200.0)
    part = mode_participation(four, X, lam, 200.0)
    total = part.wing + part.other + part.share.sum(axis=0)
    np.testing.assert_allclose(total, 1.0, rtol=1e-12)
    assert (part.share >= 0).all() and (part.wing >= 0).all()
    assert part.number.tolist() == [1, 2, 3, 4]
    np.testing.assert_allclose(part.y, POSITIONS)
    np.testing.assert_allclose(part.amplitude.max(axis=0), 1.0)
    # the whirl propeller modes are mostly propeller, the first bending mode mostly wing
    assert part.share.sum(axis=0).max() > 0.9 and part.wing.max() > 0.99


def test_a_rigidly_mounted_propeller_has_no_whirl_share():
    """Propeller 2 rigid: it has no θ, ψ, so share 0; the others and the wing add to 1."""
    m = propeller_wing(POSITIONS).with_(propellers=tuple(
        inst if j != 1 else inst.__class__(inst.propeller, inst.y, "rigid")
        for j, inst in enumerate(propeller_wing(POSITIONS).propellers)))
    lam, X = modes_at(m, 200.0)
    part = mode_participation(m, X, lam, 200.0)
    assert part.number.tolist() == [1, 3, 4]
    np.testing.assert_allclose(part.wing + part.share.sum(axis=0), 1.0, rtol=1e-12)
    for k in range(part.n_modes):
        assert part.mode(k).share_of(2) == 0.0


def test_swapping_the_propellers_swaps_their_shares():
    """The same wing with its propellers listed in another order: same modes, and each
    propeller (found by its y) has the same share, amplitude and whirl sense."""
    order = (2, 0, 3, 1)
    a = propeller_wing(POSITIONS)
    b = propeller_wing(tuple(POSITIONS[i] for i in order))
    la, Xa = modes_at(a, 230.0)
    lb, Xb = modes_at(b, 230.0)
    pa = mode_participation(a, Xa, la, 230.0)
    pb = mode_participation(b, Xb, lb, 230.0)
    osc = np.flatnonzero((la.imag > 1.0) & (np.abs(la) < 300))    # well separated low modes
    assert osc.size > 8
    for k in osc:
        kb = int(np.argmin(np.abs(lb - la[k])))
        assert abs(lb[kb] - la[k]) < 1e-8 * abs(la[k])
        for jb in range(4):            # propeller jb + 1 of b sits at a's propeller order[jb] + 1
            ja = order[jb]
            assert pb.y[jb] == pa.y[ja]
            assert pb.share[jb, kb] == pytest.approx(pa.share[ja, k], rel=1e-6, abs=1e-12)
            assert pb.whirl[jb, kb] == pa.whirl[ja, k]
    # and the numbers follow the list order: b's propeller 1 is a's propeller 3
    assert pb.number.tolist() == [1, 2, 3, 4] and pb.y[0] == POSITIONS[2]


def test_every_event_carries_the_participation(four_analysis):
    a = four_analysis
    assert a.events
    for e in a.events:
        p = e.participation
        assert isinstance(p, ModeParticipation) and len(p.propellers) == 4
        assert p.wing + sum(s.share for s in p.propellers) == pytest.approx(1.0, rel=1e-12)
        assert p.V == pytest.approx(e.V, abs=0.02)
        if e.kind == "flutter":          # the event's whirl is that of the leading propeller
            assert e.whirl == p.leading.whirl and p.leading.amplitude == 1.0
    flutter = [e for e in a.events if e.kind == "flutter" and e.event == "onset"]
    assert flutter


def test_the_summary_numbers_propellers_from_1(four_analysis):
    text = four_analysis.summary()
    assert "propeller 0" not in text
    for j, y in enumerate(POSITIONS, start=1):
        assert f"propeller {j} (y = {y:.2f} m): " in text
    lines = [ln.strip() for ln in text.splitlines() if ln.strip().startswith("propeller 3 ")]
    assert len(lines) == len(four_analysis.events)       # one line per event and propeller
    assert all(ln.split(": ")[1].split(" %")[0].isdigit() for ln in lines)
    last = text.splitlines()[-1]        # the critical wing divergence: no propeller moves
    assert last.startswith("  critical: divergence of wing 1") and "propeller share 0 %; wing 100 %" in last


def test_isolated_propeller_is_all_propeller():
    a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    p = a.critical.participation
    assert p.wing == 0.0 and p.propellers[0].share == pytest.approx(1.0)
    assert p.propellers[0].y is None and p.propellers[0].whirl == a.critical.whirl == "backward"
    assert a.critical.propeller_text() == "propeller 1: 100 %, backward whirl"


def test_participation_in_the_file_and_the_csv(four_analysis, tmp_path):
    a = four_analysis
    path = tmp_path / "a.json"
    a.save(path)
    doc = json.loads(path.read_text())
    props = doc["events"][0]["participation"]["propellers"]
    assert [p["propeller"] for p in props] == [1, 2, 3, 4]
    assert load(path).events == a.events
    csv = a.events_csv(tmp_path / "e.csv").splitlines()
    assert csv[0] == ("kind,event,mode,label,V [m/s],frequency_hz [Hz],propeller,y [m],share,"
                      "whirl,amplitude,wing_share")
    assert len(csv) == 1 + 4 * len(a.events)
    assert (tmp_path / "e.csv").read_text().splitlines() == csv
    rows = [r.split(",") for r in csv[1:5]]
    assert [r[6] for r in rows] == ["1", "2", "3", "4"]
    assert sum(float(r[8]) for r in rows) + float(rows[0][11]) == pytest.approx(1.0)


def test_bad_participation_in_a_file_is_refused(four_analysis, tmp_path):
    from propwhirl.validate import InputError

    doc = json.loads(json.dumps(four_analysis.to_dict()))
    doc["events"][0]["participation"]["propellers"][0]["whirl"] = "sideways"
    path = tmp_path / "a.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match=r"events\[0\]\.participation\.propellers\[0\]\.whirl"):
        load(path)


def test_mass_is_structural(four):
    """The shares use the model's mass without aerodynamic apparent mass (symmetric)."""
    M = mass_matrices(four, [100.0, 300.0])
    np.testing.assert_array_equal(M[0], M[0].T)
    np.testing.assert_array_equal(M[0], M[1])
