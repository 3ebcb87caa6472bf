"""Sensitivities of a critical point: dλ/dp, dV_crit/dp and df/dp from the eigenvectors.

At a crossing (flutter or divergence onset) the root λ of the full-order pencil F x = λ E x
(:meth:`propwhirl.model.blocks.BlockSystem.pencil`) has Re λ = 0.  With its right and left
eigenvectors x and y (yᴴ(F − λE) = 0), first-order perturbation theory gives, for any parameter
p of the matrices,

    ∂λ/∂p = yᴴ (∂F/∂p − λ ∂E/∂p) x / (yᴴ E x),

exact derivatives ∂F/∂p, ∂E/∂p from the generated parameter derivatives
(:mod:`propwhirl.model.derivatives`) and ∂/∂V by a central difference of the pencil (the
Houbolt–Reed derivatives are not polynomial in V).  Keeping Re λ = 0 along the crossing:

    dV_crit/dp = −Re(∂λ/∂p) / Re(∂λ/∂V),
    df/dp = sign(Im λ) (Im ∂λ/∂p + Im ∂λ/∂V · dV_crit/dp) / 2π     (0 for divergence),

and the normalised sensitivity (s / V_crit) dV_crit/dp says by how many percent the critical speed
moves when p moves by one percent of its scale s: the value p itself for a magnitude (a
stiffness, a mass, a frequency, a chord), a stated physical scale for a position, whose value
depends on its origin (:func:`scale_of`: the propeller radius R for the positions of a
propeller's point masses and pivots along its axis, the chord for the chordwise section
positions, which are fractions of it).

Beyond the parameters of :func:`propwhirl.model.derivatives.parameters`, the whole-distribution
factors of the studies (:mod:`propwhirl.studies.paths`' scale form ``wing.EI*``, ``wing.GJ*``,
``wing.mass_per_length*``: a factor on every element, 1 = the model as given) have
∂λ/∂(factor) = Σₑ pₑ ∂λ/∂pₑ exactly, from the per-element derivatives, and ``flight.density``
has ∂λ/∂ρ from the generated ∂/∂ρ of the aerodynamic blocks
(:func:`propwhirl.model.derivatives.density_blocks`); :func:`sensitivity_parameters` lists
them all.  All sensitivities of one point need one sparse factorisation for
the two eigenvectors, two pencil evaluations for ∂/∂V and one sparse product per parameter —
less than one analysis (measured in the tests).

A model without exact derivatives says so in its capabilities, and each of its parameter
paths (:func:`propwhirl.model.parameter_paths.parameter_paths`) carries how its derivative is
computed: a modal model's are central differences of its state matrix in the same eigenvalue
perturbation (:func:`difference_sensitivities`); a doublet-lattice wing's central differences
of its crossing's p-k root (:func:`dlm_sensitivities`: the default method converges its
crossings by the p-k), every perturbed model reading the analysis's doublet-lattice tables, so
its AICs are computed once for all the parameters.  Each :class:`Sensitivity` says which.

Only crossings have these derivatives: "unstable-at-start" and "frequency-zero" events (a branch
point, where λ is not differentiable) are refused with an error saying so.
"""
from __future__ import annotations

import difflib
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from propwhirl import validate as v
from propwhirl.analysis.pk_iteration import pk_root
from propwhirl.analysis.stability import ModelAnalysis
from propwhirl.analysis.summary import text_table
from propwhirl.engine.correction import full_order_root, real_direction
from propwhirl.model import derivatives as D
from propwhirl.model.aerodynamics.dlm import DlmTables, check_tables
from propwhirl.model.parameter_paths import (DENSITY, FACTORS, modal_parameters,  # noqa: F401
                                             parameter_paths, with_parameter)
from propwhirl.model.protocol import capabilities, refusal
from propwhirl.results import Result, SavedDict

#: relative step of the central difference ∂/∂V of the pencil
DV_STEP = 1e-5
#: relative step h/|p| of the central differences ∂A/∂p of a model without exact
#: derivatives (:func:`difference_sensitivities`; h = DIFF_STEP in p's unit for p = 0)
DIFF_STEP = 1e-4
#: how a sensitivity's ∂λ/∂p was computed (:attr:`Sensitivity.derivative`): the exact route,
#: differences of the state matrix (a modal model; a doublet-lattice wing's dense analysis)
#: or of the p-k root (a doublet-lattice wing's crossings by the p-k, the default method)
DERIVATIVES = ("exact", "central difference", "forward difference", "central difference (p-k)",
               "forward difference (p-k)")
#: the p-k roots of a doublet-lattice wing's central differences are converged to this
#: relative k (the analyses' KTOL is 1e-7: too coarse for a difference over 1e-4 |p|)
ROOT_KTOL = 1e-12
#: largest |λ_model − λ_analysis| / max(1, |λ|) of the same root: the analysis's crossing
#: refined again on the model it came from differs by at most about 1e-6 (every case, every
#: method); a model whose mount frequency differs by 1.5 % by 3e-3
SAME_ROOT = 1e-4


@dataclass(frozen=True)
class Sensitivity:
    """One parameter: path, value and unit (:func:`sensitivity_parameters`), ∂λ/∂p
    [1/s per unit], dV_crit/dp [m/s per unit], df/dp [Hz per unit] and
    normalised = (scale / V_crit) dV_crit/dp [-], ``scale`` [unit] the value itself (None)
    or, for a position, the physical scale named by ``scale_of`` (:func:`scale_of`)."""

    path: str
    value: float
    unit: str
    doc: str
    dlam_dp: complex
    dV_dp: float
    df_dp: float
    normalised: float
    scale: float | None = None
    scale_of: str = ""
    #: how ∂λ/∂p was computed: "exact" (the generated parameter derivatives) or
    #: "central difference" (of the state matrix, :func:`difference_sensitivities`)
    derivative: str = "exact"

    @property
    def per(self) -> str:
        """What the normalised sensitivity is per: "value" or the scale, e.g. "R = 0.9 m"."""
        if self.scale is None:
            return "value"
        if self.unit == "chord" and self.scale == 1.0:
            return self.scale_of
        return f"{self.scale_of} = {self.scale:.4g} {self.unit}".rstrip()

    def to_dict(self) -> dict[str, Any]:
        """Every field (∂λ/∂p as ``{"re", "im"}``, ``scale`` null for the value itself); a
        part of a sensitivities file."""
        return {"path": self.path, "value": self.value, "unit": self.unit, "doc": self.doc,
                "dlam_dp": _complex_dict(self.dlam_dp), "dV_dp": self.dV_dp,
                "df_dp": self.df_dp, "normalised": self.normalised, "scale": self.scale,
                "scale_of": self.scale_of,
                **({} if self.derivative == "exact" else {"derivative": self.derivative})}

    @classmethod
    def from_dict(cls, d: Any, where: str = "sensitivity") -> "Sensitivity":
        """The entry written by :meth:`to_dict`, checked (InputError naming the key); entries
        of version 1 files have no scale (normalised by the value)."""
        r = SavedDict(d, where, ("path", "value", "unit", "doc", "dlam_dp", "dV_dp", "df_dp",
                                 "normalised"), ("scale", "scale_of", "derivative"))
        scale = r.number("scale", optional=True) if r.has("scale") else None
        if scale is not None and scale <= 0:
            raise v.InputError(f"{r.name('scale')} = {scale!r} is invalid: must be > 0 "
                               "(or null: the value)")
        return cls(r.string("path"), r.number("value"), r.string("unit"), r.string("doc"),
                   _complex_of(r, "dlam_dp"), r.number("dV_dp"), r.number("df_dp"),
                   r.number("normalised"), scale,
                   r.string("scale_of") if r.has("scale_of") else "",
                   r.string("derivative", DERIVATIVES) if r.has("derivative") else "exact")


def _complex_dict(z: complex) -> dict[str, float]:
    return {"re": float(z.real), "im": float(z.imag)}


def _complex_of(r: SavedDict, key: str) -> complex:
    c = r.sub(key, ("re", "im"))
    return complex(c.number("re"), c.number("im"))


@dataclass(frozen=True)
class CriticalSensitivities(Result):
    """The sensitivities of one critical point (V [m/s], f [Hz], kind, event, mode label,
    λ and ∂λ/∂V there), one :class:`Sensitivity` per parameter in the model's order.

    A :class:`~propwhirl.results.Result` of kind "sensitivities" (format
    ``propwhirl.sensitivities/2``, each entry with its scale; version 1 still loads; ``propwhirl sensitivities --json`` writes it): the
    critical point's keys are those of an :class:`~propwhirl.analysis.stability.Instability`
    (V, frequency_hz, kind, event; mode is its label) and λ, ∂λ/∂V.

    Attributes
    ----------
    V : float
        Speed of the critical point [m/s].
    frequency_hz : float
        Its frequency [Hz].
    kind : {"flutter", "divergence"}
        Its kind.
    event : str
        Its event ("onset" or "recovery").
    mode : str
        The mode's label.
    eigenvalue : complex
        λ at the point [1/s].
    dlam_dV : complex
        ∂λ/∂V there [1/m].
    sensitivities : tuple of Sensitivity
        Per parameter: path, value and unit, ∂λ/∂p [1/s per unit], dV_crit/dp [m/s per unit],
        df/dp [Hz per unit], normalised (scale / V_crit) dV_crit/dp [-]; :meth:`ranked` sorts
        them by |normalised|.

    Examples
    --------
    The wingtip model's first flutter (§10.1) against the pitch-mount frequency and the whole
    torsional rigidity (the scale form ``wing.GJ*``): 1 % more GJ raises it by 0.30 %.

    >>> from propwhirl.analysis import analyse, critical_sensitivities, first_of_kind
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> m = wingtip_propeller_wing()
    >>> a = analyse(m)
    >>> cs = critical_sensitivities(m, a, first_of_kind(a, "flutter"),
    ...                             params=["propellers[0].propeller.f_theta", "wing.GJ*"])
    >>> cs.kind, cs.mode, round(cs.V, 2), round(cs.frequency_hz, 2)
    ('flutter', 'forward 1', 159.39, 11.25)
    >>> [(s.path, round(s.normalised, 2)) for s in cs.ranked()]
    [('wing.GJ*', 0.3), ('propellers[0].propeller.f_theta', 0.16)]
    """

    V: float
    frequency_hz: float
    kind: str
    event: str
    mode: str
    eigenvalue: complex
    dlam_dV: complex
    sensitivities: tuple[Sensitivity, ...]

    KIND: ClassVar[str] = "sensitivities"
    VERSION: ClassVar[int] = 2
    READABLE: ClassVar[tuple[int, ...]] = (1, 2)
    WHAT: ClassVar[str] = "sensitivities file"

    def ranked(self, top: int | None = None) -> list[Sensitivity]:
        """By decreasing |normalised| (the first ``top``)."""
        out = sorted(self.sensitivities, key=lambda s: -abs(s.normalised))
        return out if top is None else out[:top]

    def to_dict(self, top: int | None = None) -> dict[str, Any]:
        """``{"format", "critical": {"V", "frequency_hz", "kind", "event", "mode",
        "eigenvalue", "dlam_dV"}, "sensitivities": [...]}``, ranked (the first `top`)."""
        return {"format": self.format_name(), **self.encode(top)}

    def encode(self, top: int | None = None) -> dict[str, Any]:
        return {"critical": {"V": self.V, "frequency_hz": self.frequency_hz, "kind": self.kind,
                             "event": self.event, "mode": self.mode,
                             "eigenvalue": _complex_dict(self.eigenvalue),
                             "dlam_dV": _complex_dict(self.dlam_dV)},
                "sensitivities": [s.to_dict() for s in self.ranked(top)]}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int,
               where: str = "") -> "CriticalSensitivities":
        r = SavedDict(d, where, ("critical", "sensitivities"))
        c = r.sub("critical", ("V", "frequency_hz", "kind", "event", "mode", "eigenvalue",
                               "dlam_dV"))
        return cls(c.number("V"), c.number("frequency_hz"),
                   c.string("kind", ("flutter", "divergence")), c.string("event"),
                   c.string("mode"), _complex_of(c, "eigenvalue"), _complex_of(c, "dlam_dV"),
                   tuple(Sensitivity.from_dict(x, w) for w, x in r.items("sensitivities")))

    def save(self, path: str | Path, top: int | None = None) -> Path:
        """Write the sensitivities (the first `top` ranked) as JSON, atomically
        (:meth:`Result.save`)."""
        if top is None:
            return super().save(path)
        return replace(self, sensitivities=tuple(self.ranked(top))).save(path)

    def format(self, top: int | None = 10) -> str:
        """A text table of the ranked sensitivities."""
        head = (f"{self.kind} {self.event} of {self.mode} at V = {self.V:.2f} m/s, "
                f"f = {self.frequency_hz:.3f} Hz: sensitivities (normalised: % of V_crit per "
                "% of the parameter's value, or of the scale shown for a position)")
        shown = self.ranked(top)
        rows = [[s.path, f"{s.value:.6g}", s.unit, f"{s.dV_dp:.6g}", f"{s.normalised:+.4f}",
                 s.per] for s in shown]
        heads, align = ["parameter", "value", "unit", "dV/dp [m/s per unit]", "normalised",
                        "per"], "lrlrrl"
        routes = {s.derivative for s in shown}
        if routes - {"exact"}:                             # say which route gave each
            rows = [r + [s.derivative] for r, s in zip(rows, shown)]
            heads, align = heads + ["derivative"], align + "l"
            if routes & {"central difference", "forward difference"}:
                head += ("\nderivative: 'central difference' = ∂A/∂p by a central difference "
                         f"of the state matrix (relative step {DIFF_STEP:g}) in the exact "
                         "eigenvalue perturbation yᴴ ∂A/∂p x / yᴴx")
            if routes & {"central difference (p-k)", "forward difference (p-k)"}:
                head += ("\nderivative: 'central difference (p-k)' = ∂λ/∂p = (λ(p + h) − "
                         f"λ(p − h)) / 2h of the crossing's p-k root (h = {DIFF_STEP:g} |p|, "
                         "the doublet-lattice AICs computed once for all)")
            if "exact" in routes:
                head += "; 'exact' = generated derivatives"
        return head + "\n" + text_table(rows, heads, align)


def exact(model) -> bool:
    """Whether ``model``'s sensitivities are not central differences (the model contract:
    :attr:`~propwhirl.model.protocol.Capabilities.derivatives` is not "central difference":
    exact, or none — refused where they are asked for); central differences:
    :func:`difference_sensitivities`."""
    return capabilities(model).derivatives != "central difference"


def _check_pair(model, analysis) -> None:
    """Refuse, before any matrix is built, a model without sensitivities (exact ones need the
    full-order pencil: only a PropellerWing has one; a model the contract gives central
    differences instead is let through) and an analysis that is not a ModelAnalysis of a model
    of this size."""
    if exact(model):                  # the exact route's own checks name the values
        if not hasattr(model, "second_order_blocks"):
            raise v.InputError(f"model = {type(model).__name__}: sensitivities need the "
                               "full-order pencil of a wing model (PropellerWing); an "
                               "IsolatedPropeller has none")
        D.check_model(model)          # e.g. a doublet-lattice wing: no exact derivatives
    why = refusal(model, "sensitivity")
    if why is not None:
        raise v.InputError(f"model = {type(model).__name__}: no sensitivities: {why}")
    if not isinstance(analysis, ModelAnalysis):
        raise v.InputError(f"analysis = {v.short_repr(analysis)} is invalid: must be the "
                           "ModelAnalysis of the model (propwhirl.analysis.analyse(model))")
    name = getattr(model, "name", None)
    if name is not None and analysis.model_name != name:
        raise v.InputError(f"the analysis is of {analysis.model_name!r}, the model is {name!r}: "
                           "give the analysis of this model")
    n = int(model.dof_map().n_states)
    points = analysis.criticals.points if analysis.criticals is not None else ()
    sizes = {np.asarray(p.eigenvector).size for p in points}
    if sizes and sizes != {n}:
        raise v.InputError(f"the analysis is not of this model: its eigenvectors have "
                           f"{', '.join(map(str, sorted(sizes)))} states, the model {n}")


def _left_vector(F, E, lam: complex, y0: np.ndarray) -> np.ndarray:
    """The left eigenvector y of (F, E) at λ: (F − λE)ᴴ y = 0, by inverse iteration on the
    conjugate-transposed factorisation of a slightly shifted F − λE."""
    shift = lam + 1e-9 * max(abs(lam), 1.0)
    dtype = complex if np.iscomplexobj(y0) or np.iscomplexobj(shift) else float
    lu = spla.splu(sp.csc_matrix(F - shift * E, dtype=dtype))
    y = np.asarray(y0, dtype=dtype)
    for _ in range(6):
        y = lu.solve(y, trans="H")
        y = y / np.linalg.norm(y)
    return y


def sensitivity_parameters(model) -> tuple[D.Parameter, ...]:
    """Every parameter :func:`critical_sensitivities` covers for ``model``, each with how its
    derivative is computed: the model contract's
    :func:`~propwhirl.model.parameter_paths.parameter_paths` (a strip wing's exact parameters —
    those of :func:`propwhirl.model.derivatives.parameters`, the whole-distribution factors
    :data:`FACTORS` and ``flight.density`` —, a doublet-lattice wing's and a modal model's by
    central differences, :mod:`propwhirl.model.parameter_paths`)."""
    return parameter_paths(model)


def scale_of(model, p: D.Parameter) -> tuple[float | None, str]:
    """The scale [p's unit] of the normalised sensitivity of ``p`` and what it is: (None, "")
    for a magnitude (normalised by its own value); for a position, whose value depends on its
    origin, a physical scale — the propeller's radius R for its point masses' and pivots'
    positions along its axis [m], the chord for the chordwise section positions (elastic axis,
    centre of gravity, aerodynamic centre, in chords: scale 1)."""
    if p.kind == "propeller" and (p.name.startswith("x:") or p.name.startswith("pivot_")):
        return float(model.propellers[p.index].propeller.radius), "propeller radius R"
    if p.kind == "section" and p.name in ("elastic_axis", "centre_of_gravity",
                                          "aerodynamic_centre"):
        return 1.0, "the chord"
    return None, ""


def _resolve(model, params) -> list[D.Parameter]:
    """The parameters named by ``params`` (paths or Parameters; None: all), checked before any
    work: an unknown path is one InputError saying where to find the valid ones."""
    known = {p.path: p for p in sensitivity_parameters(model)}
    if params is None:
        return list(known.values())
    if isinstance(params, (str, bytes)):
        params = [params]
    out, seen = [], set()
    for q in params:
        path = q.path if isinstance(q, D.Parameter) else q
        if not isinstance(path, str) or path not in known:
            near = difflib.get_close_matches(str(path), list(known), n=3)
            hint = f" (did you mean {', '.join(map(repr, near))}?)" if near else ""
            raise v.InputError(
                f"parameter = {v.short_repr(path)} is invalid: not a parameter with derivatives "
                f"of this model{hint}; `propwhirl sensitivity MODEL --list` or "
                "propwhirl.analysis.sensitivity.sensitivity_parameters(model) lists them")
        if path not in seen:
            seen.add(path)
            out.append(known[path])
    return out


def critical_sensitivities(model, analysis, event=None, *, params=None,
                           dlm_tables: DlmTables | None = None) -> CriticalSensitivities:
    """The sensitivities of ``event`` (default ``analysis.critical``) of ``analysis`` (an
    analysis of ``model``, a PropellerWing) for ``params`` (paths of
    :func:`sensitivity_parameters`, checked before any work; default all).

    Exact derivatives of the crossing's eigenvalue (∂λ/∂p from the generated matrices'
    parameter derivatives), dV_crit/dp = −Re(∂λ/∂p) / Re(∂λ/∂V).

    Parameters
    ----------
    model : PropellerWing
        The analysed model.
    analysis : ModelAnalysis
        A fresh analysis of `model` (a re-read one has no eigenvectors of its crossings).
    event : Instability, optional
        An onset or recovery of `analysis` (default its critical instability).
    params : sequence of str, optional
        Parameter paths (``"propellers[0].propeller.f_theta"``, ``"wing.GJ*"``, ...,
        :func:`sensitivity_parameters`); default all.
    dlm_tables : DlmTables, optional
        A doublet-lattice wing's tables (the analysis's: ``analyse(model, dlm_tables=...)``),
        which every perturbed model reads (its AICs computed once for all parameters); None:
        new ones.

    Returns
    -------
    CriticalSensitivities
        V [m/s], f [Hz], λ [1/s], ∂λ/∂V [1/m] of the point and, per parameter, ∂λ/∂p,
        dV/dp [m/s per unit], df/dp [Hz per unit] and the normalised sensitivity [-].

    Raises
    ------
    InputError
        An unknown parameter path, no instability, or an event that is not a crossing.

    Examples
    --------
    The forward-whirl flutter of the wingtip model (§10.1) rises by 3.74 m/s per Hz of the
    pitch-mount frequency: +0.164 % of V_crit per % of f_θ.

    >>> from propwhirl.analysis import analyse, critical_sensitivities
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> m = wingtip_propeller_wing()
    >>> a = analyse(m)
    >>> flutter = next(e for e in a.events if e.kind == "flutter")
    >>> cs = critical_sensitivities(m, a, flutter, params=["propellers[0].propeller.f_theta"])
    >>> s = cs.sensitivities[0]
    >>> round(cs.V, 2), round(s.dV_dp, 2), round(s.normalised, 3)
    (159.39, 3.74, 0.164)
    """
    _check_pair(model, analysis)
    pars = _resolve(model, params)
    e = _crossing(analysis, event)
    point = _point(analysis, e)
    if not exact(model):
        if capabilities(model).aerodynamics == "doublet lattice":
            return dlm_sensitivities(model, e, point, pars, check_tables(dlm_tables))
        return difference_sensitivities(model, e, point, pars)
    V = float(point.V)
    F, E = model.second_order_blocks(np.array([V])).pencil(0)
    real = e.kind == "divergence"
    x0 = real_direction(point.eigenvector) if real else np.asarray(point.eigenvector, dtype=complex)
    got = full_order_root(F, E, point.eigenvalue.real if real else point.eigenvalue, x0)
    if got is None:
        raise v.InputError(f"the root of {e.label} at {V:.2f} m/s could not be converged on the "
                           "full-order model")
    lam, x = got
    if abs(lam - point.eigenvalue) > SAME_ROOT * max(1.0, abs(lam)):
        raise v.InputError(
            f"the analysis is not of this model: at V = {V:.2f} m/s its {e.label} root is "
            f"{point.eigenvalue:.6g} 1/s, the model's nearest root {lam:.6g} 1/s (analyse the "
            "model itself, then ask for its sensitivities)")
    y = _left_vector(F, E, lam, x)
    denom = np.vdot(y, E @ x)
    h = DV_STEP * V
    (Fp, Ep), (Fm, Em) = (model.second_order_blocks(np.array([V + s])).pencil(0)
                          for s in (h, -h))
    dlam_dV = np.vdot(y, ((Fp - Fm) - lam * (Ep - Em)) @ x) / (2 * h * denom)

    def dlam_of(blocks) -> complex:
        dF, dE = D.pencil_derivative(blocks, 0)
        return complex(np.vdot(y, (dF - lam * dE) @ x) / denom)

    # the model's own parameters, those the factors sum over included (each computed once)
    base = {p.path: p for p in D.parameters(model)}
    need = {p.path: p for p in pars if p.path in base}
    for p in pars:
        if p.kind == "factor":
            need.update((q.path, q) for q in base.values()
                        if q.kind == "element" and q.name == p.name)
    blocks = D.derivative_blocks(model, np.array([V]), list(need.values()))
    dlams = {path: dlam_of(b) for path, b in blocks.items()}
    out = []
    sgn = 1.0 if np.imag(lam) >= 0 else -1.0
    for p in pars:
        if p.kind == "factor":          # d/dc of every p_e → c p_e at c = 1: Σ p_e ∂λ/∂p_e
            dlam = complex(sum(q.value * dlams[q.path] for q in need.values()
                               if q.kind == "element" and q.name == p.name))
        elif p.kind == "flight":
            dlam = dlam_of(D.density_blocks(model, np.array([V])))
        else:
            dlam = dlams[p.path]
        dV = -dlam.real / dlam_dV.real
        df = 0.0 if real else sgn * (dlam.imag + dlam_dV.imag * dV) / (2 * np.pi)
        scale, what = scale_of(model, p)
        out.append(Sensitivity(p.path, p.value, p.unit, p.doc, dlam, float(dV), float(df),
                               float((p.value if scale is None else scale) / V * dV),
                               scale, what))
    return CriticalSensitivities(V, abs(float(np.imag(lam))) / (2 * np.pi), e.kind, e.event,
                                 e.label, complex(lam), complex(dlam_dV), tuple(out))


def _crossing(analysis, event):
    """``event`` (default the analysis's critical one), checked to be a crossing."""
    e = analysis.critical if event is None else event
    if e is None:
        raise v.InputError("no instability in the analysed range: no critical speed to "
                           "differentiate")
    if e.event not in ("onset", "recovery"):
        raise v.InputError(f"the {e.event} event of {e.label} at {e.V:.2f} m/s is not a crossing "
                           "of the imaginary axis: its speed has no derivative (choose an onset)")
    return e


def _point(analysis, e):
    """The refined crossing of event ``e`` (its eigenvalue and eigenvector)."""
    point = next((p for p in analysis.criticals.points
                  if p.mode == e.mode and abs(p.V - e.V) <= 1e-9 * max(1.0, abs(e.V))), None)
    if point is None:
        raise v.InputError("the analysis has no refined crossing for this event (re-read "
                           "analyses have no eigenvectors of their crossings)")
    return point


# ------------------------------------------------------------- without exact derivatives
def difference_parameters(model) -> tuple[D.Parameter, ...]:
    """The parameters of a modal model (:class:`~propwhirl.model.modal.ModalPropellerWing`)
    whose sensitivities :func:`difference_sensitivities` gives: its ``parameter_paths()``,
    :func:`propwhirl.model.parameter_paths.modal_parameters` (kept here by its former name)."""
    return modal_parameters(model)


def with_difference_value(model, p: D.Parameter, value: float):
    """``model`` with parameter ``p`` set to ``value`` [its unit]:
    :func:`propwhirl.model.parameter_paths.with_parameter` (kept here by its former name)."""
    return with_parameter(model, p, value)


def _eigenpair(A: np.ndarray, lam0: complex) -> tuple[complex, np.ndarray, np.ndarray]:
    """(λ, x, y): the eigenvalue of A nearest ``lam0`` and its right and left eigenvectors
    (yᴴ A = λ yᴴ)."""
    lam, Y, X = scipy.linalg.eig(A, left=True, right=True)
    i = int(np.argmin(np.abs(lam - lam0)))
    return complex(lam[i]), X[:, i], Y[:, i]


def difference_sensitivities(model, e, point, pars, state_matrix=None) -> CriticalSensitivities:
    """The sensitivities of crossing ``e`` (its refined ``point``) of a model without exact
    derivatives, for the parameters ``pars`` (:func:`difference_parameters`).

    The same first-order perturbation as the exact route, on the state matrix A(V) of the
    model's first-order state: ∂λ/∂p = yᴴ (∂A/∂p) x / (yᴴ x), with x, y the right and left
    eigenvectors of A at the crossing and ∂A/∂p the central difference
    (A(p + h) − A(p − h)) / 2h, h = :data:`DIFF_STEP` |p| (DIFF_STEP in p's unit for p = 0);
    where p − h is outside the parameter's range (a damping ratio of 0) the second-order
    forward difference (−3 A(p) + 4 A(p + h) − A(p + 2h)) / 2h.  Truncation O(h²): the
    relative error of ∂λ/∂p is ~1e-8, far below the crossings' accuracy.  ∂λ/∂V likewise
    (step :data:`DV_STEP` V).  Each :class:`Sensitivity` says which difference it is.
    ``state_matrix(model, V)``: A of a model at the speeds V (default ``model.state_matrix``;
    a doublet-lattice wing's from its tables)."""
    if state_matrix is None:
        def state_matrix(m, speeds):
            return m.state_matrix(speeds)
    V = float(point.V)
    A0 = state_matrix(model, np.array([V]))[0]
    lam, x, y = _eigenpair(A0, complex(point.eigenvalue))
    if abs(lam - point.eigenvalue) > SAME_ROOT * max(1.0, abs(lam)):
        raise v.InputError(
            f"the analysis is not of this model: at V = {V:.2f} m/s its {e.label} root is "
            f"{point.eigenvalue:.6g} 1/s, the model's nearest root {lam:.6g} 1/s (analyse the "
            "model itself, then ask for its sensitivities)")
    denom = np.vdot(y, x)

    def dlam(dA: np.ndarray) -> complex:
        return complex(np.vdot(y, dA @ x) / denom)

    hV = DV_STEP * V
    Ap, Am = state_matrix(model, np.array([V + hV, V - hV]))
    dlam_dV = dlam((Ap - Am) / (2 * hV))
    real = e.kind == "divergence"
    sgn = 1.0 if np.imag(lam) >= 0 else -1.0
    out = []
    for p in pars:
        h = DIFF_STEP * (abs(p.value) if p.value != 0 else 1.0)
        up = state_matrix(with_parameter(model, p, p.value + h), np.array([V]))[0]
        try:
            down = state_matrix(with_parameter(model, p, p.value - h), np.array([V]))[0]
            dA, how = (up - down) / (2 * h), "central difference"
        except v.InputError:              # p − h outside its range: one-sided, second order
            up2 = state_matrix(with_parameter(model, p, p.value + 2 * h), np.array([V]))[0]
            dA, how = (-3 * A0 + 4 * up - up2) / (2 * h), "forward difference"
        out.append(_entry(model, p, dlam(dA), dlam_dV, V, real, sgn, how))
    return CriticalSensitivities(V, abs(float(np.imag(lam))) / (2 * np.pi), e.kind, e.event,
                                 e.label, lam, dlam_dV, tuple(out))


def _entry(model, p: D.Parameter, d: complex, dlam_dV: complex, V: float, real: bool,
           sgn: float, how: str) -> Sensitivity:
    """The :class:`Sensitivity` of ``p`` from its ∂λ/∂p ``d`` and the point's ∂λ/∂V."""
    dV = -d.real / dlam_dV.real
    df = 0.0 if real else sgn * (d.imag + dlam_dV.imag * dV) / (2 * np.pi)
    scale, what = scale_of(model, p)
    return Sensitivity(p.path, p.value, p.unit, p.doc, complex(d), float(dV), float(df),
                       float((p.value if scale is None else scale) / V * dV), scale, what, how)


def dlm_sensitivities(model, e, point, pars, tables: DlmTables) -> CriticalSensitivities:
    """The sensitivities of crossing ``e`` (its refined ``point``) of a doublet-lattice wing,
    for ``pars`` (:func:`propwhirl.model.parameter_paths.dlm_parameters`), by central
    differences, every perturbed model reading ``tables`` (the same panels: the AICs computed
    once for all).

    The default method converges a doublet-lattice wing's crossings by the p-k
    (:mod:`propwhirl.analysis.modal_dlm`): the point's root is then the p-k root λ(V, p) at
    V, whose derivatives are central differences of the root converged again (to
    :data:`ROOT_KTOL`) at p ± h, h = :data:`DIFF_STEP` |p| (a parameter at the lower end of
    its range: the second-order forward difference), and at V ± :data:`DV_STEP` V;
    dV_crit/dp = −Re(∂λ/∂p) / Re(∂λ/∂V) as on the exact route.  A dense analysis's point is
    a root of the Roger state space: :func:`difference_sensitivities` on its state matrix,
    read from the same tables."""
    V = float(point.V)
    lam0 = complex(point.eigenvalue)

    def root(m, speed: float, start: complex) -> complex:
        return complex(pk_root(m, speed, start, ktol=ROOT_KTOL, tables=tables,
                               own_mach=True)[0])

    try:
        lam = root(model, V, lam0)
    except RuntimeError:
        lam = None
    if lam is None or abs(lam - lam0) > SAME_ROOT * max(1.0, abs(lam)):
        def roger(m, speeds):                  # the dense analysis: its Roger state space
            return m.assembly(dlm_tables=tables).state_matrix(speeds)
        return difference_sensitivities(model, e, point, pars, roger)
    real = e.kind == "divergence"
    if real:
        lam = complex(lam.real, 0.0)
    hV = DV_STEP * V
    dlam_dV = (root(model, V + hV, lam) - root(model, V - hV, lam)) / (2 * hV)
    sgn = 1.0 if np.imag(lam) >= 0 else -1.0
    out = []
    for p in pars:
        h = DIFF_STEP * (abs(p.value) if p.value != 0 else 1.0)
        up = root(with_parameter(model, p, p.value + h), V, lam)
        try:
            down = root(with_parameter(model, p, p.value - h), V, lam)
            d, how = (up - down) / (2 * h), "central difference (p-k)"
        except v.InputError:              # p − h outside its range: one-sided, second order
            up2 = root(with_parameter(model, p, p.value + 2 * h), V, lam)
            d, how = (-3 * lam + 4 * up - up2) / (2 * h), "forward difference (p-k)"
        out.append(_entry(model, p, d, dlam_dV, V, real, sgn, how))
    return CriticalSensitivities(V, abs(float(np.imag(lam))) / (2 * np.pi), e.kind, e.event,
                                 e.label, lam, complex(dlam_dV), tuple(out))
