"""studies.gradients: V_crit(x) with exact gradients, the clearance optimisation, OpenMDAO."""
import numpy as np
import pytest

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.studies.gradients import CriticalSpeed, minimum_mount_stiffness, openmdao_component
from propwhirl.validate import InputError

PATHS = ("propellers[0].propeller.K_theta", "propellers[0].propeller.K_psi")


@pytest.fixture(scope="module")
def model():
    return wingtip_propeller_wing()


def test_gradient_against_finite_differences(model):
    f = CriticalSpeed(model, PATHS, static_divergence=False, low_speed=False)
    x = f.x0 * np.array([0.6, 0.8])
    g = f.gradient(x)
    for i in range(2):
        h = 1e-3 * x[i]
        e = np.eye(2)[i] * h
        fd = (f.value(x + e) - f.value(x - e)) / (2 * h)
        assert abs(g[i] - fd) <= 0.01 * abs(fd) + 1e-6, (i, g[i], fd)
    assert f.analyses == 5                       # one per point: the gradient costs none


def test_unknown_paths_are_refused(model):
    with pytest.raises(InputError, match="no exact derivatives"):
        CriticalSpeed(model, ("wing.semi_span",))


@pytest.mark.long
def test_minimum_stiffness_clears_in_few_analyses(model):
    """Exact gradients only (the comparison is an option: 18 analyses with finite differences,
    docs/gradients.md); cleared without tolerance."""
    r = minimum_mount_stiffness(model, 130.0, 1.15)
    assert r.cleared and r.V >= 149.5 and r.V == pytest.approx(149.5, abs=0.01)
    assert r.x_fd is None and r.analyses <= 6
    assert r.message.startswith("cleared: ")
    # the optimum really clears: an independent analysis at it
    from propwhirl.studies.gradients import CriticalSpeed as C
    check = C(model, r.paths, static_divergence=False, low_speed=False)
    assert check.value(r.x) >= 1.15 * 130.0


def test_openmdao_component_partials(model):
    om = pytest.importorskip("openmdao.api")
    prob = om.Problem(reports=False)      # no n2/report files written
    comp = openmdao_component(model, PATHS, vd=130.0, static_divergence=False, low_speed=False)
    prob.model.add_subsystem("whirl", comp, promotes=["*"])
    prob.setup(force_alloc_complex=False)
    prob.set_val("propellers_0_propeller_K_theta", 0.6 * comp.propwhirl.x0[0])
    prob.run_model()
    V = float(prob.get_val("V_crit")[0])
    assert float(prob.get_val("margin")[0]) == pytest.approx(V / 149.5 - 1)
    data = prob.check_partials(method="fd", step=1e-3, step_calc="rel", out_stream=None)
    for (of, wrt), d in data["whirl"].items():
        J, Jfd = d["J_fwd"], d["J_fd"]
        assert np.allclose(J, Jfd, rtol=0.01, atol=1e-9), (of, wrt, J, Jfd)
