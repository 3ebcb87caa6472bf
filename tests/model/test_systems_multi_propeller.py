"""The multi-propeller assembly equals appendix D's block equations (D.29–D.44), built here
independently and literally from the generated chapter-8 blocks, for two propellers with
aerodynamics (the configuration of Table 10.8 / Figure 10.14)."""
import numpy as np
import pytest

from propwhirl.model.structure.assembly import free_dofs, wing_aero, wing_structure
from propwhirl.cases.ch10_other_wings import two_propeller_wing
from propwhirl.generated import prop_flexwing as pf


def global_blocks(model, j, V):
    """One propeller's global matrices of D.29 (row/column placement as in C.5–C.37)."""
    inst, node = model.propellers[j], model.nodes[j]
    p = inst.propeller
    nq = 3 * model.wing.n_nodes
    h, a = 3 * node, 3 * node + 2
    I = p.pivot_inertia()
    ab = model.wing.node_properties()["a"][node] * model.wing.node_properties()["b"][node]
    Sa, Ia, Ita = pf.inertia(I["M_P"], I["S_theta_P"], I["I_theta_P"], p.pivot_pitch, ab)[:, 0]
    ea = pf.e_alpha_geometry(p.e_theta, p.pivot_pitch, ab)[0, 0]
    Om = p.spin_rate(np.array([V]))[0]
    Kt, Kp = p.stiffness()
    zt, zp = p.viscous_damping_ratios()
    d = {k: float(x[0]) for k, x in p.aerodynamic_derivatives(np.array([V]), model.flight.speed_of_sound).items()}
    aero = dict(rho=model.flight.density, V=V, R=p.radius, e_theta=p.e_theta, e_psi=p.e_psi, e_alpha=ea, **d)
    A = {n: getattr(pf, n)(**aero) for n in ("Aa", "Ba", "Ca", "Da", "Ea", "Fa", "P1", "P2", "P3", "P4", "P5", "P6")}

    def col(block2x2):  # (2 × 2 on [h_P, α_P]) → rows (3 × 2) at the node: C.19, C.26
        out = np.zeros((nq, 2))
        out[[h, a], :] = block2x2
        return out

    def row(block2x2):  # 2 × 2 on [h_P, α_P] → (2 × nq): C.5, C.10
        out = np.zeros((2, nq))
        out[:, [h, a]] = block2x2
        return out

    def sq(block2x2):  # → (nq × nq): C.21, C.28
        out = np.zeros((nq, nq))
        out[np.ix_([h, a], [h, a])] = block2x2
        return out

    return dict(
        F=col(pf.Fs(I["S_theta_P"], Ita)), G=sq(pf.Gs(I["M_P"], Sa, Ia)), H=col(pf.Hs(p.I_Omega, Om)),
        P1=col(A["P1"]), P2=sq(A["P2"]), P3=col(A["P3"]), P4=sq(A["P4"]), P5=col(A["P5"]), P6=sq(A["P6"]),
        B=row(pf.Bs(I["S_theta_P"], Ita) - A["Ba"]), D=row(pf.Ds(p.I_Omega, Om) - A["Da"]), Fa=row(A["Fa"]),
        AA=pf.As(I["I_theta_P"], I["I_psi_P"]) - A["Aa"],
        CC=pf.Cs_viscous(p.I_Omega, Om, I["I_theta_P"], I["I_psi_P"], Kt, Kp, zt, zp) - A["Ca"],
        EE=pf.Es(Kt, Kp) - A["Ea"],
    )


@pytest.mark.parametrize("V", [60.0, 200.0])
def test_two_propellers_equal_appendix_d(V):
    model = two_propeller_wing()
    Ms, Cs, Ks = wing_structure(model.wing)
    aw = wing_aero(model.wing, model.flight.density, np.array([V]))
    blocks = [global_blocks(model, j, V) for j in range(2)]
    star = lambda k: np.hstack([b[k] for b in blocks])  # noqa: E731  D.30, D.31, D.33–D.35
    total = lambda k: sum(b[k] for b in blocks)  # noqa: E731  D.32, D.36–D.38
    diag = lambda k: np.block([[blocks[0][k], np.zeros((2, 2))], [np.zeros((2, 2)), blocks[1][k]]])  # noqa: E731
    vert = lambda k: np.vstack([b[k] for b in blocks])  # noqa: E731  D.42–D.44
    S1 = np.block([[Ms + total("G") - aw["Ma"][0] - total("P2"), star("F") - star("P1")],
                   [vert("B"), diag("AA")]])
    S2 = np.block([[Cs - aw["Ca"][0] - total("P4"), star("H") - star("P3")],
                   [vert("D"), diag("CC")]])
    S3 = np.block([[Ks - aw["Ka"][0] - total("P6"), -star("P5")],
                   [-vert("Fa"), diag("EE")]])
    keep = np.concatenate([free_dofs(model.wing.n_nodes), 3 * model.wing.n_nodes + np.arange(4)])
    s = model.second_order(np.array([V]))
    for mine, theirs in ((s.S1[0], S1), (s.S2[0], S2), (s.S3[0], S3)):
        np.testing.assert_allclose(mine, theirs[np.ix_(keep, keep)], rtol=1e-12, atol=1e-9)
