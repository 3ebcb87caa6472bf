"""The Campbell diagram: natural frequencies against propeller rotational speed, each mode followed.

Figures 8.6, 9.16, 10.3, 10.11 of the thesis.  :func:`campbell` follows every mode of the
undamped gyroscopic system M q̈ + G(Ω) q̇ + K q = 0 (aerodynamics and dissipative damping off;
G linear in the rotational speed Ω) from Ω = 0 up the asked speeds with the tracking over Ω of
:mod:`propwhirl.analysis.modes` — the engine's tracking core with the Hermitian-definite
problem's nodes and its linking by MAC in the energy norm (veering pairs followed on their
analytic branches, true crossings kept) — and names the modes at Ω = 0 by
:func:`~propwhirl.analysis.modes.label_modes`, which follows them with the same tracking.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.analysis.modes import (GyroscopicSystem, label_modes, model_modes,  # noqa: F401
                                     track_gyroscopic)
from propwhirl.analysis.naming import FAMILIES, kinetic_energy_shares, mode_family
from propwhirl.model.protocol import refusal
from propwhirl.results import Result, SavedDict

#: Default propeller speeds of :func:`campbell`: 0–6000 rev/min every 250 (covers the
#: operating range of chapters 9–10; 4433 rev/min at the flutter point of Table 9.5)
CAMPBELL_RPM = np.arange(0.0, 6001.0, 250.0)


def mode_families(model, labels: tuple[str, ...] | None = None) -> tuple[str, ...]:
    """Family of each in-vacuo mode (ascending frequency, as :func:`label_modes`) by
    :func:`propwhirl.analysis.naming.mode_family` from its name and its kinetic-energy shares
    (:func:`propwhirl.analysis.naming.kinetic_energy_shares`): "backward whirl" / "forward
    whirl" for the modes :func:`label_modes` names so, and for the others "wing torsion"
    where the wing twist α holds more of the mode's kinetic energy than the bending DOFs
    (h, φ), else "wing bending"."""
    labels = labels if labels is not None else tuple(lab for lab, _ in label_modes(model))
    modes, M = model_modes(model)
    groups = model.without_aerodynamics().dof_map().groups()
    shares = kinetic_energy_shares(modes.shapes, M, groups)
    return tuple(mode_family(lab, {g: float(f[k]) for g, f in shares.items()})
                 for k, lab in enumerate(labels))


def operating_rpm_ratio(model) -> tuple[float, ...]:
    """Each propeller's rotational speed relative to the first's, from their operation
    (:meth:`propwhirl.model.propellers.propeller.Propeller.rotational_speed`): constant-speed rpm, or
    fixed-pitch windmilling Ω = V/(μR) — a ratio that holds at every airspeed when the
    propellers run in the same operation.  Where it depends on the airspeed (fixed-pitch and
    constant-speed propellers mixed) every ratio is 1 (pass ``rpm_ratio`` to
    :func:`campbell`).  A stopped or feathered installation (``state``) turns at 0 rpm: its
    ratio is 0, and the ratios are relative to the first propeller that turns (all 0 when
    none does).  An isolated propeller: (1.0,)."""
    if not hasattr(model, "propellers"):                 # an isolated propeller
        props, turning = [model.propeller], [True]
    else:                           # a modal model's installations turn always (no state)
        props = [inst.propeller for inst in model.propellers]
        turning = [getattr(inst, "spinning", True) for inst in model.propellers]
    if not props:
        return ()
    if not any(turning):
        return (0.0,) * len(props)
    Vs = np.array([100.0, 200.0])
    speeds = np.array([p.rotational_speed(Vs) if t else np.zeros(2)
                       for p, t in zip(props, turning)])             # (n, 2) [rad/s]
    ratio = speeds / speeds[turning.index(True)]
    if not np.allclose(ratio[:, 0], ratio[:, 1], rtol=1e-12, atol=0.0):
        return tuple(1.0 if t else 0.0 for t in turning)
    return tuple(float(r) for r in ratio[:, 0])


@dataclass(frozen=True)
class CampbellResult(Result):
    """A tracked Campbell diagram: natural frequencies against propeller rotational speed.

    A :class:`~propwhirl.results.Result` of kind "campbell" (format ``propwhirl.campbell/1``;
    a dict of :meth:`to_dict` without a format, as written before it, is version 1):
    :meth:`save` / :meth:`load`, every field checked when read.

    rpm:           (T,) rotational speeds [rev/min] of the first propeller that turns, increasing;
                   propeller j spins at ``rpm_ratio[j]`` × rpm (all at rpm when the ratios are 1).
    frequency_hz:  (T, K) natural frequencies [Hz]; column k is one mode followed along rpm
                   (columns ordered by frequency at rpm = 0).
    labels:        K mode names at rpm = 0 (:func:`label_modes`: "wing n", "backward k",
                   "forward k").
    families:      K mode families (:func:`mode_families`: "wing bending", "wing torsion",
                   "backward whirl", "forward whirl"; any of
                   :data:`propwhirl.analysis.naming.FAMILIES` read).
    rpm_ratio:     each propeller's speed relative to the first's (one per propeller of the
                   model, numbered from 0 in ``model.propellers``).
    slope_hz_per_rpm: (T, K) exact df/d(rpm) [Hz per rev/min] of each curve.
    resolved:      (T,) bool, False where a step of the tracking between the previous speed
                   (or rpm = 0) and this one was left ambiguous at the smallest step.
    unresolved:    the ambiguous steps as (rpm_a, rpm_b) [rev/min].
    nodes:         speeds evaluated (asked speeds, rpm = 0 and the refinement).
    """

    rpm: np.ndarray
    frequency_hz: np.ndarray
    labels: tuple[str, ...]
    slope_hz_per_rpm: np.ndarray
    resolved: np.ndarray
    unresolved: tuple[tuple[float, float], ...] = ()
    nodes: int = 0
    families: tuple[str, ...] = ()
    rpm_ratio: tuple[float, ...] = ()

    @property
    def n_modes(self) -> int:
        return self.frequency_hz.shape[1]

    def propeller_rpm(self) -> np.ndarray:
        """(T, P) rotational speed [rev/min] of each propeller along the diagram."""
        return np.outer(self.rpm, np.asarray(self.rpm_ratio or (1.0,), dtype=float))

    def curve(self, label: str) -> np.ndarray:
        """Frequencies [Hz] of the mode named ``label`` along rpm."""
        if label not in self.labels:
            raise v.InputError(f"label = {label!r} is invalid: must be one of {list(self.labels)}")
        return self.frequency_hz[:, self.labels.index(label)]

    def table(self) -> dict[str, np.ndarray]:
        """Tidy columns sorted by rpm then mode: rpm [rev/min], mode (int), label,
        frequency_hz [Hz], resolved (bool)."""
        T, K = self.frequency_hz.shape
        return {
            "rpm": np.repeat(self.rpm, K),
            "mode": np.tile(np.arange(K), T),
            "label": np.tile(np.asarray(self.labels, dtype=object), T),
            "frequency_hz": self.frequency_hz.reshape(-1),
            "resolved": np.repeat(self.resolved, K),
        }

    KIND: ClassVar[str] = "campbell"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    UNTAGGED: ClassVar[int | None] = 1
    WHAT: ClassVar[str] = "Campbell diagram file"

    def encode(self) -> dict[str, Any]:
        """JSON-able dict of the fields (units as in the field names and docstring)."""
        return {
            "rpm": self.rpm.tolist(), "frequency_hz": self.frequency_hz.tolist(),
            "labels": list(self.labels), "slope_hz_per_rpm": self.slope_hz_per_rpm.tolist(),
            "resolved": self.resolved.tolist(), "unresolved": [list(u) for u in self.unresolved],
            "nodes": self.nodes, "families": list(self.families),
            "rpm_ratio": list(self.rpm_ratio),
        }

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "CampbellResult":
        """rpm (T,) in [0, MAX_RPM] increasing; frequency_hz and slope_hz_per_rpm (T, K)
        finite, frequencies >= 0; K labels; resolved (T,) true/false; unresolved [a, b]
        pairs [rev/min]; nodes >= 0; families none or K of :data:`FAMILIES`; rpm_ratio
        positive (InputError naming the key)."""
        r = SavedDict(d, where, ("rpm", "frequency_hz", "labels", "slope_hz_per_rpm",
                                 "resolved", "unresolved", "nodes", "families", "rpm_ratio"))
        rpm = r.array("rpm")
        if rpm.size == 0:
            raise v.InputError(f"{r.name('rpm')}: no speeds")
        if ((rpm < 0) | (rpm > limits.MAX_RPM)).any() or (np.diff(rpm) <= 0).any():
            raise v.InputError(f"{r.name('rpm')}: must be increasing speeds in "
                               f"[0, {limits.MAX_RPM:g}] rev/min")
        labels = r.strings("labels")
        shape = (rpm.size, len(labels))
        f = r.array("frequency_hz", ndim=2, shape=shape)
        if (f < 0).any():
            raise v.InputError(f"{r.name('frequency_hz')}: frequencies must be >= 0 Hz")
        families = r.strings("families")
        if families and len(families) != len(labels):
            raise v.InputError(f"{r.name('families')}: has {len(families)} entries, need "
                               f"{len(labels)} (one per label) or none")
        bad = [x for x in families if x not in FAMILIES]
        if bad:
            raise v.InputError(f"{r.name('families')}: {bad[0]!r} is invalid: must be one of "
                               f"{', '.join(FAMILIES)}")
        ratio = r.array("rpm_ratio")
        if (ratio < 0).any():
            raise v.InputError(f"{r.name('rpm_ratio')}: ratios must be >= 0 (0: a stopped "
                               "propeller)")
        pairs = [_pair(pair, w) for w, pair in r.items("unresolved")]
        return cls(rpm, f, labels, r.array("slope_hz_per_rpm", ndim=2, shape=shape),
                   r.array("resolved", kind=bool, shape=(rpm.size,)), tuple(pairs),
                   r.integer("nodes", 0), families, tuple(float(x) for x in ratio))


def _pair(x: Any, where: str) -> tuple[float, float]:
    """An unresolved step [rpm_a, rpm_b] [rev/min] (finite, a <= b) read at `where`."""
    bad = v.InputError(f"{where}: must be a pair [rpm_a, rpm_b] of finite speeds [rev/min] "
                       "with rpm_a <= rpm_b")
    if not isinstance(x, list) or len(x) != 2 or any(isinstance(y, bool) for y in x):
        raise bad
    try:
        a, b = (float(y) for y in x)
    except (TypeError, ValueError, OverflowError):
        raise bad from None
    if not (np.isfinite(a) and np.isfinite(b) and a <= b):
        raise bad
    return a, b


def campbell(model, rpm=None, *, rpm_ratio=None, max_frequency_hz: float | None = None,
             mac_min: float = 0.8, min_step: float = 0.01) -> CampbellResult:
    """Tracked Campbell diagram of a propeller–wing model (Figures 8.6, 9.16, 10.3, 10.11).

    Parameters
    ----------
    model : PropellerWing or IsolatedPropeller
        With at least one flexibly mounted propeller; aerodynamics and dissipative damping are
        switched off (the undamped gyroscopic system; the airspeed plays no part).
    rpm : array_like, optional
        Rotational speeds [rev/min] of the first propeller that turns, ≥ 0, increasing (default
        :data:`CAMPBELL_RPM`, 0–6000 every 250).  The modes are followed from rpm = 0
        whether or not it is asked for.
    rpm_ratio : sequence of float, optional
        Each propeller's speed relative to the first turning one's (one per propeller,
        >= 0, 0 for one that does not turn).  Default :func:`operating_rpm_ratio`: as the
        propellers operate (all 1 for equal propellers: every propeller spins at rpm; 0 for a
        stopped or feathered installation).
    max_frequency_hz : float, optional
        Keep only the modes below this frequency [Hz] at rpm = 0.
    mac_min : float
        A step whose matching has a MAC below this is split (module docstring).
    min_step : float
        Smallest step of the refinement [rev/min].

    Returns
    -------
    CampbellResult
        Frequencies [Hz] of each mode along rpm, named at rpm = 0 by :func:`label_modes`.
        At rpm = 0 they are the in-vacuo frequencies of :func:`model_modes`.

    Examples
    --------
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> c = campbell(wingtip_propeller_wing(), [0.0, 2000.0, 4000.0], max_frequency_hz=10.0)
    >>> c.labels
    ('wing 1', 'backward 1', 'forward 1')
    >>> bool(c.curve("backward 1")[-1] < c.curve("backward 1")[0] < c.curve("forward 1")[-1])
    True
    """
    why = refusal(model, "campbell")          # the model contract says when it cannot
    if why is not None or not model.dof_map().whirling():
        raise v.InputError("campbell needs a model with a propeller that whirls on its mount "
                           f"(the rotational speed acts through the pitch/yaw mounts): {why or ''}"
                           .rstrip(": "))
    r = CAMPBELL_RPM.copy() if rpm is None else _check_rpm(rpm)
    ratio = operating_rpm_ratio(model) if rpm_ratio is None else _check_ratio(model, rpm_ratio)
    if max_frequency_hz is not None:
        v.positive("max_frequency_hz", max_frequency_hz, "Hz")
    v.in_range("mac_min", mac_min, 0.0, 1.0)
    v.positive("min_step", min_step, "rev/min")
    per_rpm = 2.0 * np.pi / 60.0                      # [rad/s per rev/min]
    tr = track_gyroscopic(GyroscopicSystem.of(model, ratio), r * per_rpm, mac_min=mac_min,
                          min_step=min_step * per_rpm)
    names = tuple(lab for lab, _ in label_modes(model))
    families = mode_families(model, names)
    keep = np.arange(tr.omega0.size)
    if max_frequency_hz is not None:
        keep = keep[tr.omega0 / (2.0 * np.pi) <= max_frequency_hz]
    return CampbellResult(
        rpm=r, frequency_hz=tr.omega[:, keep] / (2.0 * np.pi),
        labels=tuple(names[k] for k in keep), slope_hz_per_rpm=tr.slope[:, keep] / 60.0,
        resolved=tr.resolved, nodes=tr.nodes, families=tuple(families[k] for k in keep),
        rpm_ratio=ratio,
        unresolved=tuple((a / per_rpm, b / per_rpm) for a, b in tr.unresolved))


#: the valid form of Campbell rotational speeds, for error messages
RPM_FORM = (f"an increasing 1-D array of propeller speeds in [0, {limits.MAX_RPM:,.0f}] rev/min, "
            "e.g. numpy.linspace(0.0, 6000.0, 25)")


def _check_rpm(rpm) -> np.ndarray:
    """Rotational speeds [rev/min]: 1-D, finite, in [0, MAX_RPM], strictly increasing, at
    most :data:`propwhirl.limits.MAX_SPEEDS` values (a number: one speed)."""
    bad = v.InputError(f"rpm = {rpm!r:.60} is invalid: must be {RPM_FORM}")
    if rpm is None or isinstance(rpm, (str, bytes, dict, set, frozenset, bool, np.bool_)):
        raise bad
    try:
        raw = np.atleast_1d(np.asarray(rpm))
    except (TypeError, ValueError, OverflowError) as exc:
        raise bad from exc
    if raw.dtype.kind not in "iuf":
        raise bad
    if raw.ndim != 1 or raw.size == 0:
        raise v.InputError(f"rpm must be a 1-D array of at least 1 value, got shape "
                           f"{raw.shape}: give {RPM_FORM}")
    limits.check_speed_count("rpm", raw.size, "fewer rotational speeds")
    r = v.in_range("rpm", raw.astype(float), 0.0, limits.MAX_RPM, "rev/min")
    return v.increasing("rpm", r, "rev/min") if r.size > 1 else r


def _check_ratio(model, rpm_ratio) -> tuple[float, ...]:
    """rpm_ratio: one finite number >= 0 per propeller of `model` (0: not turning; a stopped
    or feathered installation does not turn whatever its ratio)."""
    n = len(operating_rpm_ratio(model))
    r = np.atleast_1d(np.asarray(rpm_ratio, dtype=float))
    if r.ndim != 1 or r.size != n:
        raise v.InputError(f"rpm_ratio = {rpm_ratio!r:.60} is invalid: must give one ratio per "
                           f"propeller ({n})")
    v.non_negative("rpm_ratio", r)
    return tuple(float(x) for x in r)
