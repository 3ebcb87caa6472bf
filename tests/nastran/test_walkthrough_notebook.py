"""examples/nastran_walkthrough.ipynb (issue 36, "a notebook takes a BDF to a V-g-f plot and a
campaign"): run from top to bottom on an IPython kernel here, where pyNastran is (the main
environment's notebook tests skip it, naming this environment), with the checks of
tests/examples/test_notebooks.py (no error, its figure a PNG image) and what it says."""
from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

pytest.importorskip("nbclient", reason="the notebooks extra (nbclient, ipykernel) is part of "
                    ".venv-nastran's stamp (make test-nastran)")
pytest.importorskip("ipykernel")

TESTS = Path(__file__).resolve().parents[1]
NOTEBOOK = TESTS.parent / "examples" / "nastran_walkthrough.ipynb"


def _notebook_checks():
    spec = importlib.util.spec_from_file_location(
        "notebook_checks", TESTS / "examples" / "test_notebooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_walkthrough_takes_the_bdf_to_a_vgf_plot_and_a_campaign():
    checks = _notebook_checks()
    said = checks.check_outputs(checks.run(NOTEBOOK), NOTEBOOK.stem)
    # the deck as read: 13 elements, the two hinged mounts' springs and the rotors' CONM2
    assert "wing: 13 elements, semi-span 5.7 m, EI 7e+05 N m^2, GJ 2e+05 N m^2" in said
    assert said.count("flexible mount, K_theta = 9e+04 and K_psi = 7e+04 N m/rad, rotor "
                      "8.0 kg, spin inertia 1.548 kg m^2") == 2
    assert "the stick's axial motion (T_y, free at 13 grids) is not modelled" in said
    # its analysis, the campaign of three cases at two altitudes, and the report
    assert "critical: divergence of wing 1 (bending) at 141.92 m/s" in said
    assert re.search(r"forward whirl, propellers 1.2 .* 181\.24", said)
    # CS-25 at V_D = 100 m/s EAS: the least margin the wing's divergence at 3000 m
    assert re.search(r"^nominal +cleared +3000 .* 133\.49 +145\.91 +\+12\.41 ", said, flags=re.M)
    assert re.search(r"^mount stiffness at 50 % +cleared ", said, flags=re.M)
    assert re.search(r"^rotation reversed +cleared ", said, flags=re.M)
    assert "3 of 3 cases cleared; 6 analyses: CLEARED" in said
    assert re.search(r"report\.html: [\d,]+ bytes\ncleared\n", said)
