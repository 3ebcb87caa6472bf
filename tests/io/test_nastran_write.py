"""NASTRAN bulk data out (issue 36, item 5), in any environment: the deck's text, its fields,
and the models it refuses (one line naming the field).  Reading the deck back needs pyNastran:
tests/nastran/test_round_trip.py (`make test-nastran`)."""
from __future__ import annotations

import dataclasses

import pytest
from hypothesis import given
from hypothesis import strategies as st

from propwhirl import InputError
from propwhirl.cases import registry
from propwhirl.io.nastran_write import Card, _real, card_text, deck, write_bdf


@given(st.floats(min_value=-1e300, max_value=1e300))
def test_every_real_fits_a_large_field_with_a_decimal_point(x):
    """Eleven significant digits at least (ten with a three-digit exponent, beyond 1e±99)."""
    text = _real(x)
    assert len(text) <= 16 and "." in text
    rel = 5e-11 if x == 0 or 1e-99 <= abs(x) < 1e100 else 5e-10
    assert _float(text) == pytest.approx(x, rel=rel, abs=1e-320)


def _float(text: str) -> float:
    """NASTRAN's real: the exponent's E may be left out (1.5-3 is 1.5E-3)."""
    import re

    return float(re.sub(r"(?<=[0-9.])([+-])(?=[0-9]+$)", r"E\1", text))


@pytest.mark.parametrize("x, text", [(0.1, "0.1"), (2.0, "2."), (1e-5, "1.E-05"),
                                     (70898.86380875538, "70898.8638087554"),
                                     (-0.0, "-0."), (1 / 3, "0.33333333333333")])
def test_reals_are_the_shortest_text_that_fits(x, text):
    assert _real(x) == text


def test_a_card_in_large_field_format():
    text = card_text(Card("CONM2", (1001, 1001, 0, 8.0, 0.0, 0.0, 0.0, None, 1.5)))
    assert text == ("CONM2*              1001            1001               0              8.\n"
                    "*                     0.              0.              0.\n"
                    "*                    1.5\n")
    assert all(len(line) <= 72 for line in text.splitlines())


def test_the_deck_of_the_wingtip_model():
    d = deck(registry.case_model("wingtip"))
    assert d.hubs == (1001,) and d.units == "si"
    lines = d.text.splitlines()
    assert lines[0].startswith("$ propwhirl ") and "SOL 103" in lines and lines[-1] == "ENDDATA"
    names = [c.name for c in d.cards]
    assert names.count("GRID") == 26 + 2 + 4 and names.count("CBEAM") == 25
    assert names.count("CELAS2") == 2 and names.count("SPC1") == 1
    assert "--hubs 1001" in d.text
    assert d.text == deck(registry.case_model("wingtip")).text      # deterministic
    d.text.encode("ascii")                                          # plain ASCII


def test_units_scale_the_numbers():
    si = deck(registry.case_model("wingtip"))
    mm = deck(registry.case_model("wingtip"), "mm-t-s")
    y_si = [c.fields[4] for c in si.cards if c.name == "GRID"]
    y_mm = [c.fields[4] for c in mm.cards if c.name == "GRID"]
    assert y_mm == pytest.approx([1000 * y for y in y_si])
    with pytest.raises(InputError, match="units = 'furlongs' is invalid"):
        deck(registry.case_model("wingtip"), "furlongs")


def test_refused_models_name_why():
    with pytest.raises(InputError, match="IsolatedPropeller is not a beam model"):
        deck(registry.case_model("isolated-propeller"))
    model = registry.case_model("wingtip")
    inst = model.propellers[0]
    small = dataclasses.replace(inst.propeller, inertia={"I_theta_P": 1.0})
    with pytest.raises(InputError, match=r"propellers\[0\].propeller.inertia: I_theta_P = 1.0 "
                                         "kg m\\^2 is less than its point masses give"):
        deck(model.with_(propellers=(dataclasses.replace(inst, propeller=small),)))
    light = dataclasses.replace(inst.propeller, inertia={"M_P": 1.0})
    with pytest.raises(InputError, match="M_P = 1.0 kg is not more than its point masses'"):
        deck(model.with_(propellers=(dataclasses.replace(inst, propeller=light),)))


def test_write_bdf_writes_the_deck(tmp_path):
    path = tmp_path / "w.bdf"
    d = write_bdf(registry.case_model("two-propeller"), path, "in-lbf-s")
    assert path.read_text() == d.text and d.hubs == (1001, 2001)
