"""Gradient-based design: the critical speed and its exact gradient as a function of chosen
parameters, a minimum-stiffness clearance optimisation, and an OpenMDAO component.

:class:`CriticalSpeed` evaluates, for values x of parameter paths (those of
:func:`propwhirl.model.derivatives.parameters`), the critical speed V_crit(x) [m/s] of the model
(the one definition, with the thesis's exclusions as options: :mod:`propwhirl.studies.critical`)
and its gradient from :func:`propwhirl.analysis.sensitivity.critical_sensitivities` — one
analysis per point, the gradient included.  It counts the analyses it ran.

:func:`minimum_mount_stiffness` is the optimisation of issue 13.4: the smallest pitch and yaw
mount stiffnesses (Σ K/K₀) for which V_crit ≥ factor · V_D, by SLSQP (``scipy.optimize``), once
with these gradients and once with finite-difference gradients (SLSQP's own, step
:data:`FD_STEP` relative), so that the numbers of analyses can be compared.

:func:`openmdao_component` returns an ``openmdao.api.ExplicitComponent`` (the ``mdo`` extra):
inputs the chosen parameter paths, outputs the critical speed and the clearance margin
V_crit / (factor · V_D) − 1, with analytic partials.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar, Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.sensitivity import critical_sensitivities
from propwhirl.analysis.stability import analyse
from propwhirl.model import derivatives as D
from propwhirl.results import Result, SavedDict
from propwhirl.studies.critical import critical_instability, wing_divergence_predicate
from propwhirl.studies.paths import ALTERNATIVES

#: relative step of the finite-difference gradients the comparison uses
FD_STEP = 1e-4
#: lower bound of each stiffness relative to its design value: (3 Hz / 7 Hz)², the lowest mount
#: frequency of the studies' maps.  Below about 1.8 Hz (0.07 K₀) of the wingtip model's yaw mount
#: a yaw-mount instability sets in at low speed and V_crit jumps (the clearance study): an
#: optimum there sits on a discontinuity where no gradient exists (SLSQP stalled at 50
#: iterations with the bound 0.05).
LOWER_BOUND = (3.0 / 7.0) ** 2


def _checked_paths(paths: Any) -> tuple[str, ...]:
    """`paths` as a tuple of strings: at least one, none twice, no field together with its
    alternative (f_theta and K_theta of one propeller: the same stiffness twice)."""
    if isinstance(paths, (str, bytes)) or not isinstance(paths, Sequence):
        raise v.InputError(f"paths = {v.short_repr(paths)} is invalid: give a list of "
                           "parameter paths, e.g. ['propellers[0].propeller.K_theta']")
    out = tuple(paths)
    if not out:
        raise v.InputError("paths = [] is invalid: give at least one parameter path")
    bad = [p for p in out if not isinstance(p, str)]
    if bad:
        raise v.InputError(f"paths: {v.short_repr(bad[0])} is invalid: each path must be a "
                           "string such as 'propellers[0].propeller.K_theta'")
    seen: set[str] = set()
    for p in out:
        head, _, name = p.rpartition(".")
        twin = ALTERNATIVES.get(("Propeller", name)) or ALTERNATIVES.get(("Wing", name))
        if p in seen:
            raise v.InputError(f"paths: {p!r} appears twice: give each parameter once")
        if twin is not None and f"{head}.{twin}" in seen:
            raise v.InputError(f"paths {f'{head}.{twin}'!r} and {p!r} are invalid together: "
                               f"{name} is the alternative of {twin} (the same stiffness): "
                               "give one of them")
        seen.add(p)
    return out


@dataclass
class CriticalSpeed:
    """V_crit(x) [m/s] and dV_crit/dx of ``model`` over the parameter ``paths``.

    static_divergence, low_speed: the convention (False, False: the thesis's, which leaves out
    the wing's static divergence); ``analyses``: how many analyses were run so far.
    """

    model: Any
    paths: Sequence[str]
    static_divergence: bool = True
    low_speed: bool = True
    analyses: int = 0
    #: the design point (the paths' values in the model) and their units, from the model
    x0: np.ndarray = field(init=False, repr=False)
    units: tuple[str, ...] = field(init=False, repr=False)
    _cache: dict = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        self.paths = _checked_paths(self.paths)
        known = {p.path: p for p in D.parameters(self.model)}
        bad = [p for p in self.paths if p not in known]
        if bad:
            raise v.InputError(f"paths {bad} have no exact derivatives: choose among "
                               "propwhirl.model.derivatives.parameters(model)")
        self.x0 = np.array([known[p].value for p in self.paths])
        self.units = tuple(known[p].unit for p in self.paths)

    def variant(self, x) -> Any:
        m = self.model
        for p, value in zip(self.paths, np.asarray(x, dtype=float)):
            m = D.with_value(m, p, float(value))
        return m

    def _evaluate(self, x) -> tuple[float, np.ndarray | None]:
        key = tuple(np.round(np.asarray(x, dtype=float), 12))
        if key in self._cache:
            return self._cache[key]
        m = self.variant(x)
        a = analyse(m)
        self.analyses += 1
        e = critical_instability(a, static_divergence=self.static_divergence,
                                 low_speed=self.low_speed,
                                 is_wing_divergence=wing_divergence_predicate(m, a))
        if e is None:
            out = (float("inf"), np.zeros(len(self.paths)))
        elif e.event not in ("onset", "recovery"):
            out = (float(e.V), None)            # unstable at start / frequency-zero: no gradient
        else:
            cs = critical_sensitivities(m, a, e, params=list(self.paths))
            by = {s.path: s.dV_dp for s in cs.sensitivities}
            out = (float(e.V), np.array([by[p] for p in self.paths]))
        self._cache[key] = out
        return out

    def value(self, x) -> float:
        """V_crit(x) [m/s] (inf when nothing is unstable in the range)."""
        return self._evaluate(x)[0]

    def gradient(self, x) -> np.ndarray:
        """dV_crit/dx [m/s per unit of each path]; an error where the critical event is not a
        crossing (no derivative)."""
        g = self._evaluate(x)[1]
        if g is None:
            raise v.InputError("the critical event at this point is not a crossing: no gradient")
        return g


@dataclass(frozen=True)
class OptimisationResult(Result):
    """The optimum x (in the paths' units), V_crit there [m/s], the objective Σ x/x₀, whether it
    clears, SLSQP's message, and the analyses it took with exact and with finite-difference
    gradients (and each optimum).

    A :class:`~propwhirl.results.Result` of kind "stiffness-optimisation" (format
    ``propwhirl.stiffness-optimisation/1``): :meth:`save` / :meth:`load`, checked; V = inf
    (nothing unstable in the range) is saved as null."""

    paths: tuple[str, ...]
    x: np.ndarray
    V: float
    objective: float
    cleared: bool
    message: str
    analyses: int
    x_fd: np.ndarray
    analyses_fd: int

    KIND: ClassVar[str] = "stiffness-optimisation"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "optimisation file"

    def encode(self) -> dict[str, Any]:
        return {"paths": list(self.paths), "x": np.asarray(self.x, dtype=float).tolist(),
                "V_m_per_s": float(self.V) if math.isfinite(self.V) else None,
                "objective": float(self.objective), "cleared": bool(self.cleared),
                "message": self.message, "analyses": int(self.analyses),
                "x_fd": np.asarray(self.x_fd, dtype=float).tolist(),
                "analyses_fd": int(self.analyses_fd)}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "OptimisationResult":
        """paths (strings, at least one); x and x_fd one finite value per path; V [m/s] > 0
        or null (infinite: nothing unstable); the counts >= 0.  InputError naming the key."""
        r = SavedDict(d, where, ("paths", "x", "V_m_per_s", "objective", "cleared", "message",
                                 "analyses", "x_fd", "analyses_fd"))
        paths = r.strings("paths")
        if not paths:
            raise v.InputError(f"{r.name('paths')}: must name at least one parameter path")
        V = r.number("V_m_per_s", optional=True)
        if V is not None and V <= 0:
            raise v.InputError(f"{r.name('V_m_per_s')} = {V!r} is invalid: must be > 0 m/s "
                               "(null: nothing unstable)")
        n = len(paths)
        return cls(paths, r.array("x", shape=(n,)), math.inf if V is None else V,
                   r.number("objective"), r.boolean("cleared"), r.string("message"),
                   r.integer("analyses", 0), r.array("x_fd", shape=(n,)),
                   r.integer("analyses_fd", 0))


def minimum_mount_stiffness(model, vd: float, factor: float = 1.15, *, propeller: int = 0,
                            static_divergence: bool = False, low_speed: bool = False,
                            lower: float = LOWER_BOUND) -> OptimisationResult:
    """The smallest pitch and yaw mount stiffnesses of propeller ``propeller`` (objective
    K_θ/K_θ0 + K_ψ/K_ψ0, each at least ``lower`` × its value, default :data:`LOWER_BOUND`)
    that keep V_crit ≥ factor · V_D (module docstring); the convention of
    :mod:`propwhirl.studies.critical` (default the thesis's, without the wing's static
    divergence, which no mount stiffness changes)."""
    from scipy.optimize import minimize

    v.positive("vd", vd, "m/s")
    v.in_range("factor", factor, 1.0, 3.0)      # the regulations' 1.15, 1.2 (as clearance)
    pre = f"propellers[{propeller}].propeller."
    paths = (pre + "K_theta", pre + "K_psi")
    target = factor * vd
    runs = {}
    for mode in ("exact", "fd"):
        f = CriticalSpeed(model, paths, static_divergence, low_speed)
        x0 = f.x0
        cons = {"type": "ineq", "fun": lambda x, f=f: (f.value(x * x0) - target) / target}
        if mode == "exact":
            cons["jac"] = lambda x, f=f: f.gradient(x * x0) * x0 / target
        r = minimize(lambda x: float(np.sum(x)), np.ones(2), jac=lambda x: np.ones(2),
                     bounds=[(lower, None)] * 2, constraints=[cons], method="SLSQP",
                     options={"ftol": 1e-6, "maxiter": 50, "eps": FD_STEP})
        runs[mode] = (r, f)
    (r, f), (rf, ff) = runs["exact"], runs["fd"]
    V = f.value(r.x * f.x0)
    return OptimisationResult(paths, r.x * f.x0, V, float(np.sum(r.x)), bool(V >= target - 1e-6),
                              str(r.message), f.analyses, rf.x * ff.x0, ff.analyses)


def openmdao_component(model, paths: Sequence[str], *, vd: float, factor: float = 1.15,
                       static_divergence: bool = True, low_speed: bool = True):
    """An OpenMDAO ``ExplicitComponent``: inputs the parameter ``paths`` (names with "." and
    "[]" replaced by "_"; each path's value and unit), outputs ``V_crit`` [m/s] and ``margin``
    = V_crit / (factor · V_D) − 1 [-], analytic partials (:class:`CriticalSpeed`).  Needs
    ``pip install propwhirl[mdo]``.

    Checked before OpenMDAO sees anything: at least one path, each once, no field with its
    alternative, vd [m/s] > 0, factor in [1, 3] (as :func:`propwhirl.studies.clearance.clearance`).
    """
    try:
        import openmdao.api as om
    except ImportError:
        raise ImportError("the OpenMDAO component needs openmdao: pip install "
                          "propwhirl[mdo]") from None
    target = float(v.in_range("factor", factor, 1.0, 3.0)) * float(v.positive("vd", vd, "m/s"))
    f = CriticalSpeed(model, paths, static_divergence, low_speed)
    names = [p.replace(".", "_").replace("[", "_").replace("]", "") for p in f.paths]
    clash = [(p, q) for i, (p, n) in enumerate(zip(f.paths, names))
             for q, m in zip(f.paths[i + 1:], names[i + 1:]) if n == m]
    if clash:
        raise v.InputError(f"paths {clash[0][0]!r} and {clash[0][1]!r} are invalid together: "
                           f"both become the OpenMDAO input {names[f.paths.index(clash[0][0])]!r}")

    class CriticalSpeedComponent(om.ExplicitComponent):
        """V_crit and the clearance margin of a propwhirl model over parameter paths."""

        def setup(self):
            for name, x0 in zip(names, f.x0):
                self.add_input(name, val=float(x0))
            self.add_output("V_crit", val=0.0, units="m/s")
            self.add_output("margin", val=0.0)
            self.declare_partials("*", "*")

        def _x(self, inputs):
            return np.array([float(inputs[n][0]) for n in names])

        def compute(self, inputs, outputs):
            V = f.value(self._x(inputs))
            outputs["V_crit"] = V
            outputs["margin"] = V / target - 1.0

        def compute_partials(self, inputs, partials):
            g = f.gradient(self._x(inputs))
            for name, gi in zip(names, g):
                partials["V_crit", name] = gi
                partials["margin", name] = gi / target

    comp = CriticalSpeedComponent()
    comp.propwhirl = f
    return comp
