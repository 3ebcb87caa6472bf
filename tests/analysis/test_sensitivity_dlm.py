"""A doublet-lattice wing's sensitivities (issue 34 item 2, "exact where derivatives exist,
central differences otherwise, said which"): central differences of the crossing's root —
the p-k root of the default method's crossings, the Roger state space's of a dense analysis —
every perturbed model reading the analysis's doublet-lattice tables (no AIC computed per
parameter), checked against re-analyses (``verify_sensitivities``, ``--verify``).  The
capability table's sample: 4 elements, 2 x 4 panels."""
from __future__ import annotations

import json

import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.analysis.sensitivity import critical_sensitivities, sensitivity_parameters
from propwhirl.app import cli
from propwhirl.app.capability_table import _beam
from propwhirl.io import save_model
from propwhirl.model import derivatives as D
from propwhirl.model.aerodynamics.dlm import DlmTables, geometry_key
from propwhirl.model.parameter_paths import parameter_paths, with_parameter
from propwhirl.model.protocol import capabilities
from propwhirl.studies.sensitivity_check import verify_sensitivities


@pytest.fixture(scope="module")
def dlm():
    m = _beam("dlm")
    tables = DlmTables()
    return m, tables, analyse(m, dlm_tables=tables)


def _flutter(a):
    return min((e for e in a.events if e.kind == "flutter" and e.event == "onset"),
               key=lambda e: e.V)


def test_the_contract_gives_central_differences_of_the_panels_parameters(dlm):
    m, _, _ = dlm
    c = capabilities(m)
    assert c.supports("sensitivity") and not c.supports("exact-sensitivity")
    assert c.derivatives == "central difference"
    ps = parameter_paths(m)
    assert ps == sensitivity_parameters(m) and {p.derivative for p in ps} == {"central difference"}
    paths = {p.path for p in ps}
    assert {"wing.GJ[0]", "wing.GJ*", "flight.density",
            "propellers[0].propeller.f_theta"} <= paths
    # the strips' and the panels' own parameters are left out: each variant keeps the panels
    assert not any(q.startswith(("wing.lift_slope", "wing.chord", "wing.elastic_axis",
                                 "wing.aerodynamic_centre", "wing.root_chord")) for q in paths)
    for p in ps:
        changed = with_parameter(m, p, p.value * 1.01 if p.value else 0.01)
        assert geometry_key(changed.wing) == geometry_key(m.wing), p.path
    # the same paths as the strip wing's exact ones, but for those
    strip = {p.path for p in D.parameters(_beam())}
    assert paths - {"wing.EI*", "wing.GJ*", "wing.mass_per_length*", "flight.density"} < strip


def test_the_pk_roots_differences_compute_no_aic_per_parameter(dlm):
    m, tables, a = dlm
    aero = tables.aero(m.wing)
    e = _flutter(a)
    n0 = aero.evaluations
    one = critical_sensitivities(m, a, e, params=["wing.GJ*"], dlm_tables=tables)
    n1 = aero.evaluations
    every = critical_sensitivities(m, a, e, dlm_tables=tables)
    assert aero.evaluations == n1 and n1 - n0 <= 8         # 38 more parameters: no AIC more
    assert len(every.sensitivities) == len(parameter_paths(m)) > 30
    assert {s.derivative for s in every.sensitivities} == {"central difference (p-k)"}
    gj = next(s for s in every.sensitivities if s.path == "wing.GJ*")
    assert gj.dV_dp == pytest.approx(one.sensitivities[0].dV_dp, rel=1e-12)
    # the factor is the sum of its elements' (each GJ[e] times its value): one derivative
    elements = sum(s.dV_dp * s.value for s in every.sensitivities if s.path.startswith("wing.GJ["))
    assert elements == pytest.approx(gj.dV_dp, rel=1e-4)


@pytest.mark.parametrize("kind", ["divergence", "flutter"])
def test_pk_sensitivities_match_reanalyses(dlm, kind):
    m, tables, a = dlm
    e = a.critical if kind == "divergence" else _flutter(a)
    assert e.kind == kind
    cs = critical_sensitivities(m, a, e, dlm_tables=tables)
    check = verify_sensitivities(m, a, cs, top=4, dlm_tables=tables)
    assert check.passed, check.format()
    rel = [abs(c.rel_diff) for c in check.checks]
    assert max(rel) < 5e-3, check.format()


def test_a_dense_analysis_differences_the_roger_state_matrix(dlm):
    m, tables, _ = dlm
    a = analyse(m, dlm_tables=tables, method="dense")
    e = _flutter(a)
    cs = critical_sensitivities(m, a, e, params=["wing.GJ*", "flight.density"],
                                dlm_tables=tables)
    assert {s.derivative for s in cs.sensitivities} == {"central difference"}
    check = verify_sensitivities(m, a, cs, method="dense", dlm_tables=tables)
    assert check.passed, check.format()


def test_the_sensitivity_command_on_a_dlm_wing_says_which_and_verifies(tmp_path, capsys):
    f = tmp_path / "dlm.toml"
    save_model(_beam("dlm"), f)
    code = cli.main(["sensitivity", str(f), "--top", "3", "--verify", "--json",
                     str(tmp_path / "s.json")])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "central difference (p-k)" in out and "all 3 within tolerance" in out
    saved = json.loads((tmp_path / "s.json").read_text())
    ds = {s["derivative"] for s in saved["sensitivities"]["sensitivities"]}
    assert ds == {"central difference (p-k)"}
    assert [c["status"] for c in saved["checks"]] == ["ok"] * 3
    assert np.isfinite([c["dV_dp_fd_m_s_per_unit"] for c in saved["checks"]]).all()
    assert cli.main(["sensitivity", str(f), "--list"]) == 0
    listed = capsys.readouterr().out
    assert "wing.GJ[0]  [N m^2]  torsional rigidity of element 0  (central difference)" in listed
