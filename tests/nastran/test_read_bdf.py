"""NASTRAN bulk data in (issue 36, item 3): what maps to what, on hand-written decks
(tests/helpers/bdf_decks.py) whose every number is known — the stick's rigidities, masses
and inertias, the propeller's masses, pivots, springs and damping — in each unit system."""
from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import bdf_decks as d
from propwhirl.cases import registry
from propwhirl.io.nastran_read import read_bdf


@pytest.fixture(scope="module")
def base():
    return registry.case_model("wingtip")        # one flexibly mounted propeller


def read(tmp_path, cards, base, units="si", name="wing.bdf", notes=None, **kw):
    path = tmp_path / name
    path.write_text(d.text(cards, units, **kw))
    return read_bdf(path, units=units, base=base, hubs=(101,), notes=notes)


def aft(model, x_basic: float, node: int = 4) -> float:
    """A basic x [m] as a position aft of the mid-chord at the propeller's node."""
    p = model.wing.node_properties()
    return x_basic - d.STICK_X + float(p["a"][node] * p["b"][node])


def test_the_stick_becomes_the_beam_wing(tmp_path, base):
    notes: list[str] = []
    m = read(tmp_path, d.standard(), base, notes=notes)
    w = m.wing
    assert w.semi_span == 2.0 and w.element_count == 4
    assert w.stations is None and w.n_elements == 4       # equal elements: n_elements
    assert w.EI == pytest.approx(d.E * d.I1, rel=1e-15)              # plane 1 vertical
    assert w.EI_chordwise == pytest.approx(d.E * d.I2, rel=1e-15)    # T_x, R_z free
    assert w.GJ == pytest.approx(d.G * d.J, rel=1e-15)
    assert w.mass_per_length == pytest.approx(d.RHO * d.A + d.NSM, rel=1e-15)
    assert w.polar_inertia == pytest.approx(d.RHO * (d.I1 + d.I2), rel=1e-15)
    p = w.element_properties()
    np.testing.assert_allclose(p["x_alpha_b"], 0.0, atol=1e-15)      # c.g. on the axis
    assert w.root_chord == base.wing.root_chord            # the base's aerodynamics kept
    assert w.elastic_axis == base.wing.elastic_axis and w.lift_slope == base.wing.lift_slope
    assert m.flight == base.flight
    assert notes == []             # PS 2 holds T_y; a PBAR's blank K1, K2: shear-rigid


def test_a_rigid_nacelle_becomes_a_rigid_mount_with_its_masses(tmp_path, base):
    m = read(tmp_path, d.standard("rigid"), base)
    inst = m.propellers[0]
    p = inst.propeller
    assert inst.mount == "rigid" and inst.y == 2.0
    assert p.rotor.mass == d.ROTOR and p.rotor.x == pytest.approx(aft(m, d.HUB_X), abs=1e-14)
    assert [q.mass for q in p.masses] == [d.NACELLE]
    assert p.masses[0].x == pytest.approx(aft(m, d.NACELLE_X), abs=1e-14)
    assert p.spin_inertia == d.SPIN                        # the rotor's I11
    lt, lp = base.propellers[0].propeller.pivot_pitch, base.propellers[0].propeller.pivot_yaw
    assert (p.pivot_pitch, p.pivot_yaw) == (lt, lp)         # a rigid mount's: the base's
    xs = np.array([p.rotor.x, p.masses[0].x])
    ms = np.array([d.ROTOR, d.NACELLE])
    assert p.inertia["I_theta_P"] == pytest.approx(np.sum(ms * (xs - lt) ** 2) + d.I22)
    assert p.inertia["I_psi_P"] == pytest.approx(np.sum(ms * (xs - lp) ** 2) + d.I33)
    # the base's propeller aerodynamics kept
    b = base.propellers[0].propeller
    assert (p.radius, p.n_blades, p.beta_075_deg, p.rotation) == (
        b.radius, b.n_blades, b.beta_075_deg, b.rotation)


def test_two_hinges_with_springs_become_a_flexible_mount(tmp_path, base):
    m = read(tmp_path, d.standard("flexible"), base)
    inst = m.propellers[0]
    p = inst.propeller
    assert inst.mount == "flexible"
    assert p.pivot_pitch == pytest.approx(aft(m, d.PITCH_X), abs=1e-14)
    assert p.pivot_yaw == pytest.approx(aft(m, d.YAW_X), abs=1e-14)
    assert (p.K_theta, p.K_psi, p.f_theta, p.f_psi) == (d.K_THETA, d.K_PSI, None, None)
    assert base.propellers[0].propeller.damping == "g"
    assert (p.damping, p.damping_theta, p.damping_psi) == ("g", d.GE_THETA, d.GE_PSI)


def test_a_base_with_zeta_damping_gets_ge_over_two(tmp_path, base):
    import dataclasses
    inst = base.propellers[0]
    zeta = dataclasses.replace(inst.propeller, damping="zeta")
    base_z = base.with_(propellers=(dataclasses.replace(inst, propeller=zeta),))
    p = read(tmp_path, d.standard("flexible"), base_z).propellers[0].propeller
    assert (p.damping, p.damping_theta, p.damping_psi) == ("zeta", d.GE_THETA / 2, d.GE_PSI / 2)


@pytest.mark.parametrize("units", ["mm-t-s", "in-lbf-s"])
def test_every_unit_system_gives_the_si_model(tmp_path, base, units):
    si = read(tmp_path, d.standard("flexible"), base, name="si.bdf")
    other = read(tmp_path, d.standard("flexible"), base, units=units, name=f"{units}.bdf")
    assert other.wing.semi_span == pytest.approx(2.0, rel=1e-14)
    for k in ("EI", "EI_chordwise", "GJ", "mass_per_length", "polar_inertia"):
        assert getattr(other.wing, k) == pytest.approx(getattr(si.wing, k), rel=1e-13), k
    a, b = si.propellers[0].propeller, other.propellers[0].propeller
    for k in ("K_theta", "K_psi", "pivot_pitch", "pivot_yaw", "spin_inertia"):
        assert getattr(b, k) == pytest.approx(getattr(a, k), rel=1e-13, abs=1e-14), k
    assert b.rotor.mass == pytest.approx(a.rotor.mass, rel=1e-13)
    assert b.inertia["I_theta_P"] == pytest.approx(a.inertia["I_theta_P"], rel=1e-13)


def test_wtmass_multiplies_every_mass(tmp_path, base):
    si = read(tmp_path, d.standard(), base, name="si.bdf")
    w = read(tmp_path, d.standard(), base, name="w.bdf", wtmass=0.00259)
    assert w.wing.mass_per_length == pytest.approx(si.wing.mass_per_length, rel=1e-13)
    assert w.wing.polar_inertia == pytest.approx(si.wing.polar_inertia, rel=1e-13)
    assert w.propellers[0].propeller.rotor.mass == pytest.approx(d.ROTOR, rel=1e-13)
    assert w.wing.EI == si.wing.EI                          # stiffness untouched


def test_uneven_grids_become_stations(tmp_path, base):
    cards = d.standard()
    cards = d.replace_card(cards, "GRID", 2, d.grid(2, d.STICK_X, 0.3, d.STICK_Z, "2"))
    m = read(tmp_path, cards, base)
    assert m.wing.stations == (0.3, 1.0, 1.5)
    assert m.wing.max_element_length == pytest.approx(0.7)
    np.testing.assert_allclose(m.wing.node_y, [0.0, 0.3, 1.0, 1.5, 2.0], atol=1e-15)


def test_in_plane_held_makes_a_wing_rigid_in_its_plane(tmp_path, base):
    cards = d.standard()
    for k in range(2, 6):
        cards = d.replace_card(cards, "GRID", k, d.grid(k, d.STICK_X, d.Y[k - 1], d.STICK_Z,
                                                        "126"))
    m = read(tmp_path, cards, base)
    assert m.wing.EI_chordwise is None


def test_pbeam_nsm_offset_and_nsi_give_the_centre_of_gravity_and_polar_inertia(tmp_path, base):
    """PBEAM with NSM at M2 (chordwise, aft) and NSI: m = rho A + NSM, x_cg = NSM M2 / m,
    polar = rho (I1 + I2) + NSI + NSM M2^2; the c.g. as a chord fraction of the base's chord."""
    m2, nsi = 0.12, 0.7
    cards = d.beams(d.replace_card(d.standard(), "PBAR", 10, d.pbeam(nsi=nsi, m2=m2)))
    notes: list[str] = []
    m = read(tmp_path, cards, base, units="mm-t-s", notes=notes)
    mass = d.RHO * d.A + d.NSM
    assert m.wing.mass_per_length == pytest.approx(mass, rel=1e-13)
    assert m.wing.polar_inertia == pytest.approx(d.RHO * (d.I1 + d.I2) + nsi + d.NSM * m2 ** 2,
                                                 rel=1e-13)
    np.testing.assert_allclose(m.wing.element_properties()["x_alpha_b"], d.NSM * m2 / mass,
                               rtol=1e-12)
    assert not any("shear" in n for n in notes)             # K1 = K2 = 0: shear-rigid


def test_pbarl_rod_and_pbeaml_tube_by_their_closed_forms(tmp_path, base):
    r, ro, ri = 0.05, 0.06, 0.04
    cards = d.replace_card(d.standard(), "PBAR", 10, ["PBARL", 10, 20, "MSCBML0", "ROD",
                                                      None, None, None, None, d.L(r),
                                                      d.Q(d.NSM, "mass_per_length")])
    notes: list[str] = []
    m = read(tmp_path, cards, base, notes=notes)
    inertia = math.pi * r ** 4 / 4
    assert m.wing.EI == pytest.approx(d.E * inertia, rel=1e-14)
    assert m.wing.GJ == pytest.approx(d.G * 2 * inertia, rel=1e-14)
    assert m.wing.mass_per_length == pytest.approx(d.RHO * math.pi * r ** 2 + d.NSM, rel=1e-14)
    assert any("PBARL 10" in n and "shear" in n for n in notes)
    tube = ["PBEAML", 10, 20, "MSCBML0", "TUBE", None, None, None, None, d.L(ro), d.L(ri), d.Q(d.NSM, "mass_per_length"),
            "YES", 1.0, d.L(ro), d.L(ri), d.Q(d.NSM, "mass_per_length")]
    cards = d.beams(d.replace_card(d.standard(), "PBAR", 10, tube))
    m = read(tmp_path, cards, base)
    assert m.wing.EI == pytest.approx(d.E * math.pi * (ro ** 4 - ri ** 4) / 4, rel=1e-14)


def test_orientation_by_g0_and_plane_1_chordwise(tmp_path, base):
    """v = (1, 0, 0): plane 1 is the wing's plane, so I1 is the chordwise rigidity."""
    cards = [(["CBAR", c[1], c[2], c[3], c[4], 1.0, 0.0, 0.0] if c[0] == "CBAR" else c)
             for c in d.standard()]
    m = read(tmp_path, cards, base)
    assert m.wing.EI == pytest.approx(d.E * d.I2) and m.wing.EI_chordwise == pytest.approx(d.E * d.I1)
    cards = [(["CBAR", c[1], c[2], c[3], c[4], 900] if c[0] == "CBAR" else c)
             for c in d.standard()] + [d.grid(900, d.STICK_X, 0.0, 5.0)]
    assert read(tmp_path, cards, base, name="g0.bdf").wing.EI == pytest.approx(d.E * d.I1)


def test_grids_in_a_cord2r_frame(tmp_path, base):
    """Grids 2-5 given in a frame turned 90 degrees about z and moved: the same basic
    positions, the same model."""
    frame = ["CORD2R", 7, 0, d.L(1.0), d.L(0.0), d.L(d.STICK_Z), d.L(1.0), d.L(0.0),
             d.L(d.STICK_Z + 1.0), d.L(1.0), d.L(1.0), d.L(d.STICK_Z)]
    cards = d.standard()
    for k in range(2, 6):   # local x = basic y, local y = -(basic x - 1)
        cards = d.replace_card(cards, "GRID", k, d.grid(k, d.Y[k - 1], 1.0 - d.STICK_X, 0.0,
                                                        "2", cp=7))
    m = read(tmp_path, cards + [frame], base)
    np.testing.assert_allclose(m.wing.node_y, d.Y, atol=1e-14)
    assert m.wing.EI == pytest.approx(d.E * d.I1)


def test_spc_rbar_and_a_bulk_data_only_file(tmp_path, base):
    """SPC (not SPC1) for the root, an RBAR for the nacelle, no executive or case control."""
    cards = d.replace_card(d.standard(), "SPC1", 1, ["SPC", 1, 1, "123456", 0.0])
    cards = d.replace_card(cards, "RBE2", 201, ["RBAR", 201, 5, 101, "123456", None, None,
                                                "123456"])
    cards.append(["RBE2", 202, 101, "123456", 102])
    notes: list[str] = []
    m = read(tmp_path, cards, base, control=False, notes=notes)
    assert m.propellers[0].mount == "rigid" and len(m.propellers[0].propeller.masses) == 1
    assert any("SPC set 1 taken" in n for n in notes)
