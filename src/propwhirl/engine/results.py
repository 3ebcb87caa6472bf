"""Result types of the engine: :class:`Sweep`, :class:`CriticalPoint`, :class:`Hump`,
:class:`Criticals`, :class:`FrequencyZero`, :class:`Analysis` (JSON-able, complex arrays as
``{"re", "im"}``).

*Frequency and damping* (eq. 5.5): f = |Im λ|/2π [Hz], ζ = −Re λ/|λ| (ζ = 0 where λ = 0).
Mode ids and which branch is physical: see :mod:`propwhirl.engine.ordering`.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from propwhirl import fileio
from propwhirl.limits import check_read, format_bytes
from propwhirl.results import Result, SavedDict, json_type, shape_text
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
    it is reported at speed ``V[t]`` (Im λ ≥ 0; see the module docstring).  Frequencies and
    damping ratios (eq. 5.5): :attr:`frequency_hz`, :attr:`damping_ratio`; tables:
    :meth:`table`, :meth:`to_dataframe`, :meth:`to_xarray`.

    Attributes
    ----------
    V : ndarray
        (T,) speeds [m/s], increasing: the grid plus refinement points (from :func:`analyse`:
        a subset of the grid plus refinement points).
    eigenvalues : ndarray
        (T, n) complex λ [1/s].
    eigenvectors : ndarray or None
        (T, n_states, n) complex (n_states = n for a dense analysis; a reduced one,
        :mod:`propwhirl.analysis.reduced`, has fewer modes than states and lifts its vectors
        to the full state where read), ``[t, :, k]`` the right eigenvector of mode k, phase
        aligned along V (first speed: largest displacement entry real positive); None when
        re-read from a dict saved without them.  Memory: T·n²·16 bytes (100 speeds × 300
        states ≈ 144 MB).
    dlam_dV : ndarray
        (T, n) complex dλ/dV [1/m].
    physical : ndarray
        (T, n) bool: mode k reported at V[t].
    state_labels : tuple of str
        The n_states state labels.
    displacement : ndarray
        (n_states,) bool mask of the displacement states.
    mode_labels : tuple of str
        n mode labels.
    partner : ndarray
        (n,) id of the conjugate partner branch (−1 if none).
    grid : ndarray
        The speeds asked for [m/s].
    floor : ndarray
        (T,) scale floor of |λ| used for relative tolerances [1/s].
    unresolved : tuple of (float, float)
        Speed intervals [m/s] left ambiguous at ``min_step`` or the node budget.
    stats : mapping of str to int
        Counters (eig, state_matrix_calls, nodes, refined, ...).

    Examples
    --------
    The oscillator ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0 on 10 speeds: two branches, the conjugate
    pair, of which mode 0 (Im λ > 0) is the physical one.

    >>> import numpy as np
    >>> from propwhirl.engine import sweep
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1], A[:, 1, 0], A[:, 1, 1] = 1.0, -100.0, -(0.5 - 0.01 * V)
    ...     return A
    >>> sw = sweep(state_matrix, np.arange(10.0, 101.0, 10.0), n_dof=1)
    >>> sw.V.shape, sw.eigenvalues.shape, sw.eigenvectors.shape
    ((10,), (10, 2), (10, 2, 2))
    >>> sw.mode_labels, sw.physical[0].tolist(), sw.partner.tolist()
    (('mode 0', "mode 0'"), [True, False], [1, 0])
    >>> round(float(sw.frequency_hz[0, 0]), 3), round(float(sw.damping_ratio[-1, 0]), 3)
    (1.591, -0.025)
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

    #: Units of the :meth:`table` columns (and of :meth:`to_dataframe`, :meth:`to_xarray`).
    UNITS = {"V": "m/s", "frequency_hz": "Hz", "damping_ratio": "1", "real": "1/s",
             "imag": "1/s"}

    def to_dataframe(self):
        """:meth:`table` as a pandas DataFrame, one row per speed and physical mode; units in
        ``df.attrs["units"]`` (needs pandas: the ``data`` extra)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("DataFrames need pandas: pip install propwhirl[data]") from None
        df = pd.DataFrame(self.table())
        df.attrs["units"] = dict(self.UNITS)
        df.attrs["damping_convention"] = "damping_ratio = -Re(lambda)/|lambda| (eq. 5.5): < 0 unstable"
        return df

    def to_xarray(self):
        """The sweep as an xarray Dataset with dims ``V`` (speed) × ``mode``: eigenvalue
        (complex), real, imag [1/s], frequency_hz [Hz], damping_ratio, physical; coordinates
        V [m/s], mode (id) and label (per mode).  Non-physical entries (the hidden conjugate
        partners) are NaN in real, imag, frequency_hz, damping_ratio.  Units in each
        variable's ``attrs["units"]`` (needs xarray: the ``data`` extra)."""
        try:
            import xarray as xr
        except ImportError:
            raise ImportError("xarray Datasets need xarray: pip install propwhirl[data]") from None
        dims = ("V", "mode")
        keep = self.physical

        def masked(x):
            return np.where(keep, x, np.nan)

        lam = self.eigenvalues
        data = {
            "eigenvalue": (dims, np.where(keep, lam, np.nan + 0j), {"units": "1/s"}),
            "real": (dims, masked(lam.real), {"units": "1/s"}),
            "imag": (dims, masked(lam.imag), {"units": "1/s"}),
            "frequency_hz": (dims, masked(self.frequency_hz), {"units": "Hz"}),
            "damping_ratio": (dims, masked(self.damping_ratio),
                              {"units": "1", "convention": "-Re(lambda)/|lambda| (eq. 5.5): "
                               "< 0 unstable"}),
            "physical": (dims, self.physical),
        }
        coords = {"V": ("V", self.V, {"units": "m/s", "long_name": "airspeed"}),
                  "mode": ("mode", np.arange(self.n_modes)),
                  "label": ("mode", np.asarray(self.mode_labels, dtype=object))}
        return xr.Dataset(data, coords=coords)

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

    #: keys of :meth:`to_dict` ("eigenvectors" only when saved with them)
    KEYS = ("V", "eigenvalues", "dlam_dV", "physical", "state_labels", "displacement",
            "mode_labels", "partner", "grid", "floor", "unresolved", "stats")

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], where: str = "sweep") -> "Sweep":
        """The sweep written by :meth:`to_dict`, checked: every key present, shapes consistent
        (T speeds, n modes), numbers finite, speeds increasing; else an :class:`InputError`
        naming the key (`where` is its path in the file)."""
        r = SavedDict(d, where, cls.KEYS, ("eigenvectors",))
        V = r.array("V")
        T = V.size
        if T == 0:
            raise InputError(f"{r.name('V')}: no speeds")
        if not (np.diff(V) > 0).all():
            t = int(np.argmax(np.diff(V) <= 0))
            raise InputError(f"{r.name('V')}: speeds must increase, but V[{t + 1}] = {V[t + 1]!r}"
                             f" follows V[{t}] = {V[t]!r}")
        lam = r.complex_array("eigenvalues", 2, (T, None))
        n = lam.shape[1]
        if n == 0:
            raise InputError(f"{r.name('eigenvalues')}: no modes")
        labels = r.strings("state_labels")
        ns = len(labels)                 # states: n for a dense analysis, more for a reduced one
        if ns == 0:
            raise InputError(f"{r.name('state_labels')}: no states")
        X = r.complex_array("eigenvectors", 3, (T, ns, n)) if r.has("eigenvectors") else None
        partner = r.array("partner", int, shape=(n,))
        if ((partner < -1) | (partner >= n)).any():
            bad = int(partner[(partner < -1) | (partner >= n)][0])
            raise InputError(f"{r.name('partner')}: mode id {bad} is outside [-1, {n - 1}]")
        unresolved = r.array("unresolved", ndim=2, shape=(None, 2))
        return cls(
            V=V, eigenvalues=lam, eigenvectors=X,
            dlam_dV=r.complex_array("dlam_dV", 2, (T, n)),
            physical=r.array("physical", bool, 2, (T, n)),
            state_labels=labels,
            displacement=r.array("displacement", bool, shape=(ns,)),
            mode_labels=r.strings("mode_labels", n), partner=partner,
            grid=r.array("grid"), floor=r.array("floor", shape=(T,)),
            unresolved=tuple((float(lo), float(hi)) for lo, hi in unresolved),
            stats=r.counters("stats"),
        )


@dataclass(frozen=True)
class CriticalPoint:
    """A sign change of a tracked mode's real part: the engine's raw crossing.

    The analysis names it (:class:`propwhirl.analysis.stability.Instability`, the event a
    user sees: its ``event`` is this ``direction``, or "unstable-at-start" /
    "frequency-zero" for events without a crossing).  The quantities both have carry the same
    names in both dict forms: kind, mode, label, V [m/s], frequency_hz [Hz], benignity [m/s].

    Attributes
    ----------
    mode : int
        Tracked mode id.
    label : str
        Its label.
    kind : {"flutter", "divergence"}
        "flutter" (complex pair, Im λ ≠ 0) or "divergence" (real root through 0).
    direction : {"onset", "recovery"}
        "onset" (Re λ − → +) or "recovery" (+ → −).
    V : float
        Crossing speed [m/s] (bracket width ≤ xtol).
    bracket : tuple of float
        (lo, hi) [m/s] around V.
    frequency_hz : float
        |Im λ|/2π at V [Hz].
    eigenvalue : complex
        λ at V [1/s].
    dzeta_dV : float or None
        dζ/dV at V [s/m] (from dλ/dV, or a central difference), None for divergence.
    benignity : float or None
        (dζ/dV)⁻¹ [m/s] (eq. 5.13), signed (negative at an onset); None for divergence.
    eigenvector : ndarray
        Full-state eigenvector at V (mode shape for plotting).

    Examples
    --------
    The oscillator ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0 flutters at 50 m/s, 10 rad/s, with
    dζ/dV = −0.01/(2ω) = −5e-4 s/m:

    >>> import numpy as np
    >>> from propwhirl.engine import analyse
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1], A[:, 1, 0], A[:, 1, 1] = 1.0, -100.0, -(0.5 - 0.01 * V)
    ...     return A
    >>> p = analyse(state_matrix, np.arange(10.0, 101.0, 10.0), n_dof=1).criticals.points[0]
    >>> p.kind, p.direction, p.label, round(p.V, 2), round(p.frequency_hz, 3)
    ('flutter', 'onset', 'mode 0', 50.0, 1.592)
    >>> round(p.benignity), p.eigenvector.shape
    (-2000, (2,))
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
    def from_dict(cls, d: Mapping[str, Any], where: str = "point") -> "CriticalPoint":
        """The point written by :meth:`to_dict`, checked (an :class:`InputError` naming the key)."""
        r = SavedDict(d, where, [f.name for f in fields(cls)])
        e = r.sub("eigenvalue", ("re", "im"))
        lam = complex(e.number("re"), e.number("im"))
        return cls(mode=r.integer("mode", 0), label=r.string("label"),
                   kind=r.string("kind", ("flutter", "divergence")),
                   direction=r.string("direction", ("onset", "recovery")), V=r.number("V"),
                   bracket=r.bracket("bracket"), frequency_hz=r.number("frequency_hz"),
                   eigenvalue=lam, dzeta_dV=r.number("dzeta_dV", optional=True),
                   benignity=r.number("benignity", optional=True),
                   eigenvector=r.complex_array("eigenvector", 1))


@dataclass(frozen=True)
class Hump:
    """A mode that goes unstable at ``V_onset`` and recovers at ``V_recovery`` [m/s].

    Attributes
    ----------
    mode : int
        Tracked mode id.
    label : str
        Its label.
    kind : {"flutter", "divergence"}
        Oscillatory or not.
    V_onset, V_recovery : float
        Speeds [m/s] where Re λ turns positive and negative again.

    Examples
    --------
    An oscillator whose damping −0.0004 (V − 50)(V − 80) [1/s] is negative between 50 and
    80 m/s:

    >>> import numpy as np
    >>> from propwhirl.engine import analyse
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1], A[:, 1, 0] = 1.0, -100.0
    ...     A[:, 1, 1] = -0.0004 * (V - 50.0) * (V - 80.0)
    ...     return A
    >>> (h,) = analyse(state_matrix, np.arange(1.0, 201.0, 5.0), n_dof=1).criticals.humps
    >>> h.kind, round(h.V_onset, 2), round(h.V_recovery, 2)
    ('flutter', 50.0, 80.0)
    """

    mode: int
    label: str
    kind: str
    V_onset: float
    V_recovery: float


@dataclass(frozen=True)
class Criticals:
    """All crossings of a sweep (sorted by V), hump modes, modes unstable at the first speed.

    Attributes
    ----------
    points : tuple of CriticalPoint
        Every crossing of Re λ = 0, sorted by speed [m/s].
    humps : tuple of Hump
        The modes that go unstable and recover within the speeds.
    unstable_at_start : tuple of int
        Ids of the modes with Re λ > 0 at the first speed.
    stats : mapping of str to int
        Counters of the refinement.

    Examples
    --------
    The oscillator of :class:`Hump`, unstable between 50 and 80 m/s:

    >>> import numpy as np
    >>> from propwhirl.engine import analyse
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1], A[:, 1, 0] = 1.0, -100.0
    ...     A[:, 1, 1] = -0.0004 * (V - 50.0) * (V - 80.0)
    ...     return A
    >>> c = analyse(state_matrix, np.arange(1.0, 201.0, 5.0), n_dof=1).criticals
    >>> [(p.direction, round(p.V, 2)) for p in c.points], c.unstable_at_start
    ([('onset', 50.0), ('recovery', 80.0)], ())
    >>> round(c.first_onset.V, 2)
    50.0
    """

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
    def from_dict(cls, d: Mapping[str, Any], where: str = "criticals") -> "Criticals":
        """The crossings written by :meth:`to_dict`, checked (an :class:`InputError` naming
        the key)."""
        r = SavedDict(d, where, ("points", "humps", "unstable_at_start", "stats"))
        for key in ("points", "humps"):
            if not isinstance(r.raw(key), list):
                raise InputError(f"{r.name(key)}: must be a list, got {json_type(r.raw(key))}")
        humps = []
        for i, h in enumerate(r.raw("humps")):
            hr = SavedDict(h, f"{r.name('humps')}[{i}]", [f.name for f in fields(Hump)])
            humps.append(Hump(hr.integer("mode", 0), hr.string("label"),
                              hr.string("kind", ("flutter", "divergence")),
                              hr.number("V_onset"), hr.number("V_recovery")))
        start = r.array("unstable_at_start", int)
        if (start < 0).any():
            raise InputError(f"{r.name('unstable_at_start')}: mode ids must be >= 0")
        return cls(points=tuple(CriticalPoint.from_dict(p, f"{r.name('points')}[{i}]")
                                for i, p in enumerate(r.raw("points"))),
                   humps=tuple(humps), unstable_at_start=tuple(int(k) for k in start),
                   stats=r.counters("stats"))


@dataclass(frozen=True)
class FrequencyZero:
    """An unstable oscillatory mode whose pair turns into real roots (its frequency falls to 0).

    The thesis's "whirl divergence" of an already unstable whirl mode (Table 10.4); see
    :func:`propwhirl.engine.crossings.frequency_zero_points`.

    Attributes
    ----------
    mode : int
        Tracked mode id.
    label : str
        Its label.
    V : float
        Speed of the branch point [m/s] (middle of `bracket`).
    bracket : tuple of float
        (lo, hi) [m/s], width ≤ xtol: at lo the number of unstable complex pairs is the one at
        the step's start, at hi it is smaller.

    Examples
    --------
    A stable oscillator and an unstable pair 1 ± √(V − 30) that turns real at V = 30 m/s:

    >>> import numpy as np
    >>> from propwhirl.engine import frequency_zero_points, sweep
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 4, 4))
    ...     A[:, 0, 0] = A[:, 1, 1] = -0.2
    ...     A[:, 0, 1], A[:, 1, 0] = 5.0, -5.0
    ...     A[:, 2, 2] = A[:, 3, 3] = 1.0
    ...     A[:, 2, 3], A[:, 3, 2] = 1.0, V - 30.0
    ...     return A
    >>> sw = sweep(state_matrix, np.arange(1.0, 52.0, 10.0))
    >>> (p,) = frequency_zero_points(sw, state_matrix)
    >>> p.mode, p.label, round(p.V, 2)
    (1, 'mode 1', 30.0)
    """

    mode: int
    label: str
    V: float
    bracket: tuple[float, float]

    def to_dict(self) -> dict[str, Any]:
        return {"mode": self.mode, "label": self.label, "V": self.V,
                "bracket": list(self.bracket)}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], where: str = "frequency_zero") -> "FrequencyZero":
        """The event written by :meth:`to_dict`, checked (an :class:`InputError` naming the key)."""
        r = SavedDict(d, where, ("mode", "label", "V", "bracket"))
        return cls(r.integer("mode", 0), r.string("label"), r.number("V"), r.bracket("bracket"))


@dataclass(frozen=True)
class Analysis(Result):
    """A sweep and its critical points (the engine's result, before modes are named).

    A :class:`~propwhirl.results.Result` of kind "engine-analysis" (format
    ``propwhirl.engine-analysis/1``; a dict without a format, as written before it, is
    version 1).  Its eigenvectors are in the JSON (``include_eigenvectors``).

    Attributes
    ----------
    sweep : Sweep
        The tracked eigen-solutions [λ in 1/s] along the speeds [m/s].
    criticals : Criticals
        Its crossings, humps and modes unstable at the first speed.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> from propwhirl.engine import Analysis, analyse
    >>> def state_matrix(V):     # ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0: flutter at 50 m/s
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1], A[:, 1, 0], A[:, 1, 1] = 1.0, -100.0, -(0.5 - 0.01 * V)
    ...     return A
    >>> an = analyse(state_matrix, np.arange(10.0, 101.0, 10.0), n_dof=1)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = an.save(pathlib.Path(folder) / "engine.json")
    ...     again = Analysis.load(path)
    >>> round(again.criticals.first_onset.V, 2), again.sweep.V.size == an.sweep.V.size
    (50.0, True)
    """

    sweep: Sweep
    criticals: Criticals

    KIND: ClassVar[str] = "engine-analysis"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    UNTAGGED: ClassVar[int | None] = 1
    WHAT: ClassVar[str] = "engine analysis file"

    def to_dict(self, include_eigenvectors: bool = True) -> dict[str, Any]:
        """``{"format": ..., "sweep": ..., "criticals": ...}`` (JSON-able)."""
        return {"format": self.format_name(), "sweep": self.sweep.to_dict(include_eigenvectors),
                "criticals": self.criticals.to_dict()}

    def encode(self) -> dict[str, Any]:
        return {"sweep": self.sweep.to_dict(), "criticals": self.criticals.to_dict()}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "Analysis":
        """The sweep, its crossings, and mode ids within the sweep's modes, checked (an
        :class:`InputError` naming the key)."""
        r = SavedDict(d, where, ("sweep", "criticals"))
        sweep = Sweep.from_dict(r.raw("sweep"), r.name("sweep"))
        crit = Criticals.from_dict(r.raw("criticals"), r.name("criticals"))
        ids = [("points", p.mode) for p in crit.points] + [("humps", h.mode) for h in crit.humps]
        ids += [("unstable_at_start", k) for k in crit.unstable_at_start]
        for key, k in ids:
            if k >= sweep.n_modes:
                raise InputError(f"{r.name('criticals')}.{key}: mode id {k} is outside the sweep's "
                                 f"{sweep.n_modes} modes")
        return cls(sweep, crit)


# ----------------------------------------------------------------------------- eigenvector files
def eigenvectors_path(path: str | Path) -> Path:
    """The eigenvector file beside an analysis file: ``a.json`` → ``a.eigenvectors.npz``."""
    path = Path(path)
    stem = path.name[: -len(path.suffix)] if path.suffix else path.name
    return path.with_name(stem + ".eigenvectors.npz")


def eigenvectors_npz(sweep: "Sweep") -> bytes:
    """The eigenvectors of ``sweep`` as the bytes of a NumPy ``.npz`` (arrays V, eigenvalues,
    eigenvectors; uncompressed: complex numbers barely compress), read back by
    :func:`read_eigenvectors`."""
    import io

    if sweep.eigenvectors is None:
        raise InputError("the sweep has no eigenvectors to write")
    if not np.isfinite(sweep.eigenvectors).all():
        raise InputError("the eigenvectors hold non-finite numbers")
    buf = io.BytesIO()
    np.savez(buf, V=sweep.V, eigenvalues=sweep.eigenvalues, eigenvectors=sweep.eigenvectors)
    return buf.getvalue()


#: bytes of a ``.npy`` header at most (numpy's own bound on the header it parses)
NPY_HEADER_MAX = 10_000
#: bytes of zip structure around the members of an ``.npz`` at most (local and central
#: headers, end record; ≈ 100 bytes per member, the rest is slack for zip64 and comments)
NPZ_OVERHEAD = 64 * 2 ** 10
#: bytes inflated per read from a zip member
_NPZ_CHUNK = 2 ** 20
#: compression methods numpy writes (np.savez: stored, np.savez_compressed: deflated); others
#: (bzip2, LZMA) are refused: their decompressors are not bounded per read
_NPZ_METHODS = (0, 8)


def _array_text(shape: Sequence[int], dtype: np.dtype) -> str:
    return f"{shape_text(shape)} {np.dtype(dtype).name}"


def _read_exact(fh, n: int, what: str) -> bytes:
    """`n` bytes of the zip member `fh` (a short read is continued); ValueError at its end."""
    data = b""
    while len(data) < n:
        chunk = fh.read(n - len(data))
        if not chunk:
            raise ValueError(f"{what} ends after {len(data)} of {n} bytes (truncated?)")
        data += chunk
    return data


def _read_npy(fh, size: int, key: str, shape: tuple[int, ...], dtype: np.dtype,
              where: str, mismatch: str) -> np.ndarray:
    """The array `key` of the open ``.npy`` member `fh` (declared uncompressed size `size`),
    which must be of `shape` and `dtype` (either byte order): its header is read and checked
    first, then exactly its data, in chunks (never more than the member declares)."""
    import io

    from numpy.lib import format as npf

    major, minor = npf.read_magic(fh)
    if (major, minor) not in ((1, 0), (2, 0)):
        raise InputError(f"{where}: array {key}: .npy format version {major}.{minor}, "
                         "need 1.0 or 2.0 (as numpy.savez writes)")
    width = 2 if major == 1 else 4
    raw = _read_exact(fh, width, f"array {key}'s header")
    length = int.from_bytes(raw, "little")
    if length > NPY_HEADER_MAX:
        raise InputError(f"{where}: array {key}: a header of {length:,} bytes, at most "
                         f"{NPY_HEADER_MAX:,}")
    header = raw + _read_exact(fh, length, f"array {key}'s header")
    read_header = npf.read_array_header_1_0 if major == 1 else npf.read_array_header_2_0
    got_shape, fortran, got = read_header(io.BytesIO(header))
    if (tuple(got_shape) != tuple(shape) or got.hasobject or got.fields is not None
            or got.subdtype is not None or got.str[1:] != dtype.str[1:]):
        raise InputError(f"{where}: array {key} declares shape {_array_text(got_shape, got)}, "
                         f"expected {_array_text(shape, dtype)}{mismatch}")
    n_bytes = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
    total = npf.MAGIC_LEN + len(header) + n_bytes
    if size != total:
        raise InputError(f"{where}: array {key} declares {size:,} bytes uncompressed, its "
                         f"header and shape {shape_text(shape)} need {total:,}")
    out = np.empty(int(np.prod(shape, dtype=np.int64)), dtype=got)
    view = memoryview(out.view(np.uint8))
    done = 0
    while done < n_bytes:
        chunk = fh.read(min(_NPZ_CHUNK, n_bytes - done))
        if not chunk:
            raise InputError(f"{where}: array {key} ends after {done:,} of {n_bytes:,} bytes "
                             "(truncated?)")
        view[done:done + len(chunk)] = chunk
        done += len(chunk)
    if fh.read(1):          # at the member's end: zipfile checks its CRC-32 here
        raise InputError(f"{where}: array {key} has data after its {n_bytes:,} bytes")
    out = out.reshape(shape, order="F" if fortran else "C")
    return np.ascontiguousarray(out, dtype=dtype)


def read_npz(path: str | Path, expected: Mapping[str, tuple[tuple[int, ...], Any]],
             where: str | None = None, what: str = "npz file",
             mismatch: str = "") -> dict[str, np.ndarray]:
    """The arrays of the ``.npz`` file `path` (as :func:`numpy.savez` writes it), each checked
    against `expected` (name → (shape, dtype)) before it is read.

    Nothing is allocated or inflated on the file's word: the arrays' total size is held to
    :func:`propwhirl.limits.memory_limit` (:func:`propwhirl.limits.check_read`), the file's
    size to the arrays' (plus :data:`NPZ_OVERHEAD`), each zip member's declared uncompressed
    size (``ZipInfo.file_size``) to its array's (plus :data:`NPY_HEADER_MAX`), each ``.npy``
    header's shape and dtype to the expected ones, and the data is inflated in chunks, never
    beyond the declared size.  No pickle (object arrays are refused).  Anything else is an
    :class:`InputError` of one line starting with `where` (default: the path), naming the
    array, its declared shape and the expected one (followed by `mismatch`, e.g. where the
    expected shapes come from); a file that is no zip or no ``.npz`` "cannot read the `what`".
    """
    import zipfile
    import zlib

    path = Path(path)
    where = str(path) if where is None else where
    want = {k: (tuple(int(x) for x in shape), np.dtype(dt)) for k, (shape, dt) in expected.items()}
    n_bytes = {k: int(np.prod(shape, dtype=object)) * dt.itemsize
               for k, (shape, dt) in want.items()}
    check_read(sum(n_bytes.values()), f"{where}: its arrays "
               + ", ".join(f"{k} {_array_text(*want[k])}" for k in want))
    need = " and ".join(want)
    most = sum(n_bytes.values()) + len(want) * NPY_HEADER_MAX + NPZ_OVERHEAD
    try:
        # a regular file of at most `most` bytes, checked before it is opened
        with fileio.open_input(path, what, most,
                               bound=f"its arrays {need} take at most") as fh:
            with zipfile.ZipFile(fh) as z:
                infos = z.infolist()
                names = [i.filename for i in infos]
                if sorted(names) != sorted(f"{k}.npy" for k in want):
                    raise InputError(f"{where}: holds the arrays "
                                     f"{[n.removesuffix('.npy') for n in names][:10]}, "
                                     f"need {need}")
                out = {}
                for info in infos:
                    key = info.filename.removesuffix(".npy")
                    shape, dt = want[key]
                    if info.compress_type not in _NPZ_METHODS:
                        raise InputError(f"{where}: array {key} is compressed with zip method "
                                         f"{info.compress_type}, not one numpy writes")
                    if info.file_size > n_bytes[key] + NPY_HEADER_MAX:
                        raise InputError(f"{where}: array {key} declares "
                                         f"{format_bytes(info.file_size)} uncompressed, "
                                         f"expected {_array_text(shape, dt)} "
                                         f"({format_bytes(n_bytes[key])})")
                    with z.open(info) as member:
                        out[key] = _read_npy(member, info.file_size, key, shape, dt, where,
                                             mismatch)
                return out
    except InputError as exc:           # fileio's line names the file: `where` only if not
        msg = str(exc)
        named = msg.startswith(where) or fileio.quoted(path) in msg
        raise InputError(msg if named else f"{where}: {msg}") from None
    except OSError as exc:
        raise InputError(f"{where}: cannot read the {what}: {exc.strerror or exc}") from None
    except (ValueError, zipfile.BadZipFile, EOFError, zlib.error, RuntimeError,
            NotImplementedError, SyntaxError) as exc:
        why = " ".join(str(exc).split())[:200]
        raise InputError(f"{where}: cannot read the {what}: {why}") from None


def read_eigenvectors(path: str | Path, sweep: "Sweep", where: str | None = None) -> np.ndarray:
    """The eigenvectors of ``sweep`` read from the ``.npz`` written by
    :func:`eigenvectors_npz`, checked against it: the arrays' shapes and dtypes before
    reading (:func:`read_npz`: V (T,), eigenvalues (T, n), eigenvectors (T, n_states, n),
    within the memory limit), then the same speeds and eigenvalues (bit for bit), finite;
    else an :class:`InputError` naming the file (as `where`, default the path)."""
    path = Path(path)
    where = str(path) if where is None else where
    T, n = sweep.eigenvalues.shape
    ns = len(sweep.state_labels)
    arrays = read_npz(path, {"V": ((T,), np.float64), "eigenvalues": ((T, n), np.complex128),
                             "eigenvectors": ((T, ns, n), np.complex128)}, where,
                      "eigenvector file", ": does not belong to this analysis file (written "
                      "by another analysis?)")
    V, lam, X = arrays["V"], arrays["eigenvalues"], arrays["eigenvectors"]
    if not (np.array_equal(V, sweep.V) and np.array_equal(lam, sweep.eigenvalues)):
        raise InputError(f"{where}: does not belong to this analysis file (its speeds or "
                         "eigenvalues differ: written by another analysis?)")
    if not np.isfinite(X).all():
        raise InputError(f"{where}: eigenvectors hold non-finite numbers")
    return X
