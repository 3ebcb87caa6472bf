"""Gradient-based design: the critical speed and its exact gradient as a function of chosen
parameters, a minimum-stiffness clearance optimisation, and an OpenMDAO component.

:class:`CriticalSpeed` evaluates, for values x of parameter paths (those of
:func:`propwhirl.model.derivatives.parameters`), the critical speed V_crit(x) [m/s] of the model
(the one definition, with the thesis's exclusions as options: :mod:`propwhirl.studies.critical`)
and its gradient from :func:`propwhirl.analysis.sensitivity.critical_sensitivities` — one
analysis per point, the gradient included.  It counts the analyses it ran.

:func:`minimum_mount_stiffness` is the optimisation of issue 13.4: the smallest pitch and yaw
mount stiffnesses (Σ K/K₀) for which V_crit ≥ factor · V_D, by SLSQP (``scipy.optimize``), with
these gradients (default) or finite-difference gradients (SLSQP's own, step :data:`FD_STEP`
relative), or both with ``compare=True`` so that the numbers of analyses can be compared.

:func:`openmdao_component` returns an ``openmdao.api.ExplicitComponent`` (the ``mdo`` extra):
inputs the chosen parameter paths (named by :func:`openmdao_name`), outputs the critical speed
and the clearance margin V_crit / (factor · V_D) − 1, with analytic partials.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar, Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.certification import FACTOR_CS25, required_speed
from propwhirl.analysis.sensitivity import critical_sensitivities
from propwhirl.analysis.stability import analyse
from propwhirl.model import derivatives as D
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.model.parameter_paths import parameter_paths
from propwhirl.model.protocol import capabilities
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
#: upper bound of each stiffness relative to its design value: 9, three times the design mount
#: frequency.  Without it a critical speed the mount barely moves sent SLSQP to 10⁵ K₀ and past
#: the model's valid range (the X-57-like model, propeller 7: issue 25.7)
UPPER_BOUND = 9.0
#: SLSQP aims at factor · V_D · (1 + CLEARANCE_MARGIN): it accepts a constraint violated by up
#: to its ftol (1e-6 of the target), and a result 3e-6 m/s short is not cleared
CLEARANCE_MARGIN = 1e-5
#: below this fraction of the shortfall recovered by the design point's gradient within the
#: bounds, the critical instability is not the mount's (the optimisation is not started)
REACH_FRACTION = 0.1


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
    #: the doublet-lattice tables every analysis of the variants reads and fills (one set of
    #: AICs per planform, as the other studies share theirs)
    tables: DlmTables = field(default_factory=DlmTables, repr=False)
    #: the design point (the paths' values in the model) and their units, from the model
    x0: np.ndarray = field(init=False, repr=False)
    units: tuple[str, ...] = field(init=False, repr=False)
    _cache: dict = field(default_factory=dict, repr=False)
    _labels: dict = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        self.paths = _checked_paths(self.paths)
        # the model contract's paths with exact derivatives of the blocks (the factors and
        # the density have exact sensitivities but no blocks to differentiate here)
        known = {p.path: p for p in parameter_paths(self.model)
                 if p.derivative == "exact" and p.kind not in ("factor", "flight")}
        bad = [p for p in self.paths if p not in known]
        if bad:
            why = capabilities(self.model).refusal("exact-sensitivity")
            raise v.InputError(f"paths {bad} have no exact derivatives"
                               + (f" ({why})" if why else "") + ": choose among "
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
        a = analyse(m, dlm_tables=self.tables)
        self.analyses += 1
        e = critical_instability(a, static_divergence=self.static_divergence,
                                 low_speed=self.low_speed,
                                 is_wing_divergence=wing_divergence_predicate(m, a))
        self._labels[key] = "" if e is None else f"{e.kind} of {e.label}"
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

    def critical(self, x) -> str:
        """What the critical instability at x is ("flutter of forward 1"; "" when none)."""
        self._evaluate(x)
        return self._labels.get(tuple(np.round(np.asarray(x, dtype=float), 12)), "")

    def gradient(self, x) -> np.ndarray:
        """dV_crit/dx [m/s per unit of each path]; an error where the critical event is not a
        crossing (no derivative)."""
        g = self._evaluate(x)[1]
        if g is None:
            raise v.InputError("the critical event at this point is not a crossing: no gradient")
        return g


@dataclass(frozen=True)
class OptimisationResult(Result):
    """The stiffnesses found, x (in the paths' units, design values ``x0``), V_crit there
    [m/s] against the required ``target`` = factor · V_D [m/s], the objective Σ x/x₀, whether
    V_crit ≥ target there (``cleared``: no tolerance), a plain message, the gradients used
    (``method``: "exact" or "fd") and the analyses they took; with ``compare=True`` also the
    other method's optimum ``x_fd`` and analyses ``analyses_fd`` (None otherwise).

    ``str(result)`` is a readable summary.  A :class:`~propwhirl.results.Result` of kind
    "stiffness-optimisation" (format ``propwhirl.stiffness-optimisation/2``; version 1 files,
    which always held both methods, still load): :meth:`save` / :meth:`load`, checked; V = inf
    (nothing unstable in the range) is saved as null."""

    paths: tuple[str, ...]
    x: np.ndarray
    V: float
    objective: float
    cleared: bool
    message: str
    analyses: int
    x_fd: np.ndarray | None = None
    analyses_fd: int | None = None
    method: str = "exact"
    target: float | None = None
    x0: np.ndarray | None = None

    KIND: ClassVar[str] = "stiffness-optimisation"
    VERSION: ClassVar[int] = 2
    READABLE: ClassVar[tuple[int, ...]] = (1, 2)
    WHAT: ClassVar[str] = "optimisation file"

    def __str__(self) -> str:
        lines = []
        for i, p in enumerate(self.paths):
            rel = "" if self.x0 is None else f" ({self.x[i] / self.x0[i]:.3f} × design)"
            lines.append(f"  {p} = {self.x[i]:.6g}{rel}")
        V = "none in range" if not math.isfinite(self.V) else f"{self.V:.3f} m/s"
        need = "" if self.target is None else f", required {self.target:.3f} m/s"
        head = "cleared" if self.cleared else "NOT cleared"
        out = [f"stiffness optimisation ({self.method} gradients): {head}",
               *lines, f"  V_crit = {V}{need}", f"  objective Σ K/K₀ = {self.objective:.4f}",
               f"  {self.analyses} analys{'i' if self.analyses == 1 else 'e'}s",
               f"  {self.message}"]
        if self.x_fd is not None:
            other = "finite-difference" if self.method == "exact" else "exact"
            out.append(f"  compared: {other} gradients took {self.analyses_fd} analyses, "
                       "optimum " + ", ".join(f"{x:.6g}" for x in self.x_fd))
        return "\n".join(out)

    def encode(self) -> dict[str, Any]:
        def arr(a):
            return None if a is None else np.asarray(a, dtype=float).tolist()
        return {"paths": list(self.paths), "x": arr(self.x), "x0": arr(self.x0),
                "V_m_per_s": float(self.V) if math.isfinite(self.V) else None,
                "target_m_per_s": None if self.target is None else float(self.target),
                "objective": float(self.objective), "cleared": bool(self.cleared),
                "message": self.message, "method": self.method,
                "analyses": int(self.analyses), "x_fd": arr(self.x_fd),
                "analyses_fd": None if self.analyses_fd is None else int(self.analyses_fd)}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "OptimisationResult":
        """paths (strings, at least one); x, x0 and x_fd one finite value per path (x0, x_fd
        null allowed); V [m/s] > 0 or null (infinite: nothing unstable); target [m/s] > 0 or
        null; method "exact" or "fd"; the counts >= 0.  InputError naming the key."""
        keys = ("paths", "x", "V_m_per_s", "objective", "cleared", "message", "analyses",
                "x_fd", "analyses_fd")
        r = SavedDict(d, where, keys + (("x0", "target_m_per_s", "method") if version >= 2
                                        else ()))
        paths = r.strings("paths")
        if not paths:
            raise v.InputError(f"{r.name('paths')}: must name at least one parameter path")
        V = r.number("V_m_per_s", optional=True)
        if V is not None and V <= 0:
            raise v.InputError(f"{r.name('V_m_per_s')} = {V!r} is invalid: must be > 0 m/s "
                               "(null: nothing unstable)")
        n = len(paths)

        def maybe(key):
            return None if r.raw(key) is None else r.array(key, shape=(n,))
        if version < 2:
            return cls(paths, r.array("x", shape=(n,)), math.inf if V is None else V,
                       r.number("objective"), r.boolean("cleared"), r.string("message"),
                       r.integer("analyses", 0), r.array("x_fd", shape=(n,)),
                       r.integer("analyses_fd", 0))
        target = r.number("target_m_per_s", optional=True)
        if target is not None and target <= 0:
            raise v.InputError(f"{r.name('target_m_per_s')} = {target!r} is invalid: must be "
                               "> 0 m/s (or null)")
        return cls(paths, r.array("x", shape=(n,)), math.inf if V is None else V,
                   r.number("objective"), r.boolean("cleared"), r.string("message"),
                   r.integer("analyses", 0), maybe("x_fd"),
                   None if r.raw("analyses_fd") is None else r.integer("analyses_fd", 0),
                   r.string("method", ("exact", "fd")), target, maybe("x0"))


def _fd_gradient(f: "CriticalSpeed", x: np.ndarray) -> np.ndarray:
    """dV/dx at normalised x by forward differences of step :data:`FD_STEP` (SLSQP's own
    steps: the same points, so SLSQP's first gradient costs no further analysis)."""
    V = f.value(x * f.x0)
    g = np.empty(x.size)
    for i in range(x.size):
        xi = x.copy()
        xi[i] += FD_STEP
        g[i] = (f.value(xi * f.x0) - V) / FD_STEP
    return g


def _what(f: "CriticalSpeed") -> str:
    """" (the flutter of …)": what V_crit is at the design point, or "" if unknown."""
    label = f.critical(f.x0) if hasattr(f, "critical") else ""
    return f" (the {label})" if label else ""


def _optimise(f: "CriticalSpeed", method: str, target: float, lower: float, upper: float):
    """SLSQP on the normalised stiffnesses x/x₀ with `method`'s gradients: (x, V, message)."""
    from scipy.optimize import minimize

    n = len(f.paths)
    one = np.ones(n)
    aim = target * (1.0 + CLEARANCE_MARGIN)
    V0 = f.value(f.x0)
    if V0 < target:
        # can the mount move the critical instability at all?  the gradient at the design
        # point, extrapolated linearly to the most favourable corner of the bounds
        try:
            g = f.gradient(f.x0) * f.x0 if method == "exact" else _fd_gradient(f, one)
        except v.InputError:
            g = None
        if g is not None:
            reach = float(np.sum(np.maximum(g * (upper - 1.0), g * (lower - 1.0))))
            if reach < REACH_FRACTION * (target - V0):
                return one, V0, (
                    f"not cleared: V_crit = {V0:.3f} m/s{_what(f)} is {target - V0:.3g} m/s "
                    f"short of {target:.3f} m/s and does not move with these stiffnesses (by "
                    f"the gradient at the design point it rises by at most {reach:.3g} m/s "
                    f"between {lower:.3g} and {upper:.3g} times the design values): this "
                    "mount cannot clear it")
    cons = {"type": "ineq", "fun": lambda x: (f.value(x * f.x0) - aim) / target}
    if method == "exact":
        cons["jac"] = lambda x: f.gradient(x * f.x0) * f.x0 / target
    r = minimize(lambda x: float(np.sum(x)), one, jac=lambda x: one,
                 bounds=[(lower, upper)] * n, constraints=[cons], method="SLSQP",
                 options={"ftol": 1e-6, "maxiter": 50, "eps": FD_STEP})
    x = np.clip(r.x, lower, upper)
    V = f.value(x * f.x0)
    if V >= target:
        msg = (f"cleared: V_crit = {V:.3f} m/s ≥ {target:.3f} m/s (SLSQP: {r.message})")
    else:
        msg = (f"not cleared: V_crit = {V:.3f} m/s is {target - V:.3g} m/s short of "
               f"{target:.3f} m/s (SLSQP: {r.message})")
    return x, V, msg


def minimum_mount_stiffness(model, vd: float, factor: float = FACTOR_CS25, *, propeller: int = 0,
                            static_divergence: bool = False, low_speed: bool = False,
                            lower: float = LOWER_BOUND, upper: float = UPPER_BOUND,
                            gradients: str = "exact",
                            compare: bool = False) -> OptimisationResult:
    """The smallest pitch and yaw mount stiffnesses of propeller ``propeller`` (the index of
    ``model.propellers``, from 0: ``propeller=6`` is the seventh) — objective
    K_θ/K_θ0 + K_ψ/K_ψ0, each between ``lower`` and ``upper`` times its design value (defaults
    :data:`LOWER_BOUND`, :data:`UPPER_BOUND`) — that keep V_crit ≥ factor · V_D (module
    docstring); the convention of :mod:`propwhirl.studies.critical` (default the thesis's,
    without the wing's static divergence, which no mount stiffness changes).

    gradients: "exact" (:class:`CriticalSpeed`, one analysis per point) or "fd" (SLSQP's
    forward differences, relative step :data:`FD_STEP`); compare: also run the other method
    (its optimum and analyses in ``x_fd``, ``analyses_fd``).  SLSQP aims at
    target · (1 + :data:`CLEARANCE_MARGIN`) so that its accepted constraint violation (ftol
    1e-6) still clears the target; ``cleared`` is V_crit ≥ factor · V_D at the result, without
    tolerance, and the message says by how much it is short otherwise.  When V_crit at the
    design point is short and its gradient, extrapolated to the bounds, recovers less than
    :data:`REACH_FRACTION` of the shortfall, the critical instability is not this mount's: the
    result says so after one analysis (exact) or three (fd).

    Parameters
    ----------
    model : PropellerWing
        The model (its speed range is the analyses').
    vd : float
        Design dive speed V_D [m/s].
    factor : float
        Speed factor [-] (1.15: CS/FAR 25.629).
    propeller : int
        Index of the propeller in ``model.propellers``, from 0.
    static_divergence, low_speed : bool
        The convention (default the thesis's exclusions).
    lower, upper : float
        Bounds of each stiffness [-], relative to its design value.
    gradients : {"exact", "fd"}
        Exact gradients or SLSQP's finite differences.
    compare : bool
        Also run the other method.

    Returns
    -------
    OptimisationResult
        The stiffnesses ``x`` [N m/rad] of ``paths`` (design values ``x0``), V_crit there
        ``V`` [m/s] against ``target`` [m/s], ``objective`` [-], ``cleared``, ``message``,
        the ``analyses`` run.

    Examples
    --------
    The baseline wing on 4 elements with its tip propeller: to clear 1.15 × 130 m/s its
    pitch mount may be 0.41 times as stiff, its yaw mount is at its lower bound (3/7)²:

    >>> from propwhirl.studies import minimum_mount_stiffness
    >>> from propwhirl.model import FlightCondition, Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
    >>> model = PropellerWing(baseline_wing(n_elements=4),       # 4 elements, 100-200 m/s
    ...                       FlightCondition(0.96287, speed_range=(100.0, 200.0, 20.0)),
    ...                       (Installation(baseline_propeller(), 5.7),))
    >>> r = minimum_mount_stiffness(model, vd=130.0)
    >>> r.paths
    ('propellers[0].propeller.K_theta', 'propellers[0].propeller.K_psi')
    >>> r.cleared, [round(float(k), 2) for k in r.x / r.x0], round(r.V, 1), r.target
    (True, [0.41, 0.18], 149.5, 149.5)
    """
    target, _ = required_speed(vd, factor, vd_name="vd")    # factor · V_D, as clearance's
    if gradients not in ("exact", "fd"):
        raise v.InputError(f"gradients = {v.short_repr(gradients)} is invalid: must be "
                           "'exact' or 'fd'")
    v.boolean("compare", compare)
    n_props = len(getattr(model, "propellers", ()))
    if isinstance(propeller, bool) or not isinstance(propeller, (int, np.integer)) \
            or not 0 <= propeller < n_props:
        raise v.InputError(f"propeller = {v.short_repr(propeller)} is invalid: must be an "
                           f"index of model.propellers, 0 to {n_props - 1} (0 is the first)")
    v.in_range("lower", lower, 1e-3, 1.0)
    v.in_range("upper", upper, 1.0, 1e3)
    pre = f"propellers[{propeller}].propeller."
    paths = (pre + "K_theta", pre + "K_psi")
    runs = {}
    for method in ((gradients, "fd" if gradients == "exact" else "exact") if compare
                   else (gradients,)):
        f = CriticalSpeed(model, paths, static_divergence, low_speed)
        runs[method] = (f, *_optimise(f, method, target, lower, upper))
    f, x, V, msg = runs[gradients]
    other = next((r for m, r in runs.items() if m != gradients), None)
    return OptimisationResult(paths, x * f.x0, V, float(np.sum(x)), bool(V >= target), msg,
                              f.analyses, None if other is None else other[1] * other[0].x0,
                              None if other is None else other[0].analyses, gradients,
                              float(target), f.x0.copy())


def openmdao_name(path: str) -> str:
    """The OpenMDAO input name of a parameter path: every "." and every "[" becomes one "_",
    every "]" is dropped —
    ``propellers[6].propeller.f_theta`` → ``propellers_6_propeller_f_theta``, ``wing.EI[3]`` → ``wing_EI_3``, ``propellers[0].propeller.derivatives.values[Aa]`` →
    ``propellers_0_propeller_derivatives_values_Aa``.  (OpenMDAO reserves "." for its own
    hierarchy.)  Two paths of one component that would share a name are refused."""
    return path.replace(".", "_").replace("[", "_").replace("]", "")


def openmdao_component(model, paths: Sequence[str], *, vd: float, factor: float = FACTOR_CS25,
                       static_divergence: bool = True, low_speed: bool = True):
    """An OpenMDAO ``ExplicitComponent``: inputs the parameter ``paths`` (named by
    :func:`openmdao_name`; ``comp.input_names`` maps each path to its name; each path's value),
    outputs ``V_crit`` [m/s] and ``margin``
    = V_crit / (factor · V_D) − 1 [-], analytic partials (:class:`CriticalSpeed`).  Needs
    ``pip install propwhirl[mdo]``.

    Checked before OpenMDAO sees anything: at least one path, each once, no field with its
    alternative, vd [m/s] > 0, factor in [1, 3] (as :func:`propwhirl.studies.clearance.clearance`).

    Parameters
    ----------
    model : Model
        The model (its speed range is the analyses').
    paths : sequence of str
        The input parameter paths (their units are the inputs').
    vd : float
        Design dive speed V_D [m/s].
    factor : float
        Speed factor [-], in [1, 3].
    static_divergence, low_speed : bool
        The convention (:func:`propwhirl.studies.critical.critical_instability`).

    Returns
    -------
    openmdao.api.ExplicitComponent
        Inputs: the paths' values; outputs ``V_crit`` [m/s] and ``margin`` [-].

    Examples
    --------
    >>> import openmdao.api as om
    >>> from propwhirl.studies import openmdao_component
    >>> from propwhirl.model import FlightCondition, Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
    >>> model = PropellerWing(baseline_wing(n_elements=4),       # 4 elements, 100-200 m/s
    ...                       FlightCondition(0.96287, speed_range=(100.0, 200.0, 20.0)),
    ...                       (Installation(baseline_propeller(), 5.7),))
    >>> comp = openmdao_component(model, ["propellers[0].propeller.K_theta"], vd=130.0,
    ...                           static_divergence=False, low_speed=False)
    >>> comp.input_names
    {'propellers[0].propeller.K_theta': 'propellers_0_propeller_K_theta'}
    >>> prob = om.Problem(reports=False)
    >>> _ = prob.model.add_subsystem("whirl", comp, promotes=["*"])
    >>> _ = prob.setup()
    >>> prob.run_model()
    >>> round(float(prob.get_val("V_crit")[0]), 1)                     # [m/s]
    160.3
    """
    try:
        import openmdao.api as om
    except ImportError:
        raise ImportError("the OpenMDAO component needs openmdao: pip install "
                          "propwhirl[mdo]") from None
    target, _ = required_speed(vd, factor, vd_name="vd")
    f = CriticalSpeed(model, paths, static_divergence, low_speed)
    names = [openmdao_name(p) for p in f.paths]
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
    comp.input_names = dict(zip(f.paths, names))
    return comp
