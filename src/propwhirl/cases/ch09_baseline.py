"""Chapter 9: the baseline models (Tecnam P2006T / X-57 based), Table 9.1 onwards.

Baseline wing (Table 9.1): span 11.4 m (semi-span 5.7 m), root chord 1.25 m, tip chord 0.8 m,
m = 25 kg/m, radius of gyration about the centre of gravity 25 % chord, elastic axis and centre
of gravity at 50 % chord, EI = 7e5 N m², GJ = 2e5 N m², aerodynamic centre 25 % chord,
C_lα = 2π; flight condition 8000 ft, ρ = 0.962870 kg/m³.  20 beam elements alone, 25 with
propellers (§9.3).
"""
from __future__ import annotations

import numpy as np

from propwhirl.analysis.stability import analyse, first_of_kind, speed_and_frequency
from propwhirl.model.systems import (
    SPEED_OF_SOUND_8000FT,
    FlightCondition,
    Installation,
    IsolatedPropeller,
    PropellerWing,
)
from propwhirl.model.propeller import PointMass, Propeller
from propwhirl.reproduce.harness import register
from propwhirl.analysis.vibration import label_modes, wing_modes
from propwhirl.model.wing import Wing

#: Air density at 8000 ft used throughout chapters 9–11 (Table 9.1) [kg/m³]
BASELINE_DENSITY = 0.962870


def baseline_wing(n_elements: int = 20, aero_model: str = "leishman-nguyen") -> Wing:
    """The baseline wing of Table 9.1."""
    return Wing(
        name="baseline wing (Table 9.1)",
        semi_span=5.7,
        root_chord=1.25,
        tip_chord=0.8,
        mass_per_length=25.0,
        radius_of_gyration=0.25,
        elastic_axis=0.5,
        centre_of_gravity=0.5,
        EI=7.0e5,
        GJ=2.0e5,
        aerodynamic_centre=0.25,
        lift_slope=2 * np.pi,
        n_elements=n_elements,
        aero_model=aero_model,
    )


@register("t9.2")
def table_9_2() -> dict[str, float]:
    """Table 9.2: natural frequencies [Hz] and flutter/divergence of the baseline wing (20 elements).

    Flutter is the first torsion mode (the second wing mode); divergence a real root through 0.
    """
    f = wing_modes(baseline_wing()).frequency_hz
    out = {f"t9.2/freq{i + 1}": float(f[i]) for i in range(5)}
    a = analyse(baseline_wing_model())
    out["t9.2/flutter_speed"], out["t9.2/flutter_frequency"] = speed_and_frequency(a.first("wing 2", "flutter"))
    out["t9.2/divergence_speed"] = speed_and_frequency(first_of_kind(a, "divergence"))[0]
    return out


def baseline_wing_model(n_elements: int = 20) -> PropellerWing:
    """The baseline wing alone at 8000 ft (§9.1)."""
    return PropellerWing(baseline_wing(n_elements), baseline_flight(), name="baseline wing")


# ----------------------------------------------------------------------------- §9.2 propeller
def baseline_propeller(**changes) -> Propeller:
    """The baseline propeller of Tables 9.3–9.4 (X-57 cruise propeller, simplified).

    3 blades, R = 0.762 m, hub radius 0.125 m, constant chord 0.094 m, β_0.75 = 35°,
    fixed pitch windmilling with J = π tan(β − 3°) = 1.96 (eq. 9.1); rotor 8 kg at −1.16 m
    (the propeller plane), motor-nacelle 35 kg at −0.86 m, pitch and yaw pivots on the wing
    mid-chord axis (l = 0, e = −1.16 m), f_θ = f_ψ = 7 Hz, g_θ = g_ψ = 0.005; I_Ω = M_r R²/3.
    Keyword arguments replace any field (e.g. f_psi=4.0, operation="constant-speed", rpm=2250).
    """
    base = dict(
        name="baseline propeller (Tables 9.3-9.4)",
        radius=0.762,
        hub_radius=0.125,
        blade_chord=0.094,
        n_blades=3,
        rotor=PointMass(8.0, -1.16),
        masses=(PointMass(35.0, -0.86),),
        pivot_pitch=0.0,
        pivot_yaw=0.0,
        f_theta=7.0,
        f_psi=7.0,
        damping_theta=0.005,
        damping_psi=0.005,
        damping="g",
        beta_075_deg=35.0,
        zero_lift_angle_deg=-3.0,
    )
    base.update(changes)
    return Propeller(**base)


def baseline_flight() -> FlightCondition:
    """8000 ft: ρ = 0.962870 kg/m³ (Table 9.1), ISA speed of sound 330.8 m/s."""
    return FlightCondition(BASELINE_DENSITY, SPEED_OF_SOUND_8000FT)


def isolated_baseline_propeller(**changes) -> IsolatedPropeller:
    """The baseline propeller on a rigid wing (§9.2, chapter 6 model)."""
    return IsolatedPropeller(baseline_propeller(**changes), baseline_flight())


# ----------------------------------------------------------------------------- §9.3 prop-wing
N_ELEMENTS_WITH_PROPELLERS = 25
INBOARD_NODE = 7  # the thesis's node 8 counting the root as node 1: y = 7·5.7/25 = 1.596 m


def inboard_y(n_elements: int = N_ELEMENTS_WITH_PROPELLERS) -> float:
    """Spanwise position [m] of the inboard propeller node (≈ 1.6 m, node 8 of 25 in the thesis)."""
    return baseline_wing(n_elements).node_y[INBOARD_NODE * n_elements // N_ELEMENTS_WITH_PROPELLERS]


def propeller_wing(positions: tuple[float, ...], mount: str = "flexible",
                   propeller: Propeller | None = None, name: str = "propeller-wing",
                   **switches) -> PropellerWing:
    """Baseline wing (25 elements) with baseline propellers at the given node positions [m].

    `switches`: wing_aero, propeller_aero, rotating (all True by default).
    """
    prop = baseline_propeller() if propeller is None else propeller
    return PropellerWing(
        baseline_wing(N_ELEMENTS_WITH_PROPELLERS),
        baseline_flight(),
        tuple(Installation(prop, y, mount) for y in positions),
        name=name,
        **switches,
    )


def inboard_propeller_wing(mount: str = "flexible", **switches) -> PropellerWing:
    """§9.3: baseline wing with the baseline propeller at 1.6 m (node 8 of 25)."""
    switches.setdefault("name", f"inboard propeller wing ({mount} mount, §9.3)")
    return propeller_wing((inboard_y(),), mount, **switches)


def _by_label(model: PropellerWing) -> dict[str, float]:
    return dict(label_modes(model))


@register("t9.4")
def table_9_4() -> dict[str, float]:
    """Table 9.4: inertia parameters of the baseline propeller (eq. 8.5, 8.6, 9.2)."""
    p = baseline_propeller()
    inertia = p.pivot_inertia()
    return {
        "t9.4/I_theta_P": inertia["I_theta_P"],
        "t9.4/S_theta_P": inertia["S_theta_P"],
        "t9.4/I_Omega": p.I_Omega,
    }


@register("t9.6")
def table_9_6() -> dict[str, float]:
    """Table 9.6: wing with a rigidly mounted, non-rotating inboard propeller [Hz]."""
    modes = _by_label(inboard_propeller_wing("rigid", rotating=False))
    return {f"t9.6/freq{i}": modes[f"wing {i}"] for i in range(1, 6)}


@register("t9.8")
def table_9_8() -> dict[str, float]:
    """Table 9.8: flexibly mounted inboard propeller, Ω = 0 [Hz]."""
    modes = _by_label(inboard_propeller_wing())
    out = {f"t9.8/wing{i}": modes[f"wing {i}"] for i in range(1, 6)}
    out["t9.8/prop_pitch"] = modes["backward 1"]
    out["t9.8/prop_yaw"] = modes["forward 1"]
    return out


# ----------------------------------------------------------------------------- reproduction
@register("t9.5")
def table_9_5() -> dict[str, float]:
    """Table 9.5: the baseline propeller on a rigid wing: backward whirl flutter."""
    a = analyse(isolated_baseline_propeller())
    V, f = speed_and_frequency(a.first("backward", "flutter"))
    rpm = float(baseline_propeller().rotational_speed(np.array([V]))[0] * 60 / (2 * np.pi))
    return {"t9.5/whirl_flutter_speed": V, "t9.5/whirl_flutter_frequency": f, "t9.5/rpm_at_flutter": rpm}


@register("s9.2")
def section_9_2() -> dict[str, float]:
    """§9.2: unsymmetric stiffness (f_ψ = 4 Hz, Figure 9.10) and constant speed 2250 RPM (9.13).

    The constant-speed propeller is unstable at very low speeds (the advance ratio tends to 0,
    §9.2); as the thesis asks, that low-speed instability is ignored: the flutter speed is the
    backward-whirl onset after the mode first becomes stable.
    """
    a = analyse(isolated_baseline_propeller(f_psi=4.0))
    out = {"s9.2/unsymmetric_whirl_flutter_speed": speed_and_frequency(a.first("backward", "flutter"))[0]}
    cs = analyse(isolated_baseline_propeller(operation="constant-speed", rpm=2250.0),
                 np.arange(1.0, 601.0, 10.0))
    onsets = [e for e in cs.events if e.label == "backward" and e.kind == "flutter" and e.event == "onset"]
    out["s9.2/constant_speed_whirl_flutter_speed"] = onsets[0].V if onsets else float("nan")
    return out


@register("t9.7")
def table_9_7() -> dict[str, float]:
    """Table 9.7: rigidly mounted, non-rotating inboard propeller (an inert mass, §9.3.1)."""
    a = analyse(inboard_propeller_wing("rigid", rotating=False, propeller_aero=False))
    V, f = speed_and_frequency(a.first("wing 2", "flutter"))
    return {"t9.7/flutter_speed": V, "t9.7/flutter_frequency": f,
            "t9.7/divergence_speed": speed_and_frequency(first_of_kind(a, "divergence"))[0]}


def _table_9_9(prefix: str, **switches) -> dict[str, float]:
    a = analyse(inboard_propeller_wing(**switches))
    Vw, fw = speed_and_frequency(a.first("wing 2", "flutter"))
    Vf, ff = speed_and_frequency(a.first("forward 1", "flutter"))
    return {f"{prefix}/wing_flutter_speed": Vw, f"{prefix}/wing_flutter_frequency": fw,
            f"{prefix}/divergence_speed": speed_and_frequency(first_of_kind(a, "divergence"))[0],
            f"{prefix}/fw_whirl_flutter_speed": Vf, f"{prefix}/fw_whirl_flutter_frequency": ff}


@register("t9.9")
def table_9_9() -> dict[str, float]:
    """Table 9.9: flexibly mounted rotating inboard propeller, without and with propeller aero."""
    return {**_table_9_9("t9.9/no_prop_aero", propeller_aero=False), **_table_9_9("t9.9/full")}


@register("f9.19")
def figure_9_19() -> dict[str, float]:
    """Figure 9.19: inboard propeller wing without wing aerodynamics."""
    a = analyse(inboard_propeller_wing(wing_aero=False))
    V, f = speed_and_frequency(a.first("backward 1", "flutter"))
    return {"f9.19/no_wing_aero/bw_whirl_flutter_speed": V,
            "f9.19/no_wing_aero/bw_whirl_flutter_frequency": f,
            "f9.19/no_wing_aero/wing1_flutter_speed": speed_and_frequency(a.first("wing 1"))[0]}
