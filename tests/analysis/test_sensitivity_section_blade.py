"""analysis.sensitivity for the section fields (taper, chords, elastic axis, aerodynamic
centre, centre of gravity, radius of gyration) and the blade angle: dV_crit/dp from the
eigenvectors against central differences of the engine's own critical speed on the wingtip
model (issue 13.3: within 1 %)."""
import pytest

from helpers.derivative_checks import fd_critical_speed
from propwhirl.analysis import analyse
from propwhirl.analysis.sensitivity import critical_sensitivities
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

PRE = "propellers[0].propeller."


@pytest.fixture(scope="module")
def wingtip():
    m = wingtip_propeller_wing()
    return m, analyse(m)


#: per kind, the parameters checked: those that move that critical speed (the wing's static
#: divergence does not depend on the wing's mass distribution: cg and r_g are ≈ 0 there,
#: below the engine's resolution of a difference quotient)
CASES = {
    "flutter": ["wing.root_chord", "wing.tip_chord", "wing.chord[12]", "wing.elastic_axis[24]",
                "wing.centre_of_gravity[24]", "wing.radius_of_gyration[24]",
                "wing.aerodynamic_centre[24]", PRE + "beta_075_deg"],
    "divergence": ["wing.root_chord", "wing.tip_chord", "wing.chord[25]",
                   "wing.elastic_axis[24]", "wing.aerodynamic_centre[24]", PRE + "beta_075_deg"],
}


@pytest.mark.long
@pytest.mark.parametrize("kind", ["flutter", "divergence"])
def test_wingtip_section_and_blade_angle_match_finite_differences(wingtip, kind):
    m, a = wingtip
    event = min((e for e in a.events if e.kind == kind and e.event == "onset"), key=lambda e: e.V)
    cs = critical_sensitivities(m, a, event, params=CASES[kind])
    assert [s.path for s in cs.sensitivities] == CASES[kind]
    for s in cs.sensitivities:
        fd = fd_critical_speed(m, s.path, s.value, event)
        assert abs(s.dV_dp - fd) <= 0.01 * abs(fd), (s.path, s.dV_dp, fd)


def test_taper_ranks_first_for_the_wingtip_divergence(wingtip):
    """The critical point of the wingtip model is the wing's divergence (143.15 m/s); a
    narrower chord raises it, the tip chord most: first of all parameters (the air density,
    the stiffness factor wing.GJ* and the root chord follow), the chords first of the
    planform's."""
    m, a = wingtip
    cs = critical_sensitivities(m, a)
    assert cs.ranked(1)[0].path == "wing.tip_chord"
    chords = [s for s in cs.ranked(len(cs.sensitivities)) if s.path.endswith("_chord")]
    assert [s.path for s in chords[:2]] == ["wing.tip_chord", "wing.root_chord"]
    assert all(s.dV_dp < 0 for s in chords[:2])
