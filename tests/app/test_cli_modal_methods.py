"""The p-k method, ``sensitivity`` and ``boundary`` on modal models (issue 34 item 2): the modal
model of *all* the beam model's modes with a grid at every node (``write_modes``, own mounts) is
the beam model (tests/app/test_cli_modal_commands.py), so each gives the beam model's numbers:
the p-k crossings within two XTOL brackets, the sensitivities (central differences of the modal
model's state matrix against the beam model's exact derivatives) to 1e-3, the neutral-stability
curve's points to 1e-6 Hz."""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.analysis.sensitivity import (CriticalSensitivities, critical_sensitivities,
                                            difference_parameters)
from propwhirl.app import cli
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io import load_modal_model, save_model, write_modes
from propwhirl.model import Installation, PropellerWing

XTOL2 = 0.02     # [m/s] two crossings, each refined to XTOL = 0.01 m/s
PROP = "propellers[0].propeller."


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("modal_methods")
    save_model(wingtip_propeller_wing(), d / "beam.toml")
    write_modes(wingtip_propeller_wing(), d / "modal.toml")          # every mode, own mounts
    return d / "beam.toml", d / "modal.toml"


def _run(capsys, *argv) -> str:
    assert cli.main([str(a) for a in argv]) in (0, 1)
    return capsys.readouterr().out


def test_pk_on_a_modal_model_is_the_beam_models(tmp_path):
    """A small wing (8 elements, the tip propeller) to bound the p-k's work."""
    wing = baseline_wing(8)
    beam = PropellerWing(wing, baseline_flight(),
                         (Installation(baseline_propeller(), float(wing.node_y[-1])),),
                         name="small")
    write_modes(beam, tmp_path / "m.toml")
    modal = load_modal_model(tmp_path / "m.toml")
    speeds = np.arange(120.0, 321.0, 20.0)
    a, b = (analyse(m, speeds=speeds, method="pk") for m in (beam, modal))
    assert a.finite_state is not None and b.finite_state is not None
    assert [(e.kind, e.event, e.label) for e in b.events] == \
        [(e.kind, e.event, e.label) for e in a.events]
    assert any(e.kind == "flutter" for e in a.events)
    for x, y in zip(a.events, b.events):
        assert abs(x.V - y.V) <= XTOL2 and abs(x.frequency_hz - y.frequency_hz) < 1e-3


def test_sensitivities_of_a_modal_model_are_the_beam_models(files):
    beam, modal = wingtip_propeller_wing(), load_modal_model(files[1])
    params = [PROP + p for p in ("f_theta", "f_psi", "damping_theta", "damping_psi",
                                 "spin_inertia")] + ["flight.density"]
    out = []
    for m in (beam, modal):
        a = analyse(m)
        e = next(e for e in a.events if e.kind == "flutter")
        out.append(critical_sensitivities(m, a, e, params=params))
    exact, diff = out
    assert abs(exact.V - diff.V) <= XTOL2
    assert {s.derivative for s in exact.sensitivities} == {"exact"}
    assert {s.derivative for s in diff.sensitivities} == {"central difference"}
    for s, t in zip(exact.sensitivities, diff.sensitivities):
        assert s.path == t.path and t.dV_dp == pytest.approx(s.dV_dp, rel=1e-3), s.path


def test_a_mode_frequencys_sensitivity_is_the_reanalysed_difference(files):
    """structure.frequencies_hz[1] has no beam counterpart: against (V(f + δ) − V(f − δ)) / 2δ
    of two analyses (δ = 0.2 Hz: the crossings' 0.01 m/s is 0.025 m/s per Hz)."""
    modal = load_modal_model(files[1])
    a = analyse(modal)
    e = next(e for e in a.events if e.kind == "flutter")
    path = "structure.frequencies_hz[1]"
    (s,) = critical_sensitivities(modal, a, e, params=[path]).sensitivities
    (p,) = [p for p in difference_parameters(modal) if p.path == path]
    from propwhirl.analysis.sensitivity import with_difference_value
    V = []
    for sign in (1, -1):
        b = analyse(with_difference_value(modal, p, p.value + sign * 0.2))
        V.append(next(x for x in b.events if x.kind == "flutter" and x.label == e.label).V)
    assert s.dV_dp == pytest.approx((V[0] - V[1]) / 0.4, rel=2e-2)
    assert s.dV_dp > 1.0                                # 4.73 m/s per Hz


def test_a_damping_ratio_of_zero_is_a_forward_difference(files):
    from dataclasses import replace

    modal = load_modal_model(files[1])
    s = modal.structure
    undamped = modal.with_(structure=replace(s, damping_ratio=np.zeros(s.n_modes)))
    a = analyse(undamped)
    e = next(e for e in a.events if e.kind == "flutter")
    cs = critical_sensitivities(undamped, a, e, params=["structure.damping_ratio[0]",
                                                        "structure.frequencies_hz[0]"])
    assert [x.derivative for x in cs.sensitivities] == ["forward difference",
                                                        "central difference"]
    assert np.all(np.isfinite([x.dV_dp for x in cs.sensitivities]))


def test_the_sensitivity_command_on_a_modal_model(files, capsys, tmp_path):
    _, modal = files
    out = _run(capsys, "sensitivity", modal, "--top", 4, "--json", tmp_path / "s.json")
    assert "central difference" in out and "derivative" in out
    cs = CriticalSensitivities.load(tmp_path / "s.json")
    assert {s.derivative for s in cs.sensitivities} == {"central difference"}
    listed = _run(capsys, "sensitivity", modal, "--list").splitlines()
    assert ("structure.frequencies_hz[0]  [Hz]  natural frequency of mode 1  (central "
            "difference)") in listed
    assert any(ln.startswith(PROP + "f_theta") for ln in listed)
    assert cli.main(["sensitivity", str(modal), "--plot", str(tmp_path / "p.png")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "a modal model has none" in err


def test_the_boundary_of_a_modal_model_is_the_beam_models(files, capsys, tmp_path):
    rows = []
    for f in files:
        _run(capsys, "boundary", f, "--params", PROP + "f_theta", PROP + "f_psi", "--speed", 160,
             "--bounds", 5, 9, 4, 9, "--oscillatory", "--csv", tmp_path / f"{f.stem}.csv")
        with open(tmp_path / f"{f.stem}.csv") as fh:
            rows.append(np.array([[float(x) for x in r[2:5]] for r in list(csv.reader(fh))[1:]]))
    assert rows[0].shape[0] >= 5 and rows[0].shape == rows[1].shape
    np.testing.assert_allclose(rows[1], rows[0], atol=1e-6, rtol=0)
    assert 7.0 < rows[0][:, 0].min() < rows[0][:, 0].max() < 7.5     # f_θ on the curve [Hz]


def test_verify_checks_a_modal_models_central_differences(files, capsys):
    """--verify re-analyses the modal model at p ± h through the studies' paths and finds the
    state-matrix difference within tolerance (the column says what it checks)."""
    _, modal = files
    argv = ["sensitivity", modal, "--param", "structure.frequencies_hz[1]", "--verify"]
    assert cli.main([str(a) for a in argv]) == 0
    out = capsys.readouterr().out
    assert "dV/dp (diff. of A)" in out and "all 1 within tolerance" in out
