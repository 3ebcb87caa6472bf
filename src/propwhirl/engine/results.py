"""Result types of the engine: :class:`Sweep`, :class:`CriticalPoint`, :class:`Hump`,
:class:`Criticals`, :class:`FrequencyZero`, :class:`Analysis` (JSON-able, complex arrays as
``{"re", "im"}``).

*Frequency and damping* (eq. 5.5): f = |Im λ|/2π [Hz], ζ = −Re λ/|λ| (ζ = 0 where λ = 0).
Mode ids and which branch is physical: see :mod:`propwhirl.engine.ordering`.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from typing import Any

import numpy as np

from propwhirl.validate import InputError


def _c2d(z: np.ndarray) -> dict[str, Any]:
    z = np.asarray(z)
    return {"re": z.real.tolist(), "im": z.imag.tolist()}


def _d2c(d: Mapping[str, Any]) -> np.ndarray:
    return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)


@dataclass(frozen=True)
class Sweep:
    """Tracked eigen-solutions along the airspeed.

    Column ``k`` of every ``(T, n)`` array is mode (branch) ``k``; ``physical[t, k]`` says whether
    it is reported at speed ``V[t]`` (Im λ ≥ 0; see the module docstring).

    V:            (T,) speeds [m/s], increasing: the grid plus refinement points (from
                  :func:`analyse`: a subset of the grid plus refinement points).
    eigenvalues:  (T, n) complex λ [1/s].
    eigenvectors: (T, n, n) complex, ``[t, :, k]`` the unit right eigenvector of mode k, phase
                  aligned along V (first speed: largest displacement entry real positive);
                  None when re-read from a dict saved without them.  Memory: T·n²·16 bytes
                  (100 speeds × 300 states ≈ 144 MB).
    dlam_dV:      (T, n) complex dλ/dV [1/m].
    physical:     (T, n) bool.
    state_labels: n state labels; displacement: (n,) bool mask of displacement states.
    mode_labels:  n mode labels; partner: (n,) id of the conjugate partner branch (−1 if none).
    grid:         the speeds asked for [m/s].
    floor:        (T,) scale floor of |λ| used for relative tolerances [1/s].
    unresolved:   speed intervals [m/s] left ambiguous at ``min_step`` or the node budget.
    stats:        counters (eig, state_matrix_calls, nodes, refined).
    """

    V: np.ndarray
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray | None
    dlam_dV: np.ndarray
    physical: np.ndarray
    state_labels: tuple[str, ...]
    displacement: np.ndarray
    mode_labels: tuple[str, ...]
    partner: np.ndarray
    grid: np.ndarray
    floor: np.ndarray
    unresolved: tuple[tuple[float, float], ...] = ()
    stats: Mapping[str, int] = field(default_factory=dict)

    @property
    def n_modes(self) -> int:
        return self.eigenvalues.shape[1]

    @property
    def frequency_hz(self) -> np.ndarray:
        """f = |Im λ| / 2π [Hz]."""
        return np.abs(self.eigenvalues.imag) / (2 * np.pi)

    @property
    def damping_ratio(self) -> np.ndarray:
        """ζ = −Re λ / |λ| (eq. 5.5); 0 where λ = 0."""
        mag = np.abs(self.eigenvalues)
        return np.divide(-self.eigenvalues.real, mag, out=np.zeros_like(mag), where=mag > 0)

    def mode_shape(self, mode: int, t: int) -> np.ndarray:
        """Displacement part x̂ of mode ``mode`` at speed index ``t`` (eq. 5.7)."""
        if self.eigenvectors is None:
            raise InputError("this Sweep was saved without eigenvectors")
        return self.eigenvectors[t, self.displacement, mode]

    def relabel(self, labels: Sequence[str] | Callable[[complex, np.ndarray], str]) -> "Sweep":
        """New Sweep with mode labels: a sequence of n strings or f(λ, eigenvector) at V[0]."""
        if callable(labels):
            if self.eigenvectors is None:
                raise InputError("labelling by shape needs the eigenvectors")
            labels = [labels(self.eigenvalues[0, k], self.eigenvectors[0, :, k])
                      for k in range(self.n_modes)]
        labels = tuple(str(s) for s in labels)
        if len(labels) != self.n_modes:
            raise InputError(f"mode labels: got {len(labels)}, need {self.n_modes}")
        return replace(self, mode_labels=labels)

    def table(self) -> dict[str, np.ndarray]:
        """Tidy columns of the physical modes, sorted by V then mode id.

        V [m/s], mode, label, frequency_hz [Hz], damping_ratio (5.5), real, imag [1/s].
        """
        t, k = np.nonzero(self.physical)
        lam = self.eigenvalues[t, k]
        return {
            "V": self.V[t], "mode": k, "label": np.asarray(self.mode_labels, dtype=object)[k],
            "frequency_hz": self.frequency_hz[t, k], "damping_ratio": self.damping_ratio[t, k],
            "real": lam.real, "imag": lam.imag,
        }

    def to_dict(self, include_eigenvectors: bool = True) -> dict[str, Any]:
        """JSON-able dict (complex arrays as {"re", "im"})."""
        d: dict[str, Any] = {
            "V": self.V.tolist(), "eigenvalues": _c2d(self.eigenvalues),
            "dlam_dV": _c2d(self.dlam_dV), "physical": self.physical.tolist(),
            "state_labels": list(self.state_labels), "displacement": self.displacement.tolist(),
            "mode_labels": list(self.mode_labels), "partner": self.partner.tolist(),
            "grid": self.grid.tolist(), "floor": self.floor.tolist(),
            "unresolved": [list(u) for u in self.unresolved], "stats": dict(self.stats),
        }
        if include_eigenvectors and self.eigenvectors is not None:
            d["eigenvectors"] = _c2d(self.eigenvectors)
        return d

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Sweep":
        lam = _d2c(d["eigenvalues"])
        X = _d2c(d["eigenvectors"]) if "eigenvectors" in d else None
        return cls(
            V=np.asarray(d["V"], dtype=float), eigenvalues=lam, eigenvectors=X,
            dlam_dV=_d2c(d["dlam_dV"]), physical=np.asarray(d["physical"], dtype=bool),
            state_labels=tuple(d["state_labels"]),
            displacement=np.asarray(d["displacement"], dtype=bool),
            mode_labels=tuple(d["mode_labels"]), partner=np.asarray(d["partner"], dtype=int),
            grid=np.asarray(d["grid"], dtype=float), floor=np.asarray(d["floor"], dtype=float),
            unresolved=tuple(tuple(u) for u in d["unresolved"]), stats=dict(d["stats"]),
        )


@dataclass(frozen=True)
class CriticalPoint:
    """A sign change of a tracked mode's real part.

    mode, label:   tracked mode id and label.
    kind:          "flutter" (complex pair, Im λ ≠ 0) or "divergence" (real root through 0).
    direction:     "onset" (Re λ − → +) or "recovery" (+ → −).
    V:             crossing speed [m/s] (bracket width ≤ xtol); bracket: (lo, hi) [m/s].
    frequency_hz:  |Im λ|/2π at V [Hz]; eigenvalue: λ at V [1/s].
    dzeta_dV:      dζ/dV at V [s/m] (from dλ/dV, or a central difference), None for divergence.
    benignity:     (dζ/dV)⁻¹ [m/s] (eq. 5.13), signed (negative at an onset); None for divergence.
    eigenvector:   full-state eigenvector at V (mode shape for plotting).
    """

    mode: int
    label: str
    kind: str
    direction: str
    V: float
    bracket: tuple[float, float]
    frequency_hz: float
    eigenvalue: complex
    dzeta_dV: float | None
    benignity: float | None
    eigenvector: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        d["eigenvalue"] = {"re": self.eigenvalue.real, "im": self.eigenvalue.imag}
        d["eigenvector"] = _c2d(self.eigenvector)
        d["bracket"] = list(self.bracket)
        return d

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "CriticalPoint":
        kw = dict(d)
        kw["eigenvalue"] = complex(d["eigenvalue"]["re"], d["eigenvalue"]["im"])
        kw["eigenvector"] = _d2c(d["eigenvector"])
        kw["bracket"] = tuple(d["bracket"])
        return cls(**kw)


@dataclass(frozen=True)
class Hump:
    """A mode that goes unstable at ``V_onset`` and recovers at ``V_recovery`` [m/s]."""

    mode: int
    label: str
    kind: str
    V_onset: float
    V_recovery: float


@dataclass(frozen=True)
class Criticals:
    """All crossings of a sweep (sorted by V), hump modes, modes unstable at the first speed."""

    points: tuple[CriticalPoint, ...]
    humps: tuple[Hump, ...]
    unstable_at_start: tuple[int, ...]
    stats: Mapping[str, int] = field(default_factory=dict)

    @property
    def first_onset(self) -> CriticalPoint | None:
        """The lowest-speed onset crossing, or None.

        A fact of the sweep, not the decision "critical": that is
        :func:`propwhirl.analysis.critical`, which also counts the modes unstable at the first
        speed (:attr:`unstable_at_start`) and frequency-zero events."""
        on = [p for p in self.points if p.direction == "onset"]
        return min(on, key=lambda p: p.V) if on else None

    def to_dict(self) -> dict[str, Any]:
        return {"points": [p.to_dict() for p in self.points],
                "humps": [vars(h).copy() for h in self.humps],
                "unstable_at_start": list(self.unstable_at_start), "stats": dict(self.stats)}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Criticals":
        return cls(points=tuple(CriticalPoint.from_dict(p) for p in d["points"]),
                   humps=tuple(Hump(**h) for h in d["humps"]),
                   unstable_at_start=tuple(d["unstable_at_start"]), stats=dict(d["stats"]))


@dataclass(frozen=True)
class FrequencyZero:
    """An unstable oscillatory mode whose pair turns into real roots (its frequency falls to 0).

    The thesis's "whirl divergence" of an already unstable whirl mode (Table 10.4); see
    :func:`propwhirl.engine.crossings.frequency_zero_points`.

    mode, label:   tracked mode id and label.
    V:             speed of the branch point [m/s] (middle of ``bracket``).
    bracket:       (lo, hi) [m/s], width ≤ xtol: at lo the number of unstable complex pairs is
                   the one at the step's start, at hi it is smaller.
    """

    mode: int
    label: str
    V: float
    bracket: tuple[float, float]

    def to_dict(self) -> dict[str, Any]:
        return {"mode": self.mode, "label": self.label, "V": self.V,
                "bracket": list(self.bracket)}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "FrequencyZero":
        return cls(int(d["mode"]), str(d["label"]), float(d["V"]), tuple(d["bracket"]))


@dataclass(frozen=True)
class Analysis:
    """A sweep and its critical points."""

    sweep: Sweep
    criticals: Criticals

    def to_dict(self, include_eigenvectors: bool = True) -> dict[str, Any]:
        return {"sweep": self.sweep.to_dict(include_eigenvectors),
                "criticals": self.criticals.to_dict()}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Analysis":
        return cls(Sweep.from_dict(d["sweep"]), Criticals.from_dict(d["criticals"]))
