"""Aerodynamic lag roots are not modes (issue 37, item 4): which roots are structural is decided
in one place (``naming.structural_roots``), and names, "(k of n)" counts, contents and events
are of the structural modes only — on the Roger state space of a doublet-lattice wing, whose lag
roots split into complex pairs, as on strip models, whose lag roots are real."""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.io.model_files import load_model
from propwhirl.model.flight import FlightCondition
from propwhirl.model.systems import PropellerWing
from propwhirl.model.structure.wing import Wing

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: the high-lift propellers' whirl flutter near 80 m/s, coarse
DLM_SPEEDS = np.arange(20.0, 161.0, 20.0)


def is_lag(name: str) -> bool:
    """A lag root's name ("lag 3", its partner "lag 3'"; ``naming.is_lag``, spelt out here so
    that each test fails on its assertion, not an import, on the code before it)."""
    return name.split(" ", 1)[0] == "lag"


def _x57_dlm() -> PropellerWing:
    """examples/x57_like.toml (six high-lift propellers, a tip cruise propeller) on 12 elements
    with doublet-lattice aerodynamics on 3 x 12 panels."""
    m = load_model(EXAMPLES / "x57_like.toml")
    wing = replace(m.wing, aero="dlm", dlm_chordwise_panels=3, dlm_spanwise_panels=12,
                   n_elements=12)
    return replace(m, wing=wing)


def _goland() -> PropellerWing:
    """Goland's wing on strips (10 elements, Leishman-Nguyen), density 1.02 kg/m^3."""
    wing = Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71, polar_inertia=8.64,
                EI=9.77e6, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43, n_elements=10)
    return PropellerWing(wing, FlightCondition(1.02), name="goland")


@pytest.fixture(scope="module")
def x57_dlm():
    return _x57_dlm()


def _places(names, head: str) -> list[str]:
    """The "(k of n)" of the names starting with ``head``: ['1 of 6', ...]."""
    return sorted(n[len(head):].strip(" ()").split(",")[0] for n in names if n.startswith(head))


@pytest.mark.parametrize("method", ["auto", "dense"])
def test_dlm_wing_names_and_counts_only_its_structural_modes(x57_dlm, method):
    """The modal Roger state space (auto) has r structural modes, the full one (dense) one per
    DOF; the six high-lift propellers have six backward and six forward whirl modes and the tip
    propeller one of each (computed before: "(k of 8)", "(k of 10)" and "(1 of 2)", "(3 of 3)"
    with auto, "(23 of 23)", "(20 of 20)" with dense: Roger lag roots counted as modes)."""
    a = analyse(x57_dlm, DLM_SPEEDS, method=method)
    sw = a.sweep
    named = [n for k, n in enumerate(sw.mode_labels) if sw.physical[0, k] and not is_lag(n)]
    r = sw.stats.get("reduced_r", a.dof_map.n_dof) if method == "auto" else a.dof_map.n_dof
    assert len(named) == len(set(named)) == r
    for sense in ("backward", "forward"):
        assert _places(named, f"{sense} whirl, propellers 1–6") == [f"{k} of 6"
                                                                    for k in range(1, 7)]
        assert f"{sense} whirl, propeller 7" in named      # one of its sense: no "(k of n)"
    assert set(a.content) == set(named)                 # contents of the structural modes only
    assert a.events and not any(is_lag(e.label) for e in a.events)
    assert a.critical.label.startswith("backward whirl, propellers 1–6 (")


def test_the_vgf_legend_counts_structural_modes_only(x57_dlm):
    """The V-g-f's "<family>: n other modes" (computed before: "backward whirl: 5 other
    modes", "forward whirl: 7 other modes" of 8 backward and 10 forward whirl names)."""
    pytest.importorskip("matplotlib")
    from propwhirl.app.plots.vgf_plot import vgf

    a = analyse(x57_dlm, np.arange(20.0, 161.0, 10.0), vgf=True)
    legend = [t.get_text() for t in vgf(a).legends[0].get_texts()]
    sw = a.sweep
    for family in ("backward whirl", "forward whirl"):
        structural = sum(1 for k, n in enumerate(sw.mode_labels) if sw.physical[0, k]
                         and n.startswith(family.split()[0]))
        bold = sum(1 for t in legend if t.startswith(family + ","))
        other = [int(t.split(": ")[1].split()[0]) for t in legend
                 if t.startswith(f"{family}: ")]
        assert bold + sum(other) <= structural == 7, (family, legend)


@pytest.mark.parametrize("method", ["pk", "dense"])
def test_goland_divergence_is_named_after_its_structural_mode(method):
    """Goland's wing on strips diverges at 276.19 m/s (density 1.02) on a real branch that
    starts as a lag state ("lag 6" at the first speed, the name the event had before); it is
    named after the structural mode its shape is — wing 1, 95 % of its kinetic energy (the
    bending the lift drives) — and keeps the id of the branch that crossed."""
    a = analyse(_goland(), np.arange(10.0, 301.0, 10.0), method=method)
    (div,) = [e for e in a.events if e.kind == "divergence"]
    assert div.V == pytest.approx(276.19, abs=0.02)
    assert div.label == "wing 1" and is_lag(a.sweep.mode_labels[div.mode])
    assert a.describe(div.label) == "wing 1 (bending)"
    flutter = [e for e in a.events if e.kind == "flutter"]
    assert [e.label for e in flutter] == ["wing 2"]


def test_on_strips_the_structural_roots_are_the_oscillatory_ones():
    """The one rule gives strip models what their real lag roots gave before: at the first
    speed the structural roots are the physical oscillatory ones, one per DOF."""
    from propwhirl.analysis.naming import is_lag as named_lag
    from propwhirl.analysis.naming import structural_roots

    m = load_model(EXAMPLES / "wingtip.toml")
    a = analyse(m, np.arange(10.0, 251.0, 40.0), method="dense")
    sw = a.sweep
    lam = sw.eigenvalues[0]
    structural = structural_roots(m, sw)
    oscillatory = sw.physical[0] & (np.abs(lam.imag) > 0)
    assert np.array_equal(structural & sw.physical[0], oscillatory)
    assert oscillatory.sum() == a.dof_map.n_dof
    assert [named_lag(n) for n in sw.mode_labels] == list(~structural)
