"""Stability analysis of a model: labelled V-g-f sweep, instabilities, the critical one.

:func:`analyse` runs the engine of :mod:`propwhirl.engine` on a model's state matrix
(PropellerWing, IsolatedPropeller or TypicalSection) and names the tracked modes the way the
thesis does (chapters 9–11):

* propeller–wing models: each aeroelastic mode is matched at the first speed, by an optimal
  one-to-one MAC assignment on the displacement part, to the in-vacuo modes named by
  :func:`propwhirl.analysis.vibration.label_modes` ("wing n", "backward k", "forward k"); the real
  aerodynamic lag roots are "lag k";
* the isolated propeller: "backward" and "forward" whirl from the sense of the θ–ψ orbit at the
  first speed (or, without rotation, by frequency);
* the typical section: "plunge" and "pitch" by their displacement content.

A mode keeps its name along the sweep (it is a tracked branch).  At each instability the whirl
sense of the propeller motion is also reported, because strongly coupled modes may change it.

Instabilities are the onsets of the engine's crossings (flutter: a complex pair; divergence: a
real root through zero) plus *frequency-zero* events: an already unstable oscillatory mode whose
frequency falls to zero (the pair splits into real roots) — the thesis's "whirl divergence"
(Table 10.4).  Results are saved and re-read with :meth:`ModelAnalysis.save` / :func:`load`.
"""
from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.analysis.whirl import content, whirl_sense
from propwhirl.engine import XTOL, Criticals, Sweep, TrackingOptions, frequency_zero_points, mac
from propwhirl.engine import analyse as engine_analyse
from propwhirl import validate as v

#: Default airspeed grid of the thesis's analyses (0–350 m/s; the engine refines it) [m/s]
DEFAULT_SPEEDS = np.arange(1.0, 351.0, 10.0)


@dataclass(frozen=True)
class Instability:
    """One instability event of a tracked mode.

    kind:   "flutter" (oscillatory) or "divergence" (non-oscillatory)
    event:  "onset" (Re λ becomes positive), "recovery" (becomes negative again; hump modes),
            "frequency-zero" (an unstable pair turns into real roots: divergence of that mode)
    mode, label: tracked mode id and its name (e.g. "forward 1", "wing 2", "lag 1")
    V [m/s], frequency_hz [Hz] at the event; whirl: "forward"/"backward"/"planar" sense of the
    propeller θ–ψ orbit (None without flexible propellers); benignity [m/s] (eq. 5.13) at
    flutter onsets.
    """

    kind: str
    event: str
    mode: int
    label: str
    V: float
    frequency_hz: float
    whirl: str | None = None
    benignity: float | None = None


@dataclass
class ModelAnalysis:
    """A labelled sweep and its instabilities (sorted by speed)."""

    model_name: str
    sweep: Sweep
    events: tuple[Instability, ...]
    criticals: Criticals | None = field(default=None, repr=False)
    #: mode label -> share of its kinetic energy at the first speed per group of degrees of
    #: freedom ("bending": h, φ; "torsion": α; "pitch", "yaw": propeller θ, ψ; "plunge")
    content: dict[str, dict[str, float]] = field(default_factory=dict)

    def describe(self, label: str) -> str:
        """'label (dominant content)', e.g. 'wing 2 (torsion)'."""
        c = self.content.get(label)
        if not c:
            return label
        return f"{label} ({max(c, key=lambda g: c[g])})"

    @property
    def onsets(self) -> list[Instability]:
        """Events that make the system (more) unstable: onsets and frequency-zero events."""
        return [e for e in self.events if e.event in ("onset", "frequency-zero")]

    @property
    def critical(self) -> Instability | None:
        """The instability at the lowest speed."""
        ons = [e for e in self.events if e.event == "onset"]
        return min(ons, key=lambda e: e.V) if ons else None

    def first(self, label: str, kind: str | None = None, event: str = "onset") -> Instability | None:
        """The lowest-speed event of the mode named `label` (optionally of one kind)."""
        hits = [e for e in self.events
                if e.label == label and e.event == event and (kind is None or e.kind == kind)]
        return min(hits, key=lambda e: e.V) if hits else None

    def summary(self) -> str:
        lines = [f"{self.model_name}: instabilities between {self.sweep.V[0]:g} and {self.sweep.V[-1]:g} m/s"]
        lines.append(f"  {'type':10s} {'event':15s} {'mode (content at V0)':24s} {'whirl':9s} {'V [m/s]':>9s} {'f [Hz]':>8s}")
        for e in self.events:
            lines.append(
                f"  {e.kind:10s} {e.event:15s} {self.describe(e.label):24s} {e.whirl or '-':9s} {e.V:9.2f} {e.frequency_hz:8.3f}"
            )
        c = self.critical
        lines.append("  critical: " + (f"{c.kind} of {self.describe(c.label)} at {c.V:.2f} m/s, {c.frequency_hz:.3f} Hz"
                                       if c else "none in the speed range"))
        return "\n".join(lines)

    def to_dict(self, include_eigenvectors: bool = False) -> dict[str, Any]:
        return {
            "model_name": self.model_name,
            "events": [asdict(e) for e in self.events],
            "content": self.content,
            "sweep": self.sweep.to_dict(include_eigenvectors=include_eigenvectors),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "ModelAnalysis":
        return cls(d["model_name"], Sweep.from_dict(d["sweep"]),
                   tuple(Instability(**e) for e in d["events"]), content=d.get("content", {}))

    def save(self, path: str | Path, include_eigenvectors: bool = False) -> None:
        """Write the analysis as JSON (V-g-f table, labels, instabilities)."""
        Path(path).write_text(json.dumps(self.to_dict(include_eigenvectors)))


def load(path: str | Path) -> ModelAnalysis:
    """Re-read an analysis written by :meth:`ModelAnalysis.save`."""
    return ModelAnalysis.from_dict(json.loads(Path(path).read_text()))


# ----------------------------------------------------------------------------- labels
def _propeller_indices(labels: tuple[str, ...]) -> list[tuple[int, int]]:
    """(θ, ψ) state indices of each flexible propeller."""
    out = []
    j = 0
    while f"propeller {j} theta" in labels:
        out.append((labels.index(f"propeller {j} theta"), labels.index(f"propeller {j} psi")))
        j += 1
    return out


def _mode_names(model, sw: Sweep) -> list[str]:
    """Names of the tracked modes, decided at the first speed (see the module docstring)."""
    n = sw.n_modes
    lam0 = sw.eigenvalues[0]
    X0 = sw.eigenvectors[0]
    disp = sw.displacement
    names = [f"mode {k}" for k in range(n)]
    phys = sw.physical[0]
    osc = [k for k in range(n) if phys[k] and abs(lam0[k].imag) > 1e-9 * max(1.0, abs(lam0[k]))]
    real = [k for k in range(n) if phys[k] and k not in osc]
    for i, k in enumerate(sorted(real, key=lambda k: -lam0[k].real)):
        names[k] = f"lag {i + 1}"
    kind = type(model).__name__
    if kind == "PropellerWing":
        from propwhirl.analysis.vibration import label_modes, model_modes

        modes, _ = model_modes(model)
        ref = [lab for lab, _ in label_modes(model)]
        M = mac(X0[disp][:, osc][:, :, None], modes.shapes[:, None, :].astype(complex))
        rows, cols = linear_sum_assignment(-M)
        for r, c in zip(rows, cols):
            names[osc[r]] = ref[c]
    elif kind == "IsolatedPropeller":
        order = sorted(osc, key=lambda k: abs(lam0[k].imag))
        if model.rotating and len(order) == 2:
            th, ps = 0, 1
            for k in order:
                names[k] = whirl_sense(X0[th, k], X0[ps, k], model.propeller.rotation, lam0[k])
        else:
            for k, nm in zip(order, ("pitch", "yaw")):
                names[k] = nm
    elif kind == "TypicalSection":
        for k in osc:
            c = content(X0[:2, k], {"plunge": [0], "pitch": [1]})
            names[k] = max(c, key=lambda g: c[g])
    for k in range(n):  # hidden conjugate partners: "<name>'"
        if not phys[k] and sw.partner[k] >= 0:
            names[k] = f"{names[sw.partner[k]]}'"
    return names


def _rotations(model) -> list[int]:
    """Sense of rotation (+1 counter-clockwise from the front) of each flexible propeller."""
    if hasattr(model, "flexible"):
        return [model.propellers[j].propeller.rotation for j in model.flexible]
    if hasattr(model, "propeller"):
        return [model.propeller.rotation]
    return []


def _whirl(model, x: np.ndarray, lam: complex, labels: tuple[str, ...]) -> str | None:
    """Whirl sense of the propeller with the largest θ–ψ motion in full-state vector x,
    relative to that propeller's own sense of rotation."""
    props = _propeller_indices(labels)
    if not props or abs(lam.imag) == 0 or not getattr(model, "rotating", True):
        return None
    j = max(range(len(props)), key=lambda i: abs(x[props[i][0]]) ** 2 + abs(x[props[i][1]]) ** 2)
    th, ps = props[j]
    return whirl_sense(x[th], x[ps], _rotations(model)[j], lam)


CONTENT_GROUPS = {
    "bending": lambda lab: lab.endswith(" h") or lab.endswith(" phi"),
    "torsion": lambda lab: lab.endswith(" alpha") and lab.startswith("node"),
    "pitch": lambda lab: lab.endswith(" theta"),
    "yaw": lambda lab: lab.endswith(" psi"),
    "plunge": lambda lab: lab == "h",
    "pitch ": lambda lab: lab == "alpha",  # typical section pitch (named apart from propeller pitch)
}


def _content(model, sw: Sweep, names: list[str]) -> dict[str, dict[str, float]]:
    """Kinetic-energy shares of each physical oscillatory mode at the first speed."""
    from propwhirl.analysis.vibration import energy_fractions

    V0 = np.array([float(sw.V[0])])
    quiet = model.with_(**{k: False for k in ("wing_aero", "propeller_aero") if hasattr(model, k)}) \
        if hasattr(model, "with_") else model
    s = quiet.second_order(V0)
    M = s.S1[0]
    X = sw.eigenvectors[0][sw.displacement]
    out = {}
    for k in range(sw.n_modes):
        lam = sw.eigenvalues[0, k]
        if not sw.physical[0, k] or abs(lam.imag) == 0:
            continue
        frac = energy_fractions(X[:, [k]], M, s.q_labels, CONTENT_GROUPS)
        out[names[k]] = {g.strip(): round(float(f[0]), 4) for g, f in frac.items() if abs(f[0]) > 1e-3}
    return out


# ----------------------------------------------------------------------------- analyse
def analyse(model, speeds=None, *, xtol: float = XTOL, vgf: bool = False,
            options: TrackingOptions | None = None) -> ModelAnalysis:
    """Every instability of `model` over `speeds` [m/s], with tracked, named modes.

    `speeds` is the grid [m/s] (default: the model's FlightCondition.speed_range, 1–350 m/s
    every 10 m/s — the thesis's 0–350 m/s); crossings are located to `xtol` [m/s].  To find
    the critical speeds the engine needs only a subset of the grid (it starts ≈ 50 m/s apart
    and adds speeds where tracking or a possible crossing asks for them), so by default
    `.sweep` is coarse; `vgf=True` evaluates every grid speed (for V-g-f plots and tables).
    """
    if speeds is None:
        flight = getattr(model, "flight", None)
        grid = flight.speeds() if flight is not None else np.append(DEFAULT_SPEEDS, 350.0)
    else:
        grid = np.asarray(speeds, dtype=float)
    v.positive("xtol", xtol, "m/s")
    s = model.second_order(np.array([float(grid[0])]))
    labels = s.labels
    an = engine_analyse(model.state_matrix, grid, n_dof=s.n_dof, state_labels=labels,
                    options=options, xtol=xtol, **({"initial_step": None} if vgf else {}))
    sw = an.sweep
    names = _mode_names(model, sw)
    sw = sw.relabel(names)
    events = []
    for p in an.criticals.points:
        whirl = _whirl(model, p.eigenvector, p.eigenvalue, labels) if p.kind == "flutter" else None
        events.append(Instability(p.kind, p.direction, p.mode, names[p.mode], float(p.V),
                                  float(p.frequency_hz), whirl,
                                  None if p.benignity is None else float(p.benignity)))
    for k in an.criticals.unstable_at_start:
        lam0 = sw.eigenvalues[0, k]
        kind = "flutter" if abs(lam0.imag) > 0 else "divergence"
        events.append(Instability(kind, "unstable-at-start", int(k), names[k], float(sw.V[0]),
                                  float(abs(lam0.imag) / (2 * np.pi))))
    events += [Instability("divergence", "frequency-zero", p.mode, names[p.mode], p.V, 0.0)
               for p in frequency_zero_points(sw, model.state_matrix, xtol=xtol)]
    events.sort(key=lambda e: (e.V, e.mode))
    return ModelAnalysis(getattr(model, "name", type(model).__name__), sw, tuple(events), an.criticals,
                         _content(model, sw, names))


def speed_and_frequency(event: Instability | None) -> tuple[float, float]:
    """(V [m/s], f [Hz]) of an event; NaN (reported as not computed) when there is none."""
    if event is None:
        return float("nan"), float("nan")
    return event.V, event.frequency_hz


def first_of_kind(a: ModelAnalysis, kind: str, event: str = "onset") -> Instability | None:
    """The lowest-speed event of a kind ("flutter" or "divergence"), whatever the mode."""
    hits = [e for e in a.events if e.kind == kind and e.event == event]
    return min(hits, key=lambda e: e.V) if hits else None
