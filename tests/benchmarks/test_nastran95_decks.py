"""The NASTRAN-95 decks of benchmarks/nastran95_decks.py (issue 37, item 2) hold propwhirl's own
model: the small-field reals read back, the SPLINE3 cards are propwhirl's spline times its modes,
the scalar points' mass and stiffness give its frequencies, the FLUTTER SUMMARY is read; with the
optional ``nastran95`` package (Python >= 3.12: ``make bench-nastran95``'s environment) NASTRAN-95
runs a deck and its flutter speed is propwhirl's p-k's."""
import dataclasses
import importlib.util
import re
import sys
from pathlib import Path

import numpy as np
import pytest

BENCH = Path(__file__).resolve().parents[2] / "benchmarks"


def _load(name: str):
    spec = importlib.util.spec_from_file_location(name, BENCH / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules.setdefault(name, mod)               # its dataclasses look their module up
    spec.loader.exec_module(mod)
    return sys.modules[name]


sys.path.insert(0, str(BENCH))
nd = _load("nastran95_decks")
goland = _load("dlm_goland")


def _goland_4x7():
    from propwhirl.model import FlightCondition, PropellerWing
    wing = dataclasses.replace(goland.goland_wing("dlm", (4, 7)), dlm_mach=0.0)
    return PropellerWing(wing, FlightCondition(goland.RHO_SHARPY))


def _read8(text: str) -> float:
    """A NASTRAN small-field real as NASTRAN reads it (an exponent may lack its E)."""
    m = re.fullmatch(r"([-+]?\d*\.\d*)(?:E?([-+]\d+))?", text)
    assert m, text
    return float(m.group(1)) * 10.0 ** int(m.group(2) or 0)


@pytest.mark.parametrize("x", [1.0, -1.0, 0.5, 1e-4, -0.0123456789, 0.987654321, 2318.995389,
                               -3.3e7, 1.2345678e-9, 123456.789, -9.8765e12])
def test_small_field_reals_fit_and_read_back(x):
    text = nd._real8(x)
    assert len(text) <= 8 and "." in text.split("E")[0]
    assert _read8(text) == pytest.approx(x, rel=5e-4)


def _cards(text: str) -> dict[str, list[list[str]]]:
    """Every small-field card of the bulk data, its continuations joined: name -> fields."""
    cards: dict[str, list[list[str]]] = {}
    bulk = text.split("BEGIN BULK\n", 1)[1].split("ENDDATA", 1)[0].splitlines()
    current = None
    for line in bulk:
        if line.startswith("+"):
            current.extend(line[8 + 8 * i:16 + 8 * i].strip() for i in range(8))
            continue
        if "*" in line[:8]:
            current = None
            continue
        current = [line[8 + 8 * i:16 + 8 * i].strip() for i in range(8)]
        cards.setdefault(line[:8].strip(), []).append(current)
    return cards


def test_the_spline_cards_are_propwhirls_spline_on_its_modes():
    """Each box's T3 (−z, up) and R2 (α) coefficients on the scalar points, times their
    scale (the largest coefficient of the mode, 1 in the deck), are propwhirl's spline at the
    box centre times its mass-normalised modes, to the digits of a small field."""
    from propwhirl.model.aerodynamics.dlm_mesh import panel_mesh, spline
    from propwhirl.model.structure.assembly import free_dofs
    model = _goland_4x7()
    text = nd.deck(model, [150.0, 160.0], mach=0.0)
    modes = nd.structural_modes(model, 6)
    mesh = panel_mesh(model.wing)
    Z, S = spline(model.wing, mesh.points(0.5))
    keep = free_dofs(model.wing.n_nodes)
    phi = modes.shapes[:modes.n_bt]
    expect = {3: -(Z[:, keep] @ phi), 5: S[:, keep] @ phi}
    scale = np.maximum(np.abs(expect[3]).max(axis=0), np.abs(expect[5]).max(axis=0))
    splines = _cards(text)["SPLINE3"]
    assert len(splines) == 2 * mesh.n
    for f in splines:
        box, comp = int(f[2]) - nd.CAERO_ID, int(f[3])
        terms = [f[4:7]] + [f[i:i + 3] for i in range(8, len(f), 4) if f[i]]
        coef = np.zeros(6)
        for g, c, a in terms:
            assert c == "1"                  # a scalar point's component: 1 (0 shifts them)
            coef[int(g) - 1] = _read8(a)
        np.testing.assert_allclose(coef * scale, expect[comp][box], rtol=0,
                                   atol=1e-5 * scale.max())


def test_the_scalar_points_have_propwhirls_frequencies():
    """The deck's CMASS2 and CELAS2 (large fields) give the in-vacuo frequencies of propwhirl's
    structure: ω² = k / m for each scalar point."""
    model = _goland_4x7()
    modes = nd.structural_modes(model, 6)
    text = nd.deck(model, [150.0, 160.0], mach=0.0)
    values = {}
    for name in ("CMASS2", "CELAS2"):
        for line in re.findall(rf"^{name}\*.*$", text, flags=re.M):
            fields = [line[8 + 16 * i:24 + 16 * i].strip() for i in range(4)]
            values.setdefault(name, {})[int(fields[2])] = float(fields[1])
    omega = np.sqrt([values["CELAS2"][i] / values["CMASS2"][i] for i in range(1, 7)])
    np.testing.assert_allclose(omega, modes.omega, rtol=1e-8)


SUMMARY = """0                                                       FLUTTER  SUMMARY

       POINT =    2     MACH NUMBER =  0.0001     DENSITY RATIO =  1.0000E+00     METHOD = PK


       KFREQ            1./KFREQ         VELOCITY            DAMPING         FREQUENCY            COMPLEX   EIGENVALUE
        0.4100       2.4390244E+00     1.5000000E+02    -2.0000000E-02     1.1600000E+01    -1.0000000E+00     7.0000000E+01
        0.4000       2.5000000E+00     1.6000000E+02     1.0000000E-02     1.1500000E+01     5.0000000E-01     7.0000000E+01
        0.3900       2.5641026E+00     1.7000000E+02    -1.0000000E-02     1.1400000E+01    -5.0000000E-01     7.0000000E+01
"""


def test_the_flutter_summary_is_read_and_its_crossings_found():
    (point,) = nd.flutter_summary(SUMMARY)
    assert point.point == 2 and list(point.V) == [150.0, 160.0, 170.0]
    cross = nd.crossings([point])
    assert [c[3] for c in cross] == ["onset", "end"]
    assert cross[0][0] == pytest.approx(150.0 + 10.0 * 2 / 3)
    assert cross[0][1] == pytest.approx(11.6 - 0.1 * 2 / 3)
    assert cross[1][0] == pytest.approx(165.0)


def test_nastran95_agrees_with_the_pk_on_the_goland_panels():
    """NASTRAN-95's PK on the 4 x 7 Goland deck (refined 0.05 m/s apart) against propwhirl's
    p-k: flutter speed within 0.03 % (issue 37), frequency within 0.1 %."""
    pytest.importorskip("nastran95", reason="the optional nastran95 package (Python >= 3.12)")
    from propwhirl.analysis.pk import pk_sweep
    model = _goland_4x7()
    res, cpu = nd.run_deck(nd.deck(model, np.arange(158.0, 161.01, 0.05), mach=0.0))
    assert res.completed and cpu > 0
    onsets = [c for c in nd.crossings(nd.flutter_summary(res.output)) if c[3] == "onset"]
    pk = pk_sweep(model, np.arange(120.0, 201.0, 10.0)).critical
    assert onsets[0][0] == pytest.approx(pk.V, rel=3e-4)
    assert onsets[0][1] == pytest.approx(pk.frequency_hz, rel=1e-3)
