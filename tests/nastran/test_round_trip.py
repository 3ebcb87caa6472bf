"""NASTRAN bulk data out and back (issue 36, item 5): any beam model written as a SOL 103
deck is read by pyNastran card for card, and propwhirl → BDF → propwhirl gives the same
model: the same structural M and K (to 1e-10 of their largest entries: the deck's 16-character fields) and in-vacuo frequencies (to 1e-9), in every
unit system, for the thesis's wings and the examples (tip, inboard and seven propellers,
stations, a rigid mount, a wing bending in its plane, a measured propeller inertia)."""
from __future__ import annotations

import contextlib
import dataclasses
import io
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sl

from propwhirl.analysis.modes import in_vacuo_of
from propwhirl.cases import registry
from propwhirl.io import load_model
from propwhirl.io.nastran_read import read_bdf
from propwhirl.io.nastran_write import write_bdf

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _variants():
    wingtip = registry.case_model("wingtip")
    inst = wingtip.propellers[0]
    measured = dataclasses.replace(inst.propeller, inertia={"M_P": 45.0, "S_theta_P": -41.0,
                                                            "I_theta_P": 40.0, "I_psi_P": 39.0})
    out = {
        "patil (no propeller)": registry.case_model("patil"),
        "wingtip": wingtip,
        "two-propeller": registry.case_model("two-propeller"),
        "x57-like (7 propellers, stations)": load_model(EXAMPLES / "x57_like.toml"),
        "rigid mount": wingtip.with_(propellers=(dataclasses.replace(inst, mount="rigid"),)),
        "in-plane bending": wingtip.with_(wing=dataclasses.replace(
            wingtip.wing, EI_chordwise=4.0e6)),
        "measured inertia": wingtip.with_(propellers=(dataclasses.replace(
            inst, propeller=measured),)),
    }
    return out


VARIANTS = _variants()


def accurate_frequencies(model) -> np.ndarray:
    """The in-vacuo frequencies [Hz] of propwhirl's structural M, K (the InVacuo of
    propwhirl.analysis), each from the eigenproblem that resolves it: the lower half from
    M x = mu K x (mu = 1/omega^2), the upper half from K x = lambda M x.  (One eigh of
    K, M alone gives the lowest modes only to about 1e-9 of the highest: its rounding, not
    the model.)"""
    iv = in_vacuo_of(model)
    lam = sl.eigh(iv.K, iv.M, eigvals_only=True)
    low = 1.0 / sl.eigh(iv.M, iv.K, eigvals_only=True)[::-1]
    half = lam.size // 2
    return np.sqrt(np.concatenate([low[:half], lam[half:]])) / (2 * np.pi)


@pytest.mark.parametrize("units", ["si", "mm-t-s", "in-lbf-s"])
@pytest.mark.parametrize("name", list(VARIANTS))
def test_propwhirl_bdf_propwhirl_is_the_same_model(tmp_path, name, units):
    model = VARIANTS[name]
    deck = write_bdf(model, tmp_path / "m.bdf", units)
    notes: list[str] = []
    back = read_bdf(tmp_path / "m.bdf", units=units, base=model, hubs=deck.hubs, notes=notes)
    assert notes == []                           # nothing of the deck left out
    a, b = in_vacuo_of(model), in_vacuo_of(back)
    assert a.q_labels == b.q_labels
    np.testing.assert_allclose(b.M, a.M, rtol=0, atol=1e-10 * np.abs(a.M).max())
    np.testing.assert_allclose(b.K, a.K, rtol=0, atol=1e-10 * np.abs(a.K).max())
    fa, fb = accurate_frequencies(model), accurate_frequencies(back)
    np.testing.assert_allclose(fb, fa, rtol=1e-9)
    assert back.wing.node_y == pytest.approx(model.wing.node_y, abs=1e-12)
    assert [i.mount for i in back.propellers] == [i.mount for i in model.propellers]
    assert [i.y for i in back.propellers] == pytest.approx([i.y for i in model.propellers])


def test_the_structure_comes_from_the_deck_not_the_base(tmp_path):
    """Read with another wing's structure as the base (stiffer, heavier, another mesh), the
    deck's model is the written one, not the base's."""
    model = VARIANTS["two-propeller"]
    deck = write_bdf(model, tmp_path / "m.bdf")
    other = dataclasses.replace(model.wing, EI=2.0 * model.wing.EI, GJ=3.0 * model.wing.GJ,
                                mass_per_length=1.5 * model.wing.mass_per_length, n_elements=10,
                                semi_span=4.0)
    inst = [dataclasses.replace(i, y=min(i.y, 4.0), propeller=dataclasses.replace(
        i.propeller, f_theta=3.0, f_psi=4.0, pivot_pitch=-0.3)) for i in model.propellers]
    base = model.with_(wing=other, propellers=tuple(inst))
    back = read_bdf(tmp_path / "m.bdf", units="si", base=base, hubs=deck.hubs)
    np.testing.assert_allclose(accurate_frequencies(back), accurate_frequencies(model),
                               rtol=1e-9)
    assert not np.allclose(accurate_frequencies(base)[:3], accurate_frequencies(model)[:3])


def _parsed(path: Path):
    from pyNastran.bdf.bdf import BDF
    from cpylog import SimpleLogger

    bdf = BDF(log=SimpleLogger(level="critical"))
    with contextlib.redirect_stdout(io.StringIO()):
        bdf.read_bdf(str(path), xref=False)
    return bdf


def _stored(bdf, card):
    name, key = card.name, card.fields[0]
    if name == "GRID":
        return bdf.nodes[key]
    if name in ("CBEAM", "CELAS2"):
        return bdf.elements[key]
    if name == "PBEAM":
        return bdf.properties[key]
    if name == "MAT1":
        return bdf.materials[key]
    if name == "CONM2":
        return bdf.masses[key]
    if name == "RBE2":
        return bdf.rigid_elements[key]
    if name == "SPC1":
        return bdf.spcs[key][0]
    if name == "EIGRL":
        return bdf.methods[key]
    if name == "PARAM":
        return bdf.params[key]
    raise AssertionError(name)


def _blank(x) -> bool:
    return x is None or x == "" or (isinstance(x, (int, float)) and x == 0)


@pytest.mark.parametrize("name", ["x57-like (7 propellers, stations)", "in-plane bending",
                                  "measured inertia", "rigid mount"])
def test_pynastran_reads_the_deck_back_card_for_card(tmp_path, name):
    deck = write_bdf(VARIANTS[name], tmp_path / "m.bdf", "in-lbf-s")
    bdf = _parsed(tmp_path / "m.bdf")
    counts = {}
    for card in deck.cards:
        counts[card.name] = counts.get(card.name, 0) + 1
    assert {k: v for k, v in bdf.card_count.items() if k != "ENDDATA"} == counts
    for card in deck.cards:
        fields = _stored(bdf, card).raw_fields()
        assert fields[0] == card.name
        read = list(fields[1:])
        written = list(card.fields) + [None] * max(0, len(read) - len(card.fields))
        assert len(read) >= len(card.fields), (card, fields)
        for k, (w, r) in enumerate(zip(written, read)):
            where = (card.name, card.fields[0], k + 2)
            if w is None:
                assert _blank(r) or card.name == "MAT1", (where, r)   # MAT1: NU from E, G
            elif isinstance(w, float):
                assert r == pytest.approx(w, rel=1e-10, abs=1e-300), (where, w, r)
            else:
                assert r == w, (where, w, r)


def test_the_deck_has_executive_and_case_control(tmp_path):
    deck = write_bdf(VARIANTS["wingtip"], tmp_path / "m.bdf")
    bdf = _parsed(tmp_path / "m.bdf")
    assert bdf.sol == 103
    subcase = bdf.case_control_deck.subcases[0]
    assert subcase.params["SPC"][0] == 1 and subcase.params["METHOD"][0] == 1
    assert deck.hubs == (1001,)


def test_pynastran_reads_reals_without_the_exponents_e(tmp_path):
    """The writer leaves out the E of an exponent where that gains a digit (-3.6519707064+16,
    NASTRAN's form): pyNastran reads it as NASTRAN does."""
    from propwhirl.io.nastran_write import Card, card_text

    xyz = (-3.6519707063651976e16, -1.0 / 3.0 * 1e-5, 1.2345678901234567e-12)
    text = card_text(Card("GRID", (1, None, *xyz)))
    assert "E" not in text.splitlines()[0][40:]             # written without E
    (tmp_path / "g.bdf").write_text(text + "ENDDATA\n")
    from pyNastran.bdf.bdf import BDF
    from cpylog import SimpleLogger

    bdf = BDF(log=SimpleLogger(level="critical"))
    bdf.read_bdf(str(tmp_path / "g.bdf"), xref=False, punch=True)
    np.testing.assert_allclose(bdf.nodes[1].xyz, xyz, rtol=5e-11)
