"""Which instability of a study's analysis is critical: the one definition
(:func:`propwhirl.analysis.critical`) with the thesis's exclusions as options (see
:mod:`propwhirl.studies.parametric`, "Definition of critical")."""
from __future__ import annotations

from typing import Callable

import numpy as np

from propwhirl.analysis.naming import kinetic_energy_shares
from propwhirl.analysis.stability import Instability, ModelAnalysis, critical

_WHIRL_PREFIXES = ("backward", "forward")


def _label_is_wing(e: Instability) -> bool:
    return not e.label.startswith(_WHIRL_PREFIXES)


def critical_instability(a: ModelAnalysis, *, static_divergence: bool = True, low_speed: bool = True,
                         is_wing_divergence: Callable[[Instability], bool] | None = None) -> Instability | None:
    """The critical instability of an analysis (:func:`propwhirl.analysis.stability.critical`,
    the one definition) with the thesis's exclusions of the module docstring as options.

    static_divergence: count the wing's static divergence (default: yes; the thesis: no).
    low_speed: count instabilities present at the first speed even when they recover later
        (default: yes; the thesis: no).
    is_wing_divergence: says whether a divergence event is the wing's; build it with
        :func:`wing_divergence_predicate` (mode shapes).  Without it the mode's name decides
        (not "backward…"/"forward…" → wing), a fallback for analyses re-read from a file.
    With both options True (the default) this is exactly ``a.critical``.
    """
    is_wing = _label_is_wing if is_wing_divergence is None else is_wing_divergence
    recovered = {e.mode for e in a.events if e.event == "recovery"}

    def leave_out(e: Instability) -> bool:
        if e.event == "unstable-at-start" and not low_speed and e.mode in recovered:
            return True
        return e.kind == "divergence" and not static_divergence and is_wing(e)

    return critical(a.events, exclude=leave_out)


def static_divergence_speed(a: ModelAnalysis,
                            is_wing_divergence: Callable[[Instability], bool] | None = None) -> float:
    """Lowest divergence onset [m/s] of the wing (see :func:`critical_instability`; NaN if none)."""
    is_wing = _label_is_wing if is_wing_divergence is None else is_wing_divergence
    hits = [e.V for e in a.events if e.kind == "divergence" and e.event == "onset" and is_wing(e)]
    return min(hits) if hits else float("nan")


def mount_strain_share(model, V: float, q: np.ndarray) -> float:
    """Share of the strain energy qᵀKq of displacement vector `q` in the propeller mount springs
    (the θ, ψ degrees of freedom of the model's DOF map), K the structural stiffness of `model`
    at V [m/s] without aerodynamics.  1 for a model without wing degrees of freedom (the
    isolated propeller); a modal structure's coordinates are the wing's (its "on-grid"
    mounts' springs are in the modes: their strain counts as the wing's)."""
    dm = model.dof_map()
    if not (dm.has_wing or "modal" in dm.groups()):
        return 1.0
    s = model.without_aerodynamics().second_order(np.array([float(V)]))
    x = np.asarray(q)[: s.n_dof, None]
    frac = kinetic_energy_shares(x, s.S3[0], {"mount": dm.dofs("theta", "psi")})
    return float(frac["mount"][0])


def wing_divergence_predicate(model, a: ModelAnalysis) -> Callable[[Instability], bool]:
    """Predicate "is this divergence event the wing's?" for `a` = analyse(model): less than half
    of the strain energy of the diverging shape in the propeller mounts (:func:`mount_strain_share`),
    shape taken at the event (onsets) or at the first speed (unstable-at-start); other events
    (frequency-zero: no shape stored) fall back on the mode's name."""
    shares: dict[tuple[int, float], float] = {}
    for p in (a.criticals.points if a.criticals is not None else ()):
        if p.kind == "divergence":
            shares[(p.mode, float(p.V))] = mount_strain_share(model, p.V, p.eigenvector)
    sw = a.sweep
    for e in a.events:
        if e.kind == "divergence" and e.event == "unstable-at-start" and sw.eigenvectors is not None:
            shares[(e.mode, e.V)] = mount_strain_share(model, e.V, sw.eigenvectors[0, :, e.mode])

    def is_wing(e: Instability) -> bool:
        share = shares.get((e.mode, float(e.V)))
        return _label_is_wing(e) if share is None else share < 0.5

    return is_wing


def convention(static_divergence: bool, low_speed: bool) -> str:
    """In words, which events a study's critical instability counts (module docstring)."""
    if static_divergence and low_speed:
        return "every instability counts (propwhirl.analysis.critical)"
    left = [what for flag, what in ((static_divergence, "the wing's static divergence"),
                                    (low_speed, "low-speed instabilities that recover"))
            if not flag]
    thesis = " (the thesis convention)" if len(left) == 2 else ""
    return "left out: " + " and ".join(left) + thesis
