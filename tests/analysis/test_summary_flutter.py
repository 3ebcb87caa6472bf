"""The flutter summary (issue 11, item 2) and the one text-table layout (tabulate, or the
built-in formatter giving the same text)."""
from __future__ import annotations

import csv
import io
import random

import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.analysis.summary import Reference, flutter_summary, reference, text_table
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def wingtip():
    return analyse(wingtip_propeller_wing(), vgf=True)


def test_columns_follow_from_the_eigenvalues(wingtip):
    s = wingtip.flutter_summary()
    c = s.columns
    model = wingtip_propeller_wing()
    b = model.wing.root_chord / 2
    assert s.reference.b_ref == b and "root semichord" in s.reference.b_ref_is
    lam = c["real"] + 1j * c["imag"]
    np.testing.assert_allclose(c["k"], np.abs(lam.imag) * b / c["V"], rtol=1e-14)
    np.testing.assert_allclose(c["g"], 2 * c["zeta"], rtol=0)
    np.testing.assert_allclose(c["zeta"], -lam.real / np.abs(lam), rtol=1e-12)
    np.testing.assert_allclose(c["frequency_hz"], np.abs(lam.imag) / (2 * np.pi), rtol=1e-14)
    np.testing.assert_allclose(c["mach"], c["V"] / model.flight.speed_of_sound, rtol=1e-14)
    assert (c["density"] == model.flight.density).all()
    # the sign convention: g < 0 exactly where Re λ > 0 (unstable)
    assert ((c["g"] < 0) == (lam.real > 0)).all() and (lam.real > 0).any()
    assert len(s) == int(wingtip.sweep.physical.sum())


def test_text_states_b_ref_and_the_sign_convention(wingtip):
    s = wingtip.flutter_summary()
    text = s.format(["forward 1"])
    head = "\n".join(text.splitlines()[:3])
    assert "b_ref = 0.625 m (root semichord of the wing)" in head
    assert "g = 2 zeta" in head and "g < 0 UNSTABLE" in head and "NASTRAN" in head
    assert "mode 2: forward 1" in text and "wing 1" not in text
    rows = [ln for ln in text.splitlines() if ln.strip()[:1].isdigit()]
    assert len(rows) == int(wingtip.sweep.physical[:, 2].sum())
    with pytest.raises(InputError, match="'wing 99' is not a physical mode"):
        s.format(["wing 99"])


def test_csv_round_trip(wingtip, tmp_path):
    s = wingtip.flutter_summary()
    text = s.to_csv(tmp_path / "s.csv")
    assert (tmp_path / "s.csv").read_text() == text
    rows = list(csv.DictReader(io.StringIO(text)))
    assert list(rows[0]) == ["mode", "label", "V_m_per_s", "k", "inv_k", "zeta", "g",
                             "frequency_hz", "density_kg_per_m3", "mach", "real_per_s",
                             "imag_per_s"]
    assert len(rows) == len(s)
    np.testing.assert_array_equal([float(r["g"]) for r in rows], s.columns["g"])
    assert all(r["inv_k"] == "" for r, k in zip(rows, s.columns["k"]) if k == 0)


def test_dataframe(wingtip):
    pytest.importorskip("pandas")
    df = wingtip.flutter_summary().to_dataframe()
    assert df.shape == (len(wingtip.flutter_summary()), 12)
    assert df.attrs["units"]["V_m_per_s"] == "m/s" and "UNSTABLE" in df.attrs["convention"]


def test_reference_of_each_model_kind():
    r = reference(isolated_baseline_propeller())
    assert r.b_ref_is == "propeller radius R" and r.b_ref == 0.762
    with pytest.raises(InputError, match="b_ref"):
        Reference(0.0, "x", 1.0, 340.0)
    with pytest.raises(InputError, match="must be a Reference"):
        flutter_summary(analyse(isolated_baseline_propeller(), [100.0, 200.0]).sweep, None)


def test_a_loaded_analysis_keeps_its_reference(wingtip, tmp_path):
    from propwhirl.analysis import load

    wingtip.save(tmp_path / "a.json")
    back = load(tmp_path / "a.json")
    assert back.reference == wingtip.reference
    assert back.flutter_summary().to_csv() == wingtip.flutter_summary().to_csv()


def test_text_table_is_the_same_with_and_without_tabulate():
    pytest.importorskip("tabulate")
    rng = random.Random(7)
    for _ in range(500):
        nc, nr = rng.randint(1, 6), rng.randint(0, 5)
        heads = ["".join(rng.choice("ab c[]/") for _ in range(rng.randint(1, 10)))
                 for _ in range(nc)]
        rows = [[rng.choice("xy1.-é") + "".join(rng.choice("xy 1.-é") for _ in range(rng.randint(0, 12)))
                 for _ in range(nc)] for _ in range(nr)]
        align = "".join(rng.choice("lr") for _ in range(nc))
        assert (text_table(rows, heads, align, use_tabulate=True)
                == text_table(rows, heads, align, use_tabulate=False))


def test_text_table_layout():
    text = text_table([["wing 1", "1.809"], ["forward 1", "17.000"]], ["mode", "f [Hz]"], "lr",
                      use_tabulate=False)
    assert text.splitlines() == ["mode         f [Hz]", "---------  --------",
                                 "wing 1        1.809", "forward 1    17.000"]
    with pytest.raises(InputError, match="align"):
        text_table([["a"]], ["x"], "c")
