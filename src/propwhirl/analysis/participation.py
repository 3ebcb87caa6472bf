"""Per-propeller participation in a mode: which propeller whirls, how much, in which sense.

For a mode with eigenvalue λ and displacement shape q̂ (the first ``n_dof`` entries of its
eigenvector, eq. 5.7) the kinetic energy is T = ½ ẋᴴ M ẋ with ẋ = λ q̂, so T = ½ |λ|² q̂ᴴ M q̂
(M: the structural mass matrix S1 of the model at that speed — the model without
aerodynamics; the apparent mass of the strip aerodynamics is a load of the air, not kinetic
energy of the structure, and it is not symmetric).  The factor ½ |λ|² cancels in every share.

**The partition.**  The DOFs are split into groups, and group J's share is its own kinetic
energy relative to the sum of the groups' own energies,

    s_J = q̂_Jᴴ M_JJ q̂_J / Σ_K q̂_Kᴴ M_KK q̂_K      (M_JJ: the diagonal block of group J),

so every share is ≥ 0 and the shares of all groups add to exactly 100 %.  The coupling energy
between groups (Re q̂_Jᴴ M_JK q̂_K, J ≠ K: e.g. the propeller's mass moving with its wing
node while it pitches about the pivot) belongs to no group and is left out.  (Splitting it
equally instead — the row partition Re(conj q̂_i (M q̂)_i) that
:func:`propwhirl.analysis.naming.kinetic_energy_shares` uses for the mode content — gives a
propeller *negative* shares when it pitches against its node's motion: −12 % at the wingtip
wing's frequency-zero event.)  The groups are

* **propeller j**: its pitch θ and yaw ψ about the pivot (:class:`PropellerDofs` ``theta``,
  ``psi``; M_JJ its moments of inertia about the pivot) — its motion on its mount, i.e. how
  much it whirls.  The kinetic energy of the propeller's mass carried along by the wing node
  it sits on (that node's h, φ, α) is the *wing's*: a rigidly mounted propeller has no θ, ψ
  and so a whirl share of 0;
* **propeller j on a hub grid** (a modal structure's mount in the modes, ``mount =
  "on-grid"``: :class:`~propwhirl.model.protocol.HubDofs`): its pitch and yaw on the mount,
  û = R q̂ (the hub grid's rotations less the wing's there), its energy ûᴴ J û with J =
  diag(I_θ, I_ψ), its pivot inertias; that energy is inside the modes' and is taken out of
  the wing's, and so is the coupling 2 Re(ûᴴ C ŵ) of its pitch and yaw with the wing's heave
  and twist ŵ under the hub (C: a flexible mount's θψ–hα mass block), which a flexible mount's
  partition leaves out: on the same structure the shares are a flexible mount's (to 1e-3 on
  the six-propeller wing of tests/analysis/test_modal_names.py);
* **wing**: every wing DOF (h, φ, α of every free node), the inertia the propellers add at
  their nodes included;
* **other**: any other structural DOF (the typical section's plunge and pitch).

So wing + other + Σ_j propeller j = 1 for every mode (before rounding; the printed
percentages are rounded by largest remainders, so they add to 100 as well).

Besides the share, each propeller's **whirl sense** (forward / backward / planar, from the
sense of its θ–ψ orbit relative to its own rotation: :func:`propwhirl.analysis.whirl.whirl_sense`;
None when it does not spin or for a real root), its **amplitude** √(|θ̂|² + |ψ̂|²) relative to
the largest propeller amplitude of the mode (1 for the most whirling propeller), and its
spanwise position y [m].  Propellers are numbered from 1 in their model's order
(``PropellerWing.propellers``; rigid ones count), "propeller 3" being ``propellers[2]``.

Examples
--------
>>> from propwhirl.analysis import analyse
>>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
>>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
>>> print(a.critical.participation.describe())
propeller 1: 100 %, backward whirl
"""
from __future__ import annotations

import re
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.analysis.modes import InVacuo
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.engine import eigen, mac
from propwhirl.model.protocol import DofMap, Model
from propwhirl.results import SavedDict

_WHIRL = ("forward", "backward", "planar")


def _percentages(shares: np.ndarray) -> np.ndarray:
    """Whole percentages of shares summing to one, rounded by largest remainders (they add
    to 100); negative shares are rounded to the nearest integer and kept aside."""
    p = 100.0 * np.asarray(shares, dtype=float)
    out = np.rint(p)
    pos = p > 0
    if pos.any():
        target = 100 - int(out[~pos].sum())
        base = np.floor(p[pos])
        rest = int(target - base.sum())
        order = np.argsort(-(p[pos] - base), kind="stable")
        base[order[:max(rest, 0)]] += 1
        out[pos] = base
    return out.astype(int)


@dataclass(frozen=True)
class PropellerShare:
    """One flexibly mounted propeller's part in one mode.

    propeller: its number, from 1 (``PropellerWing.propellers[propeller - 1]``).
    y:         spanwise position [m] of its wing node; None without a wing.
    share:     its θ–ψ share of the mode's kinetic energy (the partition of the module
               docstring), in [0, 1].
    whirl:     "forward", "backward" or "planar" sense of its θ–ψ orbit relative to its own
               rotation; None when it does not spin or the root is real.
    amplitude: √(|θ̂|² + |ψ̂|²) relative to the largest propeller amplitude of the mode [-].
    """

    propeller: int
    y: float | None
    share: float
    whirl: str | None
    amplitude: float

    def name(self) -> str:
        """'propeller 3 (y = 3.00 m)'."""
        where = "" if self.y is None else f" (y = {self.y:.2f} m)"
        return f"propeller {self.propeller}{where}"

    def to_dict(self) -> dict[str, Any]:
        return {"propeller": self.propeller, "y": self.y, "share": self.share,
                "whirl": self.whirl, "amplitude": self.amplitude}


@dataclass(frozen=True)
class ModeParticipation:
    """The participation of the propellers in one mode at one speed.

    V:          speed [m/s] at which the mode shape was taken.
    wing:       share of the wing DOFs; other: of any other structural DOF (typical section).
    propellers: every flexibly mounted propeller, in model order.
    """

    V: float
    wing: float
    other: float
    propellers: tuple[PropellerShare, ...]

    def share_of(self, propeller: int) -> float:
        """Share of propeller ``propeller`` (numbered from 1); 0 for a propeller without pitch
        and yaw DOFs (rigidly mounted)."""
        for p in self.propellers:
            if p.propeller == propeller:
                return p.share
        return 0.0

    @property
    def leading(self) -> PropellerShare | None:
        """The propeller with the largest amplitude (the one whose whirl an event reports)."""
        return max(self.propellers, key=lambda p: p.amplitude) if self.propellers else None

    def describe(self, count: int | None = None, sep: str = "; ") -> str:
        """'propeller 3 (y = 3.00 m): 61 %, backward whirl; ...; wing 14 %' — the propellers by
        decreasing share (with ``count``: the first ``count`` of those above 0 %), then the
        wing (and other DOFs) when present."""
        parts = [(p.share, p) for p in self.propellers]
        rest = [("wing", self.wing)] if self.wing != 0 else []
        rest += [("other DOFs", self.other)] if self.other != 0 else []
        pct = _percentages(np.array([s for s, _ in parts] + [s for _, s in rest]))
        ranked = sorted(range(len(parts)), key=lambda i: -parts[i][0])
        if count is not None:                  # the leading ones, those that show at all
            ranked = [i for i in ranked[:count] if pct[i] > 0]
        out = [] if ranked or not parts else ["propeller share 0 %"]
        for i in ranked:
            p = parts[i][1]
            w = f", {p.whirl} whirl" if p.whirl else ""
            amp = f", amplitude {p.amplitude:.2f}" if len(parts) > 1 else ""
            out.append(f"{p.name()}: {pct[i]} %{w}{amp}")
        out += [f"{name} {pct[len(parts) + i]} %" for i, (name, _) in enumerate(rest)]
        return sep.join(out)

    def to_dict(self) -> dict[str, Any]:
        return {"V": self.V, "wing": self.wing, "other": self.other,
                "propellers": [p.to_dict() for p in self.propellers]}

    @classmethod
    def from_dict(cls, d: Any, where: str = "participation") -> "ModeParticipation":
        """The participation written by :meth:`to_dict`, checked (an InputError naming the key)."""
        r = SavedDict(d, where, ("V", "wing", "other", "propellers"))
        props = r.raw("propellers")
        if not isinstance(props, list):
            raise v.InputError(f"{r.name('propellers')}: must be a list")
        out = []
        for i, p in enumerate(props):
            pr = SavedDict(p, f"{r.name('propellers')}[{i}]",
                           ("propeller", "y", "share", "whirl", "amplitude"))
            out.append(PropellerShare(pr.integer("propeller", 1), pr.number("y", optional=True),
                                      pr.number("share"), pr.string("whirl", _WHIRL, True),
                                      pr.number("amplitude")))
        return cls(r.number("V"), r.number("wing"), r.number("other"), tuple(out))


@dataclass(frozen=True)
class Participation:
    """Participation of m modes (the last axis) of one model; P flexibly mounted propellers.

    V:         (m,) speed [m/s] of each mode shape.
    number:    (P,) propeller numbers, from 1.
    y:         (P,) spanwise positions [m] (NaN without a wing).
    share:     (P, m) kinetic-energy share of each propeller's θ, ψ.
    wing:      (m,) share of the wing DOFs; other: (m,) of any other structural DOF.
    whirl:     (P, m) object array of "forward" / "backward" / "planar" / None.
    amplitude: (P, m) θ–ψ amplitude relative to the mode's largest propeller amplitude.
    """

    V: np.ndarray
    number: np.ndarray
    y: np.ndarray
    share: np.ndarray
    wing: np.ndarray
    other: np.ndarray
    whirl: np.ndarray
    amplitude: np.ndarray

    @property
    def n_modes(self) -> int:
        return self.wing.shape[0]

    def mode(self, k: int) -> ModeParticipation:
        """The participation of mode (column) ``k``."""
        props = tuple(
            PropellerShare(int(self.number[j]), None if np.isnan(self.y[j]) else float(self.y[j]),
                           float(self.share[j, k]), self.whirl[j, k], float(self.amplitude[j, k]))
            for j in range(self.number.size))
        return ModeParticipation(float(self.V[k]), float(self.wing[k]), float(self.other[k]),
                                 props)


def participation(dm: DofMap, X, M, eigenvalues, V) -> Participation:
    """Per-propeller participation of modes (module docstring).

    Parameters
    ----------
    dm : DofMap
        The model's DOF map.
    X : array_like, (n, m) complex
        Mode shapes in columns: full-state eigenvectors (n = ``dm.n_states``) or their
        displacement parts (n = ``dm.n_dof``).
    M : array_like, (n_dof, n_dof) or (m, n_dof, n_dof)
        Structural mass matrix S1 [kg, kg m, kg m²] (one for all modes, or one per mode).
    eigenvalues : array_like, (m,) complex
        λ of each mode [1/s] (its sign of Im λ sets the orbit sense; real: no whirl sense).
    V : float or array_like (m,)
        Speed of each mode shape [m/s] (recorded).

    Returns
    -------
    Participation
    """
    X = np.asarray(X, dtype=complex)
    if X.ndim == 1:
        X = X[:, None]
    if X.shape[0] not in (dm.n_dof, dm.n_states):
        raise v.InputError(f"mode shapes have {X.shape[0]} rows, need {dm.n_dof} (displacements) "
                           f"or {dm.n_states} (states)")
    q = X[: dm.n_dof]
    m = q.shape[1]
    lam = np.broadcast_to(np.asarray(eigenvalues, dtype=complex), (m,))
    Vs = np.broadcast_to(np.asarray(V, dtype=float), (m,)).copy()
    M = np.asarray(M, dtype=float)
    if M.shape[-2:] != (dm.n_dof, dm.n_dof):
        raise v.InputError(f"mass matrix of shape {M.shape}, need ({dm.n_dof}, {dm.n_dof})")
    props = dm.whirling()
    wing = np.array([i for i, (n, k) in enumerate(zip(dm.q_node, dm.q_kinds))
                     if n >= 0 or k == "eta"], dtype=int)        # a modal structure's modes too
    used = set(wing.tolist()) | {i for p in props if p.dofs for i in p.dofs}
    groups = {"wing": wing,
              "other": np.array(sorted(set(range(dm.n_dof)) - used), dtype=int)}
    Ms = np.broadcast_to(M, (m, dm.n_dof, dm.n_dof))
    own = {f"p{j}": p.energy(q, Ms)                # its own DOFs' block, or its inertia
           for j, p in enumerate(props)}
    for g, ix in groups.items():                   # q̂_Jᴴ M_JJ q̂_J of every mode at once
        qJ = q[ix]
        own[g] = np.real(np.einsum("ik,kij,jk->k", qJ.conj(), Ms[:, ix][:, :, ix], qJ))
    # a hub's pitch and yaw (no DOFs of its own) move inside the modes: their energy, and
    # its coupling with the wing's motion under the hub (which a flexible mount's partition
    # gives to no group), are taken out of the wing's (what is left, never below 0)
    hub = sum((own[f"p{j}"] + p.coupling_energy(q) for j, p in enumerate(props)
               if p.dofs is None), np.zeros(m))
    own["wing"] = np.maximum(own["wing"] - hub, 0.0)
    total = sum(own.values())
    sh = {g: np.divide(e, total, out=np.zeros_like(e), where=total > 0) for g, e in own.items()}
    P = len(props)
    share = np.array([sh[f"p{j}"] for j in range(P)]).reshape(P, m)
    u = np.array([p.pitch_yaw(q) for p in props]).reshape(P, 2, m)     # (θ̂, ψ̂) of each
    amp = np.hypot(np.abs(u[:, 0]), np.abs(u[:, 1]))
    top = amp.max(axis=0, initial=0.0)
    rel = np.divide(amp, top, out=np.zeros_like(amp), where=top > 0)
    whirl = np.full((P, m), None, dtype=object)
    for j, p in enumerate(props):
        if not p.spinning:
            continue
        for k in range(m):
            if lam[k].imag != 0:
                whirl[j, k] = whirl_sense(u[j, 0, k], u[j, 1, k], p.rotation, lam[k])
    return Participation(
        V=Vs, number=np.array([p.number + 1 for p in props], dtype=int),
        y=np.array([np.nan if p.y is None else p.y for p in props], dtype=float),
        share=share, wing=sh["wing"], other=sh["other"], whirl=whirl, amplitude=rel)


def mass_matrices(model: Model, V, in_vacuo=None) -> np.ndarray:
    """Structural mass matrices S1 of ``model`` at speeds ``V`` [m/s], (len(V), n_dof, n_dof):
    the model without aerodynamics (module docstring).  A wing model's S1 alone, from its blocks
    (:meth:`~propwhirl.model.blocks.BlockSystem.matrix`): not the six other matrices of each speed,
    which for a large wing are hundreds of MB.  ``in_vacuo``: the model without aerodynamics,
    already assembled (``model.assembly().without_aerodynamics()``), or its structure evaluated
    once (:class:`~propwhirl.analysis.modes.InVacuo`: its mass at every speed, a read-only view
    — without aerodynamics the mass does not depend on the speed); default: assembled here."""
    V = np.atleast_1d(np.asarray(V, dtype=float))
    if isinstance(in_vacuo, InVacuo):
        return np.broadcast_to(in_vacuo.M, V.shape + in_vacuo.M.shape)
    quiet = model.without_aerodynamics() if in_vacuo is None else in_vacuo
    if hasattr(quiet, "second_order_blocks"):
        return quiet.second_order_blocks(V).matrix("S1")
    return quiet.second_order(V).S1


def mode_participation(model: Model, X, eigenvalues, V, in_vacuo=None) -> Participation:
    """:func:`participation` of modes of ``model`` at speeds ``V`` [m/s] (one per mode or one
    for all), with the model's structural mass at each speed (:func:`mass_matrices`, which
    ``in_vacuo`` is passed to)."""
    Vs = np.atleast_1d(np.asarray(V, dtype=float))
    M = mass_matrices(model, Vs, in_vacuo)
    M = M[0] if Vs.size == 1 else M
    return participation(model.dof_map(), X, M, eigenvalues, V)


# ----------------------------------------------------------------------------- events
def branch_point_shape(model: Model, sw, mode: int, V: float, state_matrix=None,
                       lift: np.ndarray | None = None) -> tuple[np.ndarray, complex, float]:
    """(eigenvector, λ, V) of ``mode`` just below a frequency-zero event, at the lower end
    ``V`` [m/s] of its bracket (within xtol of the event, where the pair is still oscillatory):
    of the unstable roots of A(V) with Im λ > 0, the one whose displacement shape is closest
    (MAC, eq. 5.14) to the mode's shape at the last swept speed ≤ V.  ``state_matrix`` and
    ``lift``: a reduced model's A(V) and the map of its states to the model's
    (:mod:`propwhirl.analysis.reduced`); default the model's own A(V)."""
    lam, X = eigen((state_matrix or model.state_matrix)(np.array([V])))
    lam, X = lam[0], X[0] if lift is None else lift @ X[0]
    t = max(int(np.searchsorted(sw.V, V, side="right")) - 1, 0)
    ref = sw.eigenvectors[t, :, mode][sw.displacement]
    cand = [i for i in range(lam.size) if lam[i].real > 0 and lam[i].imag > 0]
    if not cand:                               # (the pair is real already): any unstable root
        cand = [i for i in range(lam.size) if lam[i].real > 0] or list(range(lam.size))
    macs = [float(mac(ref, X[sw.displacement, i])) for i in cand]
    i = cand[int(np.argmax(macs))]
    return X[:, i], complex(lam[i]), float(V)


def with_participation(model: Model, events: list,
                        shapes: list[tuple[np.ndarray, complex, float]], in_vacuo=None) -> list:
    """The events with the propellers' participation in their mode at the event
    (:mod:`propwhirl.analysis.participation`), computed for all events at once
    (``in_vacuo``: :func:`mass_matrices`)."""
    if not events:
        return events
    X = np.stack([x for x, _, _ in shapes], axis=1)
    part = mode_participation(model, X, np.array([lam for _, lam, _ in shapes]),
                              np.array([V for _, _, V in shapes]), in_vacuo)
    return [replace(e, participation=part.mode(k)) for k, e in enumerate(events)]


def _named_numbers(label: str) -> set[int] | None:
    """The propeller numbers a mode's name carries ('... propellers 1–6, 8 ...'), or None."""
    m = re.search(r"propellers? ([0-9–, ]+)", label)
    if m is None:
        return None
    out: set[int] = set()
    for part in m.group(1).replace(" ", "").split(","):
        lo, _, hi = part.partition("–")
        if lo.isdigit():
            out.update(range(int(lo), int(hi if hi.isdigit() else lo) + 1))
    return out or None


def at_the_event(e) -> str:
    """What a whirl flutter mode is at its event when its name (what it was at the first speed)
    says otherwise, e.g. 'backward whirl at the onset' for the wingtip model's 'forward 1' at
    159.39 m/s, or 'at the onset: backward whirl, propeller 3 leading' for a mode named after
    propeller 7; '' when the name still says it (or for a divergence, a wing mode).
    ``e``: an :class:`~propwhirl.analysis.stability.Instability`."""
    if e.kind != "flutter" or e.whirl not in ("forward", "backward"):
        return ""
    sense = e.label.split()[0] if e.label.startswith(("forward", "backward")) else None
    if sense is None:
        return ""
    p = e.participation
    lead = p.leading if p is not None else None
    named = _named_numbers(e.label)
    if lead is not None and named is not None and lead.propeller not in named:
        return f"at the {e.event}: {e.whirl} whirl, propeller {lead.propeller} leading"
    if e.whirl != sense:
        return f"{e.whirl} whirl at the {e.event}"
    return ""


def participation_lines(events, indent: str = "") -> list[str]:
    """Text lines of the propellers' participation at each event that has propellers (events:
    :class:`~propwhirl.analysis.stability.Instability`): one line per event, one more per
    propeller when the model has several."""
    with_props = [e for e in events if e.participation is not None and e.participation.propellers]
    if not with_props:
        return []
    lines = [f"{indent}propellers at each event (numbered from 1): share of the mode's kinetic "
             "energy in each propeller's", f"{indent}pitch and yaw (the wing's: the rest), whirl "
             "sense of its orbit, amplitude relative to the largest"]
    for e in with_props:
        there = at_the_event(e)
        head = (f"{indent}  at the {e.kind} {e.event} of {e.label} ({e.V:.2f} m/s"
                + (f"; {there})" if there else ")"))
        p = e.participation
        if len(p.propellers) == 1:
            lines.append(f"{head}: {p.describe()}")
        else:
            lines.append(f"{head}:")
            lines += [f"{indent}    {part}" for part in p.describe(sep="\n").split("\n")]
    return lines


#: Columns of :func:`events_table`: (key, unit).
EVENT_COLUMNS: tuple[tuple[str, str], ...] = (
    ("kind", ""), ("event", ""), ("mode", ""), ("label", ""), ("V", "m/s"),
    ("frequency_hz", "Hz"), ("propeller", ""), ("y", "m"), ("share", ""), ("whirl", ""),
    ("amplitude", ""), ("wing_share", ""))


def events_table(events) -> dict[str, np.ndarray]:
    """Tidy columns (:data:`EVENT_COLUMNS`) of events and their propellers' participation:
    one row per event and flexibly mounted propeller (propeller numbered from 1), one row
    with propeller 0 and NaN shares for an event without them."""
    rows = []
    for e in events:
        p = e.participation
        base = [e.kind, e.event, e.mode, e.label, e.V, e.frequency_hz]
        if p is None or not p.propellers:
            rows.append(base + [0, np.nan, np.nan, "", np.nan,
                                np.nan if p is None else p.wing])
            continue
        for s in p.propellers:
            rows.append(base + [s.propeller, np.nan if s.y is None else s.y, s.share,
                                s.whirl or "", s.amplitude, p.wing])
    cols = list(zip(*rows)) if rows else [()] * len(EVENT_COLUMNS)
    kinds = {"mode": int, "propeller": int, "V": float, "frequency_hz": float, "y": float,
             "share": float, "amplitude": float, "wing_share": float}
    return {key: np.asarray(col, dtype=kinds.get(key, object))
            for (key, _), col in zip(EVENT_COLUMNS, cols)}


def events_csv(events, path=None) -> str:
    """:func:`events_table` as CSV, header "column [unit]"; NaN as an empty cell; written to
    ``path`` too if given (atomically, :func:`propwhirl.fileio.write_text`)."""
    t = events_table(events)
    return fileio.csv_table({k: t[k] for k, _ in EVENT_COLUMNS}, dict(EVENT_COLUMNS), path,
                            what="events table")
