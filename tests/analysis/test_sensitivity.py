"""analysis.sensitivity: dV_crit/dp from the eigenvectors against finite differences of the
engine's own critical speed (issue 13.3: within 1 %, or 1e-4 m/s per unit where ≈ 0)."""
import json

import numpy as np
import pytest

from helpers.derivative_checks import fd_critical_speed
from helpers.work import count_calls, named
from propwhirl.analysis import analyse
from propwhirl.analysis.sensitivity import critical_sensitivities, sensitivity_parameters
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model import derivatives as D
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.validate import InputError


def check(model, event, sens, top=4):
    for s in sens.ranked(top):
        fd = fd_critical_speed(model, s.path, s.value, event)
        assert abs(s.dV_dp - fd) <= 0.01 * abs(fd) + 1e-4, (s.path, s.dV_dp, fd)


@pytest.fixture(scope="module")
def wingtip():
    m = wingtip_propeller_wing()
    return m, analyse(m)


@pytest.mark.long
@pytest.mark.parametrize("kind", ["flutter", "divergence"])
def test_wingtip_top_sensitivities_match_finite_differences(wingtip, kind):
    m, a = wingtip
    event = min((e for e in a.events if e.kind == kind and e.event == "onset"), key=lambda e: e.V)
    cs = critical_sensitivities(m, a, event)
    assert cs.V == pytest.approx(event.V, abs=0.01)
    check(m, event, cs)


@pytest.mark.long
def test_a_random_distributed_wing_matches_finite_differences():
    rng = np.random.default_rng(7)
    wing = baseline_wing(12)
    ys = wing.node_y
    props = tuple(Installation(baseline_propeller(f_theta=f, f_psi=0.9 * f), float(ys[i]),
                               "flexible")
                  for i, f in zip((5, 12), rng.uniform(5.5, 8.5, 2)))
    m = PropellerWing(wing, baseline_flight(), props)
    a = analyse(m)
    event = min((e for e in a.events if e.kind == "flutter" and e.event == "onset"),
                key=lambda e: e.V)
    check(m, event, critical_sensitivities(m, a, event), top=3)


def test_all_sensitivities_cost_less_than_one_analysis(wingtip):
    """The work of every sensitivity of the critical point, counted (not timed: the seconds
    depend on the machine's load): two sparse LU factorisations (the right and the left
    eigenvector) and no dense eigen-decomposition, where one analysis of a fresh model makes
    a dense eigen-decomposition at each of its ≥ 10 tracker nodes."""
    m = wingtip_propeller_wing()
    a, analysis_calls = count_calls(analyse, m)
    cs, sens_calls = count_calls(critical_sensitivities, m, a)
    assert len(cs.sensitivities) == len(sensitivity_parameters(m)) == len(D.parameters(m)) + 4 > 100
    assert named(sens_calls, "splu") <= 2
    assert named(sens_calls, "eig", "eigvals", "eigh") == 0
    assert named(analysis_calls, "eig", "eigvals") >= 10


def test_frequency_from_the_eigenvalue_and_ranking(wingtip):
    m, a = wingtip
    event = next(e for e in a.events if e.kind == "flutter")
    cs = critical_sensitivities(m, a, event, params=["propellers[0].propeller.f_theta",
                                                     "wing.GJ[0]"])
    assert cs.frequency_hz == pytest.approx(event.frequency_hz, rel=1e-4)
    assert abs(cs.eigenvalue.real) < 1e-3
    r = cs.ranked()
    assert abs(r[0].normalised) >= abs(r[1].normalised)
    d = cs.to_dict(1)
    assert set(d["critical"]) >= {"V", "frequency_hz", "kind", "mode"} and len(d["sensitivities"]) == 1
    assert set(d["sensitivities"][0]) >= {"path", "value", "unit", "dV_dp", "normalised"}


def test_events_without_a_derivative_are_refused(wingtip):
    m, a = wingtip
    fz = next(e for e in a.events if e.event == "frequency-zero")
    with pytest.raises(InputError, match="not a crossing"):
        critical_sensitivities(m, a, fz)


def test_cli_json_and_plot(tmp_path, capsys):
    from propwhirl.app.cli import main

    out, png = tmp_path / "s.json", tmp_path / "s.png"
    assert main(["sensitivity", "wingtip", "--kind", "flutter", "--top", "7", "--json",
                 str(out), "--plot", str(png)]) == 0
    text = capsys.readouterr().out
    assert "flutter onset of forward 1" in text and "propellers[0].propeller.f_theta" in text
    d = json.loads(out.read_text())
    assert d["critical"]["kind"] == "flutter" and len(d["sensitivities"]) == 7
    assert png.stat().st_size > 10_000
    assert main(["sensitivity", "isolated-propeller"]) == 2
    assert "wing models" in capsys.readouterr().err


def test_spanwise_plot_content(wingtip):
    from propwhirl.app import plots

    m, a = wingtip
    cs = critical_sensitivities(m, a)
    fig = plots.spanwise_sensitivity(cs, m)
    axes = [ax for ax in fig.axes if ax.get_title(loc="left")]
    titles = [ax.get_title(loc="left") for ax in axes]
    assert [t.split(":")[0] for t in titles] == ["bending rigidity EI", "torsional rigidity GJ",
                                                 "mass per length m"]
    n_el = m.wing.element_count
    assert all(len(ax.patches) == n_el for ax in axes)
    total = sum(s.normalised for s in cs.sensitivities if s.path.startswith("wing.GJ["))
    assert f"{total:+.4f}" in titles[1]
