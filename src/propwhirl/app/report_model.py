"""What the certification report (:mod:`propwhirl.app.report`) shows of the analysed model
(issue 35, item 4): what a reviewer needs to check it without opening the model file.

* :func:`model_summary` — name, semi-span, mesh, total masses, the wing's aerodynamics and the
  propellers' derivatives, the structural damping of the wing, the analysis method and the
  speed grid;
* :func:`propeller_table` — per propeller: station, masses and inertias about the pivots, the
  mount's stiffness and uncoupled frequencies, its structural damping, operation and rotation;
* :func:`wing_properties` — m, EI and GJ along the span (the report draws them:
  :func:`propwhirl.app.plots.campaign_plot.wing_properties_plot`);
* :func:`in_vacuo_modes` — the first in-vacuo modes (V = 0, not rotating): name, frequency
  and the kinetic-energy shares of bending, torsion, pitch and yaw.

Every value is plain text or a number with its unit in its heading; the report escapes them.
A model that is not a beam wing (a modal model) gives what it has: its tables say so.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.naming import kinetic_energy_shares
from propwhirl.analysis.reduced import choose_method
from propwhirl.analysis.vibration import label_modes, model_modes

#: In-vacuo modes listed in the report.
IN_VACUO_COUNT = 12


def _propellers(model: Any) -> tuple[Any, ...]:
    props = getattr(model, "propellers", ()) or ()
    return tuple(props) if isinstance(props, tuple) else ()


def model_summary(model: Any) -> list[tuple[str, str]]:
    """(quantity with unit, value) pairs describing a propeller-wing model."""
    out = [("name", str(getattr(model, "name", "")))]
    wing = getattr(model, "wing", None)
    if wing is not None:
        for label, attr, fmt in (("semi-span [m]", "semi_span", ".4g"),
                                 ("elements", "element_count", "d"), ("nodes", "n_nodes", "d")):
            x = getattr(wing, attr, None)
            if x is not None:
                out.append((label, format(x, fmt)))
        props = wing_properties(model)
        if props is not None:
            L = np.diff(np.asarray(wing.node_y, dtype=float))
            out.append(("wing mass (semi-span) [kg]", f"{float(np.sum(props['m'] * L)):.4g}"))
        mu, lam = (tuple(getattr(wing, "rayleigh", (0.0, 0.0))) + (0.0, 0.0))[:2]
        out.append(("wing structural damping", "none (Rayleigh μ = λ = 0: conservative)"
                    if mu == 0 and lam == 0 else
                    f"Rayleigh C = μ M + λ K, μ = {mu:g} 1/s, λ = {lam:g} s"))
        out.append(("wing aerodynamics", _wing_aero(model, wing)))
    elif getattr(model, "aero", None) == "dlm" and getattr(model, "wing_aero", False):
        nc, ns = model.dlm_planform.counts()          # a modal model's doublet lattice
        out.append(("wing aerodynamics", f"doublet lattice on the modes, {nc} chordwise × "
                    f"{ns} spanwise panels, Mach {model.dlm_mach}, its Roger "
                    "rational-function fit"))
    props = _propellers(model)
    if props:
        total = sum(i.propeller.pivot_inertia()["M_P"] for i in props
                    if hasattr(i, "propeller"))
        out.append(("propellers", f"{len(props)} (table below), {total:.4g} kg in all"))
        out.append(("propeller aerodynamics", _propeller_aero(model, props)))
    try:
        method = choose_method(model, "auto")
    except v.InputError as exc:       # a method the model refuses: said, not raised
        method = f"not chosen ({exc})"
    out.append(("analysis method", f"analyse(method='auto') → {method}: eigenvalues of the "
                "aeroelastic state space along the speed grid, modes tracked, every crossing "
                "refined"))
    flight = getattr(model, "flight", None)
    rng = getattr(flight, "speed_range", None)
    if rng is not None:
        lo, hi, step = (float(x) for x in rng)
        out.append(("speed grid [m/s]", f"{lo:g} to {hi:g} in steps of {step:g} (refined "
                    "near every event; the campaign extends it beyond each required speed)"))
    return out


def _wing_aero(model: Any, wing: Any) -> str:
    if not getattr(model, "wing_aero", True):
        return "off (switches.wing_aero = false)"
    if getattr(wing, "aero", "strip") == "dlm":
        span = getattr(wing, "dlm_spanwise_panels", None)
        return (f"doublet lattice, {wing.dlm_chordwise_panels} chordwise × "
                f"{'one per element' if span is None else span} spanwise panels, Mach "
                f"{wing.dlm_mach}, its Roger rational-function fit")
    return (f"strip theory, {getattr(wing, 'aero_model', '')} unsteady lift (Theodorsen's "
            "function approximated by lag states), lift slope and aerodynamic centre of the "
            "model file")


def _propeller_aero(model: Any, props: tuple[Any, ...]) -> str:
    if not getattr(model, "propeller_aero", True):
        return "off (switches.propeller_aero = false)"
    kinds = set()
    for inst in props:
        p = getattr(inst, "propeller", None)
        if p is None:
            continue
        if getattr(p, "derivatives", None) is not None:
            kinds.add("measured derivatives")
        else:
            s = p.aero_settings
            kinds.add(f"{s.method.replace('_', '-')} quasi-steady derivatives (wake "
                      f"{'on' if s.wake else 'off'}, compressibility "
                      f"{'on' if s.compressibility else 'off'})")
    return "; ".join(sorted(kinds)) or "none"


#: The propeller table's headings (units in them).
PROPELLER_HEAD = ("propeller", "y [m]", "mount", "state", "masses [kg]", "I_θ, I_ψ [kg m²]",
                  "K_θ, K_ψ [N m/rad]", "f_θ, f_ψ [Hz]", "mount damping", "R [m]",
                  "operation", "rotation")


def propeller_table(model: Any) -> list[tuple[str, ...]]:
    """One row per propeller (:data:`PROPELLER_HEAD`): its station, mount, state, masses,
    inertias about the pivots, mount stiffness and uncoupled frequencies f = √(K/I)/2π, the
    mount's structural damping (as given, g or ζ) and operation."""
    rows = []
    for i, inst in enumerate(_propellers(model), start=1):
        p = getattr(inst, "propeller", None)
        if p is None:
            continue
        inertia = p.pivot_inertia()
        Kt, Kp = p.stiffness()
        It, Ip = inertia["I_theta_P"], inertia["I_psi_P"]
        ft = np.sqrt(Kt / It) / (2 * np.pi) if It > 0 else float("nan")
        fp = np.sqrt(Kp / Ip) / (2 * np.pi) if Ip > 0 else float("nan")
        masses = " + ".join(f"{m.mass:g}" for m in p.all_masses)
        damping = (f"g = {p.damping_theta:g}, {p.damping_psi:g}" if p.damping == "g" else
                   f"ζ = {p.damping_theta:g}, {p.damping_psi:g}")
        rot = getattr(inst, "rotation", None) or getattr(p, "rotation", None)
        op = p.operation + (f", {p.rpm:g} rpm" if p.rpm is not None else "")
        y = getattr(inst, "y", None)
        grid = getattr(inst, "grid", None)       # a modal model's hub grid
        rows.append((str(i), f"{float(y):.4g}" if y is not None else
                     "–" if grid is None else f"grid {grid}",
                     str(getattr(inst, "mount", "")), str(getattr(inst, "state", "operating")),
                     f"{masses} = {inertia['M_P']:g}", f"{It:.4g}, {Ip:.4g}",
                     f"{Kt:.4g}, {Kp:.4g}", f"{ft:.3f}, {fp:.3f}", damping,
                     f"{p.radius:g}", op,
                     "–" if rot is None else ("counter-clockwise" if int(rot) > 0 else
                                              "clockwise") + " from the front"))
    return rows


def wing_properties(model: Any) -> dict[str, np.ndarray] | None:
    """The wing's m [kg/m], EI and GJ [N m²] per element at its mid-span y [m] (None: no beam
    wing)."""
    wing = getattr(model, "wing", None)
    if wing is None or not hasattr(wing, "element_properties"):
        return None
    p = wing.element_properties()
    return {"y": np.asarray(wing.element_y, dtype=float), "m": np.asarray(p["m"], dtype=float),
            "EI": np.asarray(p["EI"], dtype=float), "GJ": np.asarray(p["GJ"], dtype=float)}


def in_vacuo_modes(model: Any, count: int = IN_VACUO_COUNT
                   ) -> tuple[tuple[str, ...], list[tuple[str, ...]]]:
    """The first `count` in-vacuo modes (V = 0, not rotating; as ``propwhirl modes``):
    headings and rows (mode, f [Hz], each group's share of the kinetic energy)."""
    try:
        modes, M = model_modes(model)
    except v.InputError as exc:          # said in the table's place, not raised
        return ("in-vacuo modes",), [(f"not computed: {exc}",)]
    dm = model.dof_map()
    found = dm.groups()
    modal = "modal" in found
    names = label_modes(model) if dm.has_wing or modal else None
    groups = (("modal",) if modal else ("bending", "torsion")) + (
        ("chordwise",) if "chordwise" in found else ()) + ("pitch", "yaw")
    share = kinetic_energy_shares(modes.shapes, M, {g: found.get(g, []) for g in groups})
    order = np.argsort(modes.omega, kind="stable")[:count]
    rows = []
    for r, i in enumerate(order):
        label, f = (names[r] if names is not None else
                    (max(groups, key=lambda g: share[g][i]), float(modes.frequency_hz[i])))
        rows.append((label, f"{f:.3f}", *(f"{abs(x) if round(x) == 0 else x:.0f}"
                                          for x in (100 * share[g][i] for g in groups))))
    return ("mode", "f [Hz]", *(f"{g} [% of kinetic energy]" for g in groups)), rows
