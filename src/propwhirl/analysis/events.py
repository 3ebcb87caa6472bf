"""Instability events: :class:`Instability` (one named event of a tracked mode) and
:func:`critical`, the one definition of the critical instability.

An :class:`Instability` is the analysis's event; the engine's
:class:`~propwhirl.engine.results.CriticalPoint` is the raw crossing it comes from (a sign
change of Re λ of mode id k, with its bracket, eigenvalue and eigenvector, before the mode has a
name).  :func:`~propwhirl.analysis.stability.analyse` makes one Instability of each
CriticalPoint (event "onset" or "recovery") and adds the events the engine has no crossing for
("unstable-at-start", "frequency-zero").  The same quantities have the same keys in both dict
forms: ``kind``, ``mode``, ``label``, ``V`` [m/s], ``frequency_hz`` [Hz], ``benignity`` [m/s];
the crossing's ``direction`` is the event's ``event``.

This module is at the bottom of :mod:`propwhirl.analysis` (it imports only the participation
it carries): the analysis (:mod:`~propwhirl.analysis.stability`), the p-k method
(:mod:`~propwhirl.analysis.pk`) and the summaries all build on it.
"""
from __future__ import annotations


from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.naming import is_lag
from propwhirl.analysis.participation import ModeParticipation, at_the_event
from propwhirl.results import SavedDict

__all__ = ["Exclusion", "Instability", "UNSTABLE_EVENTS", "critical", "describe_critical"]

#: the values of :attr:`Instability.kind`, :attr:`Instability.event`, :attr:`Instability.whirl`
KINDS = ("flutter", "divergence")
EVENTS = ("onset", "recovery", "frequency-zero", "unstable-at-start")
WHIRL = ("forward", "backward", "planar")


@dataclass(frozen=True)
class Instability:
    """One instability event of a tracked mode (the analysis's named event; the engine's raw
    crossing is :class:`~propwhirl.engine.results.CriticalPoint`: the module docstring).

    Attributes
    ----------
    kind : {"flutter", "divergence"}
        "flutter" (oscillatory) or "divergence" (non-oscillatory).
    event : {"onset", "recovery", "frequency-zero", "unstable-at-start"}
        "onset" (Re λ becomes positive), "recovery" (becomes negative again; hump modes),
        "frequency-zero" (an unstable pair turns into real roots: divergence of that mode),
        "unstable-at-start" (Re λ > 0 already at the first analysed speed, V = that speed).
    mode : int
        Tracked mode id.
    label : str
        The mode's name (e.g. "forward 1", "wing 2"): the name of a structural mode — a branch
        that is an aerodynamic lag root at the first speed ("lag 3") is named after the
        structural mode its shape at the event is (:func:`propwhirl.analysis.naming.event_label`).
    V : float
        Speed of the event [m/s].
    frequency_hz : float
        Frequency at the event [Hz] (0 for divergence).
    whirl : {"forward", "backward", "planar"} or None
        Sense of the θ–ψ orbit of the propeller with the largest θ–ψ motion (None without
        flexible propellers).
    benignity : float or None
        (dζ/dV)⁻¹ [m/s] (eq. 5.13) at flutter onsets (negative: the more negative, the more
        gradual); None otherwise.
    participation : ModeParticipation or None
        Every flexibly mounted propeller's share of the mode's kinetic energy [-], whirl sense,
        relative amplitude and position [m] at the event
        (:mod:`propwhirl.analysis.participation`; None without the mode shape).

    Examples
    --------
    The first flutter of the wingtip model (§10.1): the forward whirl mode, whirling backward
    at its onset, 16 % of its kinetic energy in the propeller:

    >>> from propwhirl.analysis import analyse, first_of_kind
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> e = first_of_kind(analyse(wingtip_propeller_wing()), "flutter")
    >>> e.kind, e.event, e.label, round(e.V, 2), round(e.frequency_hz, 2), e.whirl
    ('flutter', 'onset', 'forward 1', 159.39, 11.25, 'backward')
    >>> round(e.benignity, 1), e.propeller_text()
    (-86.8, 'propeller 1 (y = 5.70 m): 16 %, backward whirl; wing 84 %')
    """

    kind: str
    event: str
    mode: int
    label: str
    V: float
    frequency_hz: float
    whirl: str | None = None
    benignity: float | None = None
    participation: ModeParticipation | None = None

    def propeller_text(self, count: int | None = None) -> str:
        """Which propellers take part: 'propeller 3 (y = 3 m): 61 %, backward whirl, ...'
        ("" without flexibly mounted propellers or without the mode shape)."""
        p = self.participation
        return "" if p is None or not p.propellers else p.describe(count)

    def to_dict(self) -> dict[str, Any]:
        """The event as a JSON-able dict (keys: the fields; a non-finite benignity → None;
        the participation as :meth:`ModeParticipation.to_dict`).  A part of an analysis
        file, without a format tag."""
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        b = self.benignity
        d["benignity"] = None if b is None or not np.isfinite(b) else float(b)
        d["participation"] = None if self.participation is None else self.participation.to_dict()
        return d

    @classmethod
    def from_dict(cls, d: Any, where: str = "event",
                  mode_labels: Sequence[str] | None = None) -> "Instability":
        """The event written by :meth:`to_dict`, checked (an InputError naming the key under
        `where`); with `mode_labels` (the sweep's), the mode id must be one of them and the
        label its name — or, where that names an aerodynamic lag root, the name of a
        structural mode of the sweep (:func:`propwhirl.analysis.naming.event_label`).  whirl,
        benignity and participation may be absent (older files)."""
        r = SavedDict(d, where, ("kind", "event", "mode", "label", "V", "frequency_hz"),
                      ("whirl", "benignity", "participation"))
        high = None if mode_labels is None else len(mode_labels) - 1
        mode = r.integer("mode", 0, high)
        label = r.string("label")
        if mode_labels is not None and label != mode_labels[mode] and not (
                is_lag(mode_labels[mode]) and not is_lag(label) and label in mode_labels):
            raise v.InputError(f"{where}.label = {label!r} is not the name of mode {mode} in "
                               f"the sweep ({mode_labels[mode]!r})")
        part = r.raw("participation") if r.has("participation") else None
        return cls(r.string("kind", KINDS), r.string("event", EVENTS), mode, label,
                   r.number("V"), r.number("frequency_hz"),
                   r.string("whirl", WHIRL, optional=True) if r.has("whirl") else None,
                   r.number("benignity", optional=True) if r.has("benignity") else None,
                   None if part is None
                   else ModeParticipation.from_dict(part, f"{where}.participation"))


#: Events that make the system (more) unstable, candidates for the critical instability.
UNSTABLE_EVENTS = ("onset", "unstable-at-start", "frequency-zero")

#: What :func:`critical` may leave out: kinds ("flutter", "divergence"), or a predicate on an
#: event that is True for events to leave out.
Exclusion = str | Sequence[str] | Callable[[Instability], bool]


def critical(events: Sequence[Instability], *, exclude: Exclusion = ()) -> Instability | None:
    """The critical instability: the lowest-speed event that makes the system unstable.

    This is the one definition used by the summary, the CLI, ``propwhirl run``, the studies and
    the result files.  Candidates are the onsets of flutter and of divergence (static
    divergence included), frequency-zero events (an unstable pair turning real), and modes
    already unstable at the first analysed speed — event "unstable-at-start", reported at that
    speed, never skipped.  Ties at one speed go to the lower mode id.

    Parameters
    ----------
    events : sequence of Instability
        The events of an analysis (:attr:`ModelAnalysis.events`).
    exclude : str, sequence of str or callable, optional
        Leave out events of these kinds ("flutter", "divergence"), or the events for which
        ``exclude(event)`` is True (e.g. the wing's static divergence, which the thesis's
        chapter-11 studies ignore).  Default: nothing is left out.

    Returns
    -------
    Instability or None
        None when nothing is unstable in the analysed range.

    Examples
    --------
    >>> from propwhirl.analysis.stability import Instability, critical
    >>> ev = [Instability("flutter", "onset", 3, "forward 1", 159.39, 11.25),
    ...       Instability("divergence", "onset", 0, "wing 1", 143.15, 0.0)]
    >>> critical(ev).label
    'wing 1'
    >>> critical(ev, exclude="divergence").V
    159.39
    """
    if callable(exclude):
        leave_out = exclude
    else:
        kinds = {exclude} if isinstance(exclude, str) else set(exclude)
        bad = sorted(kinds - {"flutter", "divergence"})
        if bad:
            raise v.InputError(f"exclude = {bad!r} is invalid: kinds are 'flutter' and 'divergence'")
        leave_out = lambda e: e.kind in kinds  # noqa: E731
    cands = [e for e in events if e.event in UNSTABLE_EVENTS and not leave_out(e)]
    return min(cands, key=lambda e: (e.V, e.mode)) if cands else None


def describe_critical(c: Instability | None, describe: Callable[[str], str] = str) -> str:
    """One line for the critical instability, e.g. 'flutter of forward 1 (yaw) at 159.39 m/s,
    11.247 Hz' or 'unstable from V = 150 m/s, the start of the range: divergence of wing 1'."""
    if c is None:
        return "none in the speed range"
    what = f"{c.kind} of {describe(c.label)}"
    there = at_the_event(c)
    if there:                        # the name says what the mode was at V0: say both
        what = (what[:-1] + f"; {there})" if what.endswith(")") and describe(c.label) != c.label
                else f"{what} ({there})")
    if c.event == "unstable-at-start":
        f = f" ({c.frequency_hz:.3f} Hz)" if c.kind == "flutter" else ""
        who = c.propeller_text(count=3)
        return (f"unstable from V = {c.V:g} m/s, the start of the range: {what}{f}"
                + (f"; {who}" if who else ""))
    f = f", {c.frequency_hz:.3f} Hz" if c.kind == "flutter" else ""
    who = c.propeller_text(count=3)
    return f"{what} at {c.V:.2f} m/s{f}" + (f"; {who}" if who else "")
