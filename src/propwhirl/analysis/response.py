"""Time response to initial conditions (§9.2, Figures 9.11–9.12).

Time response
-------------
:func:`simulate` integrates a model's linear aeroelastic system ẋ = A(V) x (eq. 5.3 for the
structure, 6.18 for the isolated propeller, D.27 for propellers on a wing) at one airspeed from
given initial conditions with the exact transition matrix e^{AΔt}
(:func:`propwhirl.engine.time_response`; the thesis used MATLAB's ode45, available here as
``method="ivp"``).  It returns a :class:`Response` whose histories are labelled like the
model's states, in SI: displacements ("propeller 1 theta" [rad], "node 3 h" [m, positive
down], "node 3 alpha" [rad, nose up] ...), their rates ("d/dt ..." [rad/s, m/s]) and the
aerodynamic lag states.  :func:`propwhirl.reproduce.ch09.baseline_propeller_responses` reproduces the setting of
Figures 9.11–9.12: the isolated baseline propeller (symmetric, or f_ψ = 4 Hz) released from an
initial pitch of 1° at 77, 222 and 250 m/s, 10 s.

The response is the superposition of the modes, x(t) = Σ c_k x̂_k e^{λ_k t} (eq. 5.8), so its
modal coordinates η_k(t) = (X⁻¹ x(t))_k grow exactly like e^{λ_k t} (:meth:`Response.modal`),
and after the well-damped forward whirl mode has died out the envelope of the propeller motion
grows at the rate Re λ of the backward whirl mode (:meth:`Response.growth_rate`).  The whirl
sense of the motion is the sense of the θ–ψ path (θ on X, ψ on Y, :meth:`Response.orbit_area`)
relative to the rotation of the propeller (:func:`rotation_sign`).

The Campbell diagram (frequencies against propeller speed) is
:func:`propwhirl.analysis.vibration.campbell`.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from propwhirl.analysis.whirl import rotation_sign_from_gyroscopic
from propwhirl.engine import eigen, time_response
from propwhirl import validate as v
from propwhirl.results import Result, SavedDict

__all__ = [
    "Response", "simulate", "rotation_sign",
]


# ----------------------------------------------------------------------------------------------
# Time response
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Response(Result):
    """Free response of a model at one airspeed.

    model_name; V [m/s]; t (T,) [s]; x (T, n) state histories (SI) with ``labels`` (n);
    n_dof: the first n_dof states are the displacements (degrees of freedom), the next n_dof
    their rates, the rest aerodynamic lag states; eigenvalues (n,) [1/s] and right
    eigenvectors (n, n) of A(V), used by :meth:`modal`.

    A :class:`~propwhirl.results.Result` of kind "free-response" (format
    ``propwhirl.free-response/1``): :meth:`save` / :meth:`load`, every field checked when
    read (complex numbers saved as ``{"re": ..., "im": ...}``).
    """

    model_name: str
    V: float
    t: np.ndarray
    x: np.ndarray
    labels: tuple[str, ...]
    n_dof: int
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray

    KIND: ClassVar[str] = "free-response"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "free-response file"

    def encode(self) -> dict[str, Any]:
        lam, X = np.asarray(self.eigenvalues), np.asarray(self.eigenvectors)
        return {"model_name": self.model_name, "V_m_per_s": float(self.V),
                "t_s": self.t.tolist(), "x": self.x.tolist(), "labels": list(self.labels),
                "n_dof": int(self.n_dof),
                "eigenvalues_per_s": {"re": lam.real.tolist(), "im": lam.imag.tolist()},
                "eigenvectors": {"re": X.real.tolist(), "im": X.imag.tolist()}}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "Response":
        """V > 0; t finite and increasing; x (T, n) finite with n labels; n_dof in
        [0, n/2]; eigenvalues (n,) and eigenvectors (n, n), finite (InputError naming the
        key)."""
        r = SavedDict(d, where, ("model_name", "V_m_per_s", "t_s", "x", "labels", "n_dof",
                                 "eigenvalues_per_s", "eigenvectors"))
        V = r.number("V_m_per_s")
        if V <= 0:
            raise v.InputError(f"{r.name('V_m_per_s')} = {V!r} is invalid: must be > 0 m/s")
        t = r.array("t_s")
        if t.size == 0 or not (np.diff(t) > 0).all():
            raise v.InputError(f"{r.name('t_s')}: must be at least one time, increasing")
        labels = r.strings("labels")
        n = len(labels)
        return cls(r.string("model_name"), V, t, r.array("x", ndim=2, shape=(t.size, n)),
                   labels, r.integer("n_dof", 0, n // 2),
                   r.complex_array("eigenvalues_per_s", 1, (n,)),
                   r.complex_array("eigenvectors", 2, (n, n)))

    def __getitem__(self, label: str) -> np.ndarray:
        """History of the state called ``label`` (SI)."""
        try:
            return self.x[:, self.labels.index(label)]
        except ValueError:
            raise v.InputError(f"no state labelled {label!r}; states are {self.labels}") from None

    @property
    def dof_labels(self) -> tuple[str, ...]:
        return self.labels[: self.n_dof]

    @property
    def dofs(self) -> dict[str, np.ndarray]:
        """Displacement histories by degree of freedom [m or rad]."""
        return {lab: self.x[:, i] for i, lab in enumerate(self.dof_labels)}

    @property
    def rates(self) -> dict[str, np.ndarray]:
        """Velocity histories [m/s or rad/s], keyed by the degree of freedom's label."""
        return {lab: self.x[:, self.n_dof + i] for i, lab in enumerate(self.dof_labels)}

    def table(self) -> dict[str, np.ndarray]:
        """Tidy long-format columns of the displacements: t [s], dof, value [SI]."""
        T, n = self.t.size, self.n_dof
        return {"t": np.repeat(self.t, n), "dof": np.tile(np.asarray(self.dof_labels, dtype=object), T),
                "value": self.x[:, :n].reshape(-1)}

    def amplitude(self, labels: Sequence[str]) -> np.ndarray:
        """√(Σ x_i²) over the given states (e.g. θ and ψ: radius of the whirl path) [SI]."""
        return np.sqrt(sum(self[lab] ** 2 for lab in labels))

    def _window(self, t_from: float, t_to: float | None) -> np.ndarray:
        hi = self.t[-1] if t_to is None else t_to
        sel = (self.t >= t_from) & (self.t <= hi)
        if sel.sum() < 3:
            raise v.InputError(f"time window [{t_from}, {hi}] s holds fewer than 3 samples of "
                               f"the response (t = {self.t[0]}..{self.t[-1]} s)")
        return sel

    def orbit_area(self, theta: str = "propeller 1 theta", psi: str = "propeller 1 psi",
                   t_from: float = 0.0, t_to: float | None = None) -> float:
        """Signed area swept by the (θ on X, ψ on Y) path, ½∫(θ dψ − ψ dθ) [rad²].

        Positive for a counter-clockwise path.  Trapezoidal rule on the samples in
        [t_from, t_to] [s].
        """
        sel = self._window(t_from, t_to)
        th, ps = self[theta][sel], self[psi][sel]
        return float(0.5 * np.sum(th[:-1] * ps[1:] - ps[:-1] * th[1:]))

    def growth_rate(self, label: str = "propeller 1 theta", t_from: float = 0.0,
                    t_to: float | None = None) -> float:
        """Exponential rate σ [1/s] of the envelope of one history: least-squares line through
        log|x| at its local extrema (one per half cycle) in [t_from, t_to] [s].

        For a response dominated by one mode λ this is Re λ (eq. 5.8).
        """
        sel = self._window(t_from, t_to)
        y, tt = self[label][sel], self.t[sel]
        a = np.abs(y)
        i = np.nonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:]))[0] + 1
        if i.size < 3:
            raise v.InputError(f"{label}: fewer than 3 extrema in [{tt[0]}, {tt[-1]}] s; "
                               "lengthen the window or refine the time step")
        # parabolic refinement of each extremum of |y| (sampling error of the peak height)
        y0, y1, y2 = a[i - 1], a[i], a[i + 1]
        den = y0 - 2 * y1 + y2
        d = np.divide(0.5 * (y0 - y2), den, out=np.zeros_like(den), where=den != 0)
        peak = y1 - 0.25 * (y0 - y2) * d
        tp = tt[i] + d * (tt[1] - tt[0])
        return float(np.polyfit(tp, np.log(peak), 1)[0])

    def modal(self) -> np.ndarray:
        """Modal coordinates η(t) = X⁻¹ x(t), shape (T, n): η_k(t) = η_k(0) e^{λ_k t} (eq. 5.8)."""
        return np.linalg.solve(self.eigenvectors, self.x.T.astype(complex)).T


def _model_labels(model) -> tuple[tuple[str, ...], int]:
    s = model.second_order(np.array([1.0]))
    return tuple(s.labels), int(s.n_dof)


def simulate(model, V: float, initial: Mapping[str, float], *, duration: float = 10.0,
             dt: float = 0.002, method: str = "expm") -> Response:
    """Linear free response of ``model`` at airspeed ``V`` [m/s] (§9.2, Figures 9.11–9.12).

    ``initial``: initial values of states by label, SI — e.g. ``{"propeller 1 theta":
    np.radians(1.0)}`` (rad), ``{"node 25 h": 0.01}`` (m, down), ``{"d/dt node 25 alpha": 0.1}``
    (rad/s); every other state starts at zero (aerodynamic lag states included).  Sampled every
    ``dt`` [s] for ``duration`` [s]; ``method`` "expm" (exact transition matrix) or "ivp"
    (scipy's RK45, like the thesis's ode45).  Works for any model with ``state_matrix`` and
    ``second_order`` (PropellerWing, IsolatedPropeller, TypicalSection).
    """
    Vf = float(v.positive("V", V, "m/s"))
    T = float(v.positive("duration", duration, "s"))
    h = float(v.positive("dt", dt, "s"))
    if h >= T:
        raise v.InputError(f"dt = {dt!r} s is invalid: must be smaller than duration = {duration!r} s")
    labels, n_dof = _model_labels(model)
    if not initial:
        raise v.InputError("initial must give at least one nonzero initial state "
                           f"(by label, e.g. {labels[0]!r})")
    x0 = np.zeros(len(labels))
    for lab, val in initial.items():
        if lab not in labels:
            raise v.InputError(f"initial: no state labelled {lab!r}; states are {labels}")
        x0[labels.index(lab)] = float(v.finite(f"initial[{lab!r}]", val))
    n_steps = int(round(T / h))
    t = np.arange(n_steps + 1) * h
    A = np.asarray(model.state_matrix(np.array([Vf])))[0]
    r = time_response(A, x0, t, labels, method=method)
    lam, X = eigen(A)
    return Response(model.name, Vf, r.t, r.x, labels, n_dof,
                    lam, X)


def rotation_sign(model, propeller: int = 0) -> int:
    """Sense of the spin of a flexible propeller in the (θ on X, ψ on Y) plane: +1 counter-
    clockwise (the thesis's rotor, Figure 6.1), from the gyroscopic coupling of the model
    (:func:`~propwhirl.analysis.whirl.rotation_sign_from_gyroscopic`; aerodynamics off, at 100 m/s for
    a fixed-pitch rotor).  An independent check of the DOF map's ``rotation``."""
    p = model.dof_map().propeller(propeller)
    s = model.without_aerodynamics().second_order(np.array([100.0]))
    C = s.S2[0]
    return rotation_sign_from_gyroscopic(0.5 * (C[p.theta, p.psi] - C[p.psi, p.theta]))
