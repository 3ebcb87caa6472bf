"""Chapter 9: the baseline wing, the baseline propeller on a rigid wing and the inboard
propeller-wing (Tables 9.2–9.9, §9.2, Figure 9.19; the cases are :mod:`propwhirl.cases.ch09_baseline`)."""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.response import Response, simulate
from propwhirl.analysis.stability import first_of_kind, speed_and_frequency
from propwhirl.analysis.vibration import label_modes, wing_modes
from propwhirl.cases.ch09_baseline import (
    baseline_propeller,
    baseline_wing,
    baseline_wing_model,
    inboard_propeller_wing,
    isolated_baseline_propeller,
)
from propwhirl.model.systems import PropellerWing
from propwhirl.reproduce.harness import analyse, register


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


# ----------------------------------------------------------------------------- aeroelastic results
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


# ----------------------------------------------------------------------------- Figures 9.11–9.12
#: Airspeeds of Figures 9.11–9.12 [m/s]: below (cruise), near and above the whirl flutter speed
THESIS_RESPONSE_SPEEDS = (77.0, 222.0, 250.0)


def baseline_propeller_responses(speeds: Sequence[float] = THESIS_RESPONSE_SPEEDS, *,
                                 f_psi: float = 7.0, theta0_deg: float = 1.0,
                                 duration: float = 10.0, dt: float = 0.002,
                                 method: str = "expm") -> dict[float, Response]:
    """Figures 9.11 (f_ψ = 7 Hz, symmetric) and 9.12 (f_ψ = 4 Hz): the isolated baseline
    propeller (§9.2, fixed-pitch windmilling) released from θ = ``theta0_deg`` [deg] at rest,
    at each airspeed [m/s], for ``duration`` [s].  Returns {V: Response}."""
    model = isolated_baseline_propeller(f_psi=f_psi)
    th0 = float(np.radians(v.finite("theta0_deg", theta0_deg, "deg")))
    return {float(V): simulate(model, V, {"propeller 1 theta": th0}, duration=duration, dt=dt,
                               method=method)
            for V in speeds}
