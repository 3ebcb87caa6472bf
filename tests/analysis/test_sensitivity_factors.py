"""analysis.sensitivity (issue 25.7): the studies' whole-distribution factors (wing.EI*,
wing.GJ*, wing.mass_per_length*) and flight.density have exact sensitivities, checked against
central differences of the full-order root at the critical speed on models built by the
studies' own paths; positions are normalised by a stated physical scale; `propwhirl
sensitivity --param` computes only the paths asked for and refuses an unknown one in one line,
before any analysis."""
import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.analysis import sensitivity as S
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.engine.correction import full_order_root
from propwhirl.studies import paths as P
from propwhirl.validate import InputError

NEW = ["wing.EI*", "wing.GJ*", "wing.mass_per_length*", "flight.density"]


@pytest.fixture(scope="module")
def flutter():
    m = wingtip_propeller_wing()
    a = analyse(m)
    e = min((e for e in a.events if e.kind == "flutter" and e.event == "onset"),
            key=lambda e: e.V)
    point = next(p for p in a.criticals.points if p.mode == e.mode and abs(p.V - e.V) < 1e-6)
    return m, a, e, point


def _root(model, V, lam, x):
    F, E = model.second_order_blocks(np.array([V])).pencil(0)
    return full_order_root(F, E, lam, x)[0]


@pytest.mark.parametrize("path", NEW)
def test_factors_and_density_match_differences_of_the_root(flutter, path):
    """∂λ/∂p at the critical speed against (λ(p + h) − λ(p − h)) / 2h of the full-order root,
    the models built by the studies' paths (the scale form multiplies every element)."""
    m, a, e, point = flutter
    cs = S.critical_sensitivities(m, a, e, params=[path])
    s = cs.sensitivities[0]
    p0 = 1.0 if path.endswith("*") else m.flight.density
    h = 1e-4 * p0
    lam = [_root(P.set_value(m, path, p0 + d), cs.V, cs.eigenvalue, point.eigenvector)
           for d in (h, -h)]
    fd = (lam[0] - lam[1]) / (2 * h)
    assert abs(s.dlam_dp - fd) <= 1e-4 * abs(fd), (path, s.dlam_dp, fd)
    assert s.value == p0 and s.dV_dp == pytest.approx(-s.dlam_dp.real / cs.dlam_dV.real)


def test_a_factor_is_the_sum_over_its_elements(flutter):
    m, a, e, _ = flutter
    n = m.wing.element_count
    per = [f"wing.GJ[{k}]" for k in range(n)]
    cs = S.critical_sensitivities(m, a, e, params=["wing.GJ*", *per])
    by = {s.path: s for s in cs.sensitivities}
    total = sum(by[p].value * by[p].dV_dp for p in per)
    assert by["wing.GJ*"].dV_dp == pytest.approx(total, rel=1e-12)
    assert by["wing.GJ*"].normalised == pytest.approx(sum(by[p].normalised for p in per),
                                                      rel=1e-9)


def test_positions_are_normalised_by_a_stated_scale(flutter):
    m, a, e, _ = flutter
    paths = ["propellers[0].propeller.masses[0].x", "propellers[0].propeller.pivot_pitch",
             "wing.elastic_axis[24]", "propellers[0].propeller.f_theta"]
    cs = S.critical_sensitivities(m, a, e, params=paths)
    by = {s.path: s for s in cs.sensitivities}
    R = m.propellers[0].propeller.radius
    for p in paths[:2]:          # a pivot at 0 m had normalised 0, a mass at −0.86 m flipped sign
        s = by[p]
        assert s.scale == R and s.per == f"propeller radius R = {R:.4g} m"
        assert s.normalised == pytest.approx(R / cs.V * s.dV_dp)
    assert by["wing.elastic_axis[24]"].scale == 1.0 and by["wing.elastic_axis[24]"].per == "the chord"
    f = by["propellers[0].propeller.f_theta"]
    assert f.scale is None and f.normalised == pytest.approx(f.value / cs.V * f.dV_dp)
    text = cs.format()
    assert "propeller radius R = " in text and "the chord" in text
    back = S.CriticalSensitivities.from_dict(cs.to_dict())
    assert set(back.sensitivities) == set(cs.sensitivities)        # saved ranked, scales kept


def test_unknown_parameters_are_one_line_errors_before_the_work(flutter):
    m, a, e, _ = flutter
    with pytest.raises(InputError, match=r"parameter = 'wing\.EI' is invalid: not a parameter "
                       r"with derivatives of this model \(did you mean .*'wing\.EI\*'.*--list"):
        S.critical_sensitivities(m, a, e, params=["wing.EI"])


def test_the_cli_computes_only_the_params_asked_for(flutter, monkeypatch, capsys):
    from propwhirl.analysis import stability
    from propwhirl.app.cli import main

    m, a, _, _ = flutter
    calls = []
    monkeypatch.setattr(stability, "analyse", lambda model, **kw: calls.append(1) or a)
    assert main(["sensitivity", "wingtip", "--param", "wing.EI"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--param 'wing.EI' is invalid" in err and "propwhirl sensitivity wingtip --list" in err
    assert len(err.splitlines()) == 1 and not calls               # refused before analysing
    assert main(["sensitivity", "wingtip", "--param", "wing.GJ*", "--plot", "s.png"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--plot draws the per-element" in err and len(err.splitlines()) == 1 and not calls
    assert main(["sensitivity", "wingtip", "--kind", "flutter", "--param", "wing.GJ*",
                 "--param", "flight.density"]) == 0
    out = capsys.readouterr().out
    rows = [line.split()[0] for line in out.splitlines()[3:] if line.strip()]
    assert sorted(rows) == ["flight.density", "wing.GJ*"] and calls == [1]
    assert main(["sensitivity", "wingtip", "--list"]) == 0
    listed = capsys.readouterr().out
    assert all(p in listed for p in NEW) and calls == [1]


def test_a_version_1_entry_has_no_scale():
    d = {"path": "propellers[0].propeller.pivot_pitch", "value": 0.1, "unit": "m", "doc": "",
         "dlam_dp": {"re": 1.0, "im": 0.0}, "dV_dp": 2.0, "df_dp": 0.0, "normalised": 0.001}
    s = S.Sensitivity.from_dict(d)
    assert s.scale is None and s.per == "value"
    with pytest.raises(InputError, match=r"sensitivity\.scale = -1\.0 is invalid"):
        S.Sensitivity.from_dict({**d, "scale": -1.0, "scale_of": "R"})
