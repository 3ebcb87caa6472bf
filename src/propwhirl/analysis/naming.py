"""Names and descriptions of tracked modes: the thesis's mode names, whirl sense, content.

Everything here reads what a state is from the model's :class:`~propwhirl.model.protocol.DofMap`
(``model.dof_map()``), never from its class or its labels.  Modes are named once, at the first
speed of a sweep (a tracked mode keeps its name along the sweep):

* models with wing degrees of freedom (propeller–wing models, chapters 7–11): each oscillatory
  mode is matched, by an optimal one-to-one MAC assignment on the displacement part, to the
  in-vacuo modes named by :func:`propwhirl.analysis.modes.label_modes` ("wing n",
  "backward k", "forward k");
* models with a spinning propeller and no wing (chapter 6): "backward" and "forward" whirl from
  the sense of the θ–ψ orbit; not spinning: "pitch" and "yaw" by increasing frequency;
* any other model (the typical section): the dominant content group of each mode ("plunge",
  "pitch");
* real roots are "lag k" (by decreasing real part) — or "static k" where the root is already
  unstable at the first speed (a range starting beyond a divergence speed: a diverged
  structural mode, described by its content) — and the hidden
  conjugate partner of mode "x" is "x'".

Content is the share of a mode's kinetic energy x̂ᴴ M x̂ (M the structural mass, aerodynamics
off) in each group of :meth:`~propwhirl.model.protocol.DofMap.groups`: "bending" (h, φ),
"torsion" (wing α), "pitch" (propeller θ or the section's α), "yaw" (ψ), "plunge".
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.analysis.modes import label_modes, model_modes
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.engine import Sweep, mac
from propwhirl.model.protocol import DofMap, Model


def kinetic_energy_shares(X: np.ndarray, M: np.ndarray,
                          groups: Mapping[str, Sequence[int] | np.ndarray]) -> dict[str, np.ndarray]:
    """Share of each mode's (column of X) kinetic energy x̂ᴴMx̂ in each group of DOFs.

    Group g's share is Re Σ_{i∈g} conj(x_i) (M x)_i / x̂ᴴMx̂; over groups covering every DOF the
    shares sum to one.  ``groups`` maps names to indices into x (e.g. :meth:`DofMap.groups`).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.diag([1.0, 3.0])
    >>> shares = kinetic_energy_shares(np.array([[1.0], [1.0]]), M, {"a": [0], "b": [1]})
    >>> {g: float(s[0]) for g, s in shares.items()}
    {'a': 0.25, 'b': 0.75}
    """
    X = np.asarray(X)
    e = np.real(np.conj(X) * (M @ X))
    total = e.sum(axis=0)
    return {name: e[np.asarray(ix, dtype=int)].sum(axis=0) / total for name, ix in groups.items()}


def _oscillatory(sw: Sweep, t: int = 0) -> list[int]:
    lam = sw.eigenvalues[t]
    return [k for k in range(sw.n_modes)
            if sw.physical[t, k] and abs(lam[k].imag) > 1e-9 * max(1.0, abs(lam[k]))]


def mode_names(model: Model, sw: Sweep, basis: np.ndarray | None = None) -> list[str]:
    """Names of the tracked modes of ``sw`` = a sweep of ``model``, decided at its first speed
    (rules in the module docstring).  ``basis``: a reduced model's basis over the DOFs (the
    reference modes are then its Rayleigh–Ritz modes, :func:`~propwhirl.analysis.modes.model_modes`)."""
    dm = model.dof_map()
    n = sw.n_modes
    lam0 = sw.eigenvalues[0]
    X0 = sw.eigenvectors[0]
    names = [f"mode {k}" for k in range(n)]
    osc = _oscillatory(sw)
    real = [k for k in range(n) if sw.physical[0, k] and k not in osc]
    real = sorted(real, key=lambda k: -lam0[k].real)
    diverged = [k for k in real if lam0[k].real > 0]
    for i, k in enumerate(diverged):        # unstable real roots: not aerodynamic lags
        names[k] = f"static {i + 1}"
    for i, k in enumerate(k for k in real if k not in diverged):
        names[k] = f"lag {i + 1}"
    if dm.has_wing:
        modes, _ = model_modes(model, basis)
        ref = [lab for lab, _ in label_modes(model, basis, modes)]
        shapes = modes.shapes.astype(complex)
        M = mac(X0[sw.displacement][:, osc][:, :, None], shapes[:, None, :])
        rows, cols = linear_sum_assignment(-M)
        for r, c in zip(rows, cols):
            names[osc[r]] = ref[c]

    elif "eta" in dm.q_kinds:       # a modal structure: its largest coordinate ("mode 3", ...)
        for k in osc:
            names[k] = dm.q_labels[int(np.argmax(np.abs(X0[: dm.n_dof, k])))]
    elif dm.propellers:
        p = dm.propellers[0]
        order = sorted(osc, key=lambda k: abs(lam0[k].imag))
        if p.spinning and len(order) == 2:
            for k in order:
                names[k] = whirl_sense(X0[p.theta, k], X0[p.psi, k], p.rotation, lam0[k])
        else:
            for k, nm in zip(order, ("pitch", "yaw")):
                names[k] = nm
    else:
        groups = dm.groups()
        for k in osc:
            e = {g: float(np.sum(np.abs(X0[ix, k]) ** 2)) for g, ix in groups.items()}
            names[k] = max(e, key=lambda g: e[g])
    for k in range(n):  # hidden conjugate partners: "<name>'"
        if not sw.physical[0, k] and sw.partner[k] >= 0:
            names[k] = f"{names[sw.partner[k]]}'"
    return names


def whirl(dm: DofMap, x: np.ndarray, lam: complex) -> str | None:
    """Whirl sense ("forward"/"backward"/"planar") of the propeller with the largest θ–ψ
    motion in the full-state vector ``x`` at eigenvalue ``lam``, relative to that propeller's
    own sense of rotation; None without spinning flexibly mounted propellers or for a real root.
    """
    props = [p for p in dm.propellers if p.spinning]
    if not props or abs(lam.imag) == 0:
        return None
    p = max(props, key=lambda p: abs(x[p.theta]) ** 2 + abs(x[p.psi]) ** 2)
    return whirl_sense(x[p.theta], x[p.psi], p.rotation, lam)


def mode_content(model: Model, sw: Sweep, names: Sequence[str]) -> dict[str, dict[str, float]]:
    """Kinetic-energy shares of each physical oscillatory mode (and of each real root already
    unstable) at the first speed of ``sw``, by content group, rounded to 4 digits (shares
    ≤ 1e-3 left out): {name: {group: share}}."""
    quiet = model.without_aerodynamics()
    s = quiet.second_order(np.array([float(sw.V[0])]))
    groups = quiet.dof_map().groups()
    X = sw.eigenvectors[0][sw.displacement]
    out = {}
    for k in range(sw.n_modes):
        lam = sw.eigenvalues[0, k]
        if not sw.physical[0, k] or (lam.imag == 0 and lam.real <= 0):   # not the lag roots
            continue
        frac = kinetic_energy_shares(X[:, [k]], s.S1[0], groups)
        out[names[k]] = {g: round(float(f[0]), 4) for g, f in frac.items() if abs(f[0]) > 1e-3}
    return out
