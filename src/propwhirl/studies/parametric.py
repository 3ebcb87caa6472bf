"""Parametric studies of chapter 11 (Figures 11.1–11.15): critical speed against one parameter.

Each study varies one property of the baseline propeller (Tables 9.3–9.4) and analyses, for
every value, the models the thesis compares:

* ``"wingtip"``  — the baseline wing with the flexibly mounted, rotating propeller at the tip,
  wing and propeller aerodynamics on (§10.1, the headline configuration);
* ``"isolated"`` — the same propeller on a rigid wing (chapter 6 model, §9.2);
* ``"rigid"``    — the wingtip model with a rigid, non-rotating mount and no propeller
  aerodynamics (the inert tip mass of §10.1.1; Figure 11.6 shows it for the motor mass).

Every study returns a :class:`StudyTable`: one row per (model, parameter value) with the
parameter column(s), the critical speed [m/s], the critical frequency [Hz], the critical mode's
label ("forward 1", "backward", "wing 2", ...) and dominant content ("torsion", "yaw", ...),
the instability kind ("flutter"/"divergence"), the event and the whirl sense at the critical
point, plus the wing's static divergence speed.

Definition of "critical" (:func:`critical_instability`)
--------------------------------------------------------
By default the critical instability is the one of :func:`propwhirl.analysis.critical` — the
lowest-speed event that makes the system unstable, of any kind: a flutter onset, a divergence
onset (the wing's static divergence included), a frequency-zero event, or an instability present
at the first speed (counted there).  The thesis's figures leave two classes of events out; pass
``static_divergence=False, low_speed=False`` (the *thesis convention*, recorded in the table's
``convention``) to do the same:

* static divergence of the wing (``static_divergence=False``).  The thesis does not report it
  for the wingtip models although its own equations have it (docs/validation.md, chapter 10).
  It is always reported in the column ``static_divergence_speed``.  A divergence is the wing's
  when less than half of the strain energy of its (static) mode shape is in the propeller mount
  springs (:func:`wing_divergence_predicate`); otherwise it is a divergence of the propeller
  mount (e.g. a very soft yaw mount, Figure 11.1) and always counts.  The shape decides, not the
  mode's name: with soft mounts the in-vacuo names can sit on other modes (at f_ψ = 2 Hz the
  wing's divergence happens on the branch named "backward 1", at f_θ = 1 Hz a mount divergence
  on "wing 1");
* instabilities present at the first speed of the grid that recover further on
  (``low_speed=False``): the windmilling propeller has (almost) no aerodynamic or structural
  damping as V → 0, and the thesis tells the reader to ignore such low-speed instabilities
  (§9.2).  An instability present at the first speed that never recovers counts, at that speed.

Speed ranges: the propeller–wing models use the thesis's 0–350 m/s (their FlightCondition's
speed_range, refined by the engine); the isolated propeller, whose critical speeds the thesis
plots beyond the speed of sound (Figures 11.1, 11.15), uses 1–1000 m/s.  Points with no
instability in the range have NaN speed and frequency and kind "none".

Parallelism: the analyses of a study are independent; ``processes > 1`` runs them in a
:class:`concurrent.futures.ProcessPoolExecutor` whose workers pin BLAS to one thread (a pool of
`processes` single-threaded workers, not a pool of multi-threaded BLAS calls).  The results do
not depend on ``processes``.  Models are built in the calling process and sent to the workers,
so a propeller with a user-supplied callable (blade chord, derivatives) must be picklable (a
module-level function) for ``processes > 1``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, ClassVar, Literal, Mapping, Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.results import Result, SavedDict
from propwhirl.studies import paths as P
from propwhirl.studies.critical import (convention, critical_instability, mount_strain_share,  # noqa: F401
                                        static_divergence_speed, wing_divergence_predicate)
from propwhirl.studies.runner import (ISOLATED_SPEEDS, MODELS, build_model,  # noqa: F401
                                      check_models, map_analyses, parameter_grid, speeds_for,
                                      study_points, study_table)
from propwhirl.studies.sweeps import run_points
from propwhirl.studies.table import RESULT_UNITS, StudyTable  # noqa: F401

__all__ = [  # the chapter-11 studies, and the machinery they are built on (re-exported)
    "nacelle_stiffness", "nacelle_damping", "motor_mass", "pivot_length", "spin_inertia",
    "blade_angle", "whirl_flutter_speeds", "blade_angle_mode_switch", "ModeSwitch",
    "StudyTable", "RESULT_UNITS", "MODELS", "ISOLATED_SPEEDS", "build_model", "map_analyses",
    "propeller_study", "critical_instability", "convention", "static_divergence_speed",
    "mount_strain_share", "wing_divergence_predicate", "PROPELLER_PATHS",
]

#: Where each study model holds its propeller: the prefix of the propeller's parameter paths
#: (:mod:`propwhirl.studies.paths`).
PROPELLER_PATHS: dict[str, str] = {"wingtip": "propellers[0].propeller.",
                                   "rigid": "propellers[0].propeller.", "isolated": "propeller."}


def propeller_study(name: str, parameter: str, unit: str, parameters: Mapping[str, np.ndarray],
                    settings: Sequence[Mapping[str, float]], *, propeller: Propeller | None = None,
                    models: Sequence[str] = ("wingtip", "isolated"),
                    parameter_units: Mapping[str, str] | None = None,
                    static_divergence: bool = True, low_speed: bool = True,
                    speeds=None, xtol: float = 0.01, processes: int = 1, client=None,
                    progress=None, checkpoint=None) -> StudyTable:
    """The generic study: each model of `models` (built with `propeller`, default the
    baseline) at each point of `settings`; one row per (model, point).

    settings: per point, the propeller's parameters to set, as parameter paths relative to
        the propeller (``{"f_theta": 3.0, "f_psi": 3.0}``, ``{"masses[0].mass": 10.0}``),
        applied to each model at its :data:`PROPELLER_PATHS` prefix
        (:func:`propwhirl.studies.paths.set_values`: the model's own validation runs);
    parameters: columns describing each point (equal length to `settings`), the x-axis column
        `parameter` [unit] among them;
    speeds: initial speed grid [m/s] for all models, or a mapping model → grid (default: the
        module docstring's ranges); xtol [m/s]: crossing accuracy; processes: pool size;
    client: a ``dask.distributed.Client`` or scheduler address; progress: a bar (True) or a
        callable ``report(done, total)``; checkpoint: keep the finished points in a
        partial-results file and resume from it (:class:`propwhirl.studies.execution.Checkpoint`;
        its fingerprint defaults to the study's name, parameter, models, xtol and convention).
    The points are analysed by :func:`propwhirl.studies.sweeps.run_points`.  A point whose
    variant is invalid or whose analysis fails is recorded, the others go on: its row has kind
    "error", NaN speeds and the message in the column ``error`` ("" elsewhere).
    """
    models = check_models(models)
    keys, checkpoint = study_points(name, parameter, parameters, len(settings), models, xtol,
                                    static_divergence, low_speed, checkpoint)
    base = _base(propeller)
    variants, grids = [], []
    for m in models:
        model, grid = build_model(m, base), speeds_for(m, speeds)
        prefix = PROPELLER_PATHS[m]
        paths = {k: P.resolve(model, prefix + k) for k in settings[0]}
        for point in settings:
            try:
                variants.append(P.set_values(model, {paths[k]: x for k, x in point.items()}))
            except v.InputError as exc:          # recorded in its row, the others go on
                variants.append(exc)
            grids.append(grid)
    rows = run_points(variants, speeds_each=grids, xtol=xtol, static_divergence=static_divergence,
                      low_speed=low_speed, processes=processes, client=client, progress=progress,
                      checkpoint=checkpoint, keys=keys, desc=name)
    return study_table(name, parameter, unit, parameters, models, rows, parameter_units,
                       static_divergence, low_speed)


def _variant_propellers(base: Propeller, settings: Sequence[Mapping[str, float]]) -> list[Propeller]:
    """The propeller of each point (for the columns derived from it: inertia, I_Omega, ...)."""
    return [P.set_values(base, point) for point in settings]


def _base(propeller: Propeller | None) -> Propeller:
    if propeller is None:
        return baseline_propeller()
    if not isinstance(propeller, Propeller):
        raise v.InputError(f"propeller = {propeller!r} is invalid: must be a propwhirl.model.propellers.propeller.Propeller")
    return propeller


_Vary = Literal["pitch", "yaw", "both"]


def _check_vary(vary: str) -> str:
    if vary not in ("pitch", "yaw", "both"):
        raise v.InputError(f"vary = {vary!r} is invalid: must be 'pitch', 'yaw' or 'both'")
    return vary


# ----------------------------------------------------------------------------- §11.1 stiffness
#: Default mount frequencies of the stiffness study [Hz] (the thesis sweeps 1–12 Hz)
STIFFNESS_FREQUENCIES = (1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0, 12.0)


def nacelle_stiffness(vary: _Vary = "both", frequencies=STIFFNESS_FREQUENCIES, *,
                      fixed_frequency: float = 7.0, propeller: Propeller | None = None,
                      models: Sequence[str] = ("wingtip", "isolated"), **options) -> StudyTable:
    """§11.1, Figures 11.1–11.2: critical speed against the nacelle stiffness.

    vary: "yaw" (f_θ = `fixed_frequency`, f_ψ swept — the thesis's case 1), "pitch" (f_ψ fixed,
    f_θ swept — case 2) or "both" (f_θ = f_ψ swept — case 3).  `frequencies` [Hz] are the
    uncoupled mount frequencies (K = I (2π f)², §8.1).  The x-axis column is the mean frequency
    (f_θ + f_ψ)/2 of Figures 11.1–11.2; the columns f_theta, f_psi give both.
    options: see :func:`propeller_study` (static_divergence, low_speed, speeds, xtol, processes).

    Parameters
    ----------
    vary : {"yaw", "pitch", "both"}
        Which mount frequency is swept.
    frequencies : array_like
        The swept mount frequencies [Hz].
    fixed_frequency : float
        The other mount's frequency [Hz] when one is swept.
    propeller : Propeller, optional
        The propeller (default the baseline, Tables 9.3–9.4).
    models : sequence of str
        Which models: "wingtip" (§10.1), "isolated" (§9.2), ...
    **options
        Those of :func:`propeller_study`: static_divergence, low_speed, speeds [m/s],
        xtol [m/s], processes, client, progress, checkpoint.

    Returns
    -------
    StudyTable
        One row per (model, frequency): f_theta, f_psi, mean_frequency [Hz], the critical
        speed [m/s], frequency [Hz], mode, kind, ...

    Examples
    --------
    The isolated baseline propeller with both mounts at 6 and 8 Hz:

    >>> from propwhirl.studies import nacelle_stiffness
    >>> t = nacelle_stiffness("both", [6.0, 8.0], models=("isolated",),
    ...                       speeds=[100.0, 200.0, 300.0])
    >>> t.columns["mean_frequency"].tolist(), list(t.columns["kind"])
    ([6.0, 8.0], ['flutter', 'flutter'])
    >>> [round(float(V), 1) for V in t.columns["critical_speed"]]          # [m/s]
    [184.5, 265.7]
    """
    _check_vary(vary)
    f = parameter_grid("frequencies", frequencies, "Hz", v.positive)
    v.positive("fixed_frequency", fixed_frequency, "Hz")
    base = _base(propeller)
    ft = f if vary in ("pitch", "both") else np.full_like(f, fixed_frequency)
    fp = f if vary in ("yaw", "both") else np.full_like(f, fixed_frequency)
    points = [{"f_theta": a, "f_psi": b} for a, b in zip(ft, fp)]  # K_theta, K_psi cleared
    return propeller_study(f"nacelle stiffness, {vary} varied", "mean_frequency", "Hz",
                           {"f_theta": ft, "f_psi": fp, "mean_frequency": 0.5 * (ft + fp)}, points,
                           propeller=base, models=models,
                           parameter_units={"f_theta": "Hz", "f_psi": "Hz"}, **options)


# ----------------------------------------------------------------------------- §11.2 damping
#: Default damping values of the damping study (the thesis sweeps 0–1, with a close-up near 0)
DAMPING_VALUES = (0.0, 0.0025, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0)


def nacelle_damping(vary: _Vary = "both", values=DAMPING_VALUES, *, fixed_value: float = 0.005,
                    damping: Literal["g", "zeta"] | None = None, propeller: Propeller | None = None,
                    models: Sequence[str] = ("wingtip", "isolated"), **options) -> StudyTable:
    """§11.2, Figures 11.4–11.5: critical speed against the nacelle structural damping.

    vary: "yaw" (pitch damping = `fixed_value`, yaw swept — the thesis's case 1), "pitch" or
    "both".  The values are read as `damping` ("g": structural coefficient, viscous equivalent
    ζ = g/2; "zeta": viscous ratio, eq. 6.4–6.6); default: the reading of the base propeller.
    Chapter 11 calls the baseline value 0.005 "ζ", but it is the g = 0.005 of Table 9.4, read
    as g throughout propwhirl (docs/validation.md, Table 9.5 evidence); with the default the
    swept values are on the same footing as that baseline.  x-axis: the mean value.
    """
    _check_vary(vary)
    d = parameter_grid("damping values", values, "", v.non_negative)
    v.non_negative("fixed_value", fixed_value)
    base = _base(propeller)
    reading = base.damping if damping is None else damping
    if reading not in ("g", "zeta"):
        raise v.InputError(f"damping = {reading!r} is invalid: must be 'g' or 'zeta'")
    dt = d if vary in ("pitch", "both") else np.full_like(d, fixed_value)
    dp = d if vary in ("yaw", "both") else np.full_like(d, fixed_value)
    points = [{"damping_theta": a, "damping_psi": b} for a, b in zip(dt, dp)]
    return propeller_study(f"nacelle damping ({reading}), {vary} varied", "mean_damping", "",
                           {"damping_theta": dt, "damping_psi": dp, "mean_damping": 0.5 * (dt + dp)}, points,
                           propeller=replace(base, damping=reading), models=models, **options)


# ----------------------------------------------------------------------------- §11.3 motor mass
#: Default motor-nacelle masses [kg] (baseline 35 kg; 17.5 kg is half of it)
MOTOR_MASSES = (10.0, 17.5, 25.0, 30.0, 35.0, 40.0, 50.0, 60.0, 70.0)


def motor_mass(masses=MOTOR_MASSES, *, propeller: Propeller | None = None,
               models: Sequence[str] = ("wingtip", "isolated", "rigid"), **options) -> StudyTable:
    """§11.3, Figure 11.6: critical speed against the motor-nacelle mass [kg].

    The first of the base propeller's `masses` (the motor-nacelle, 35 kg at −0.86 m) takes each
    mass; its position stays (the thesis: "its CG location remains the same"); I_Ω does not
    change (it depends on the rotor only, eq. 9.2).  Default models: wingtip, isolated and the
    rigid non-rotating mount, as Figure 11.6.
    """
    m = parameter_grid("motor masses", masses, "kg", v.positive)
    base = _base(propeller)
    if not base.masses:
        raise v.InputError("propeller has no motor-nacelle mass (its `masses` is empty)")
    return propeller_study("motor-nacelle mass", "motor_mass", "kg", {"motor_mass": m},
                           [{"masses[0].mass": x} for x in m], propeller=base, models=models,
                           **options)


# ----------------------------------------------------------------------------- §11.4 pivot / CG
#: Default shifts [m] of the pivot-length study (Tables 11.1–11.5 use −0.6 … +0.46)
PIVOT_SHIFTS = (-0.6, -0.4, -0.2, 0.0, 0.2, 0.4)


def pivot_length(variant: Literal["cg", "pivot", "cg+pivot"] = "pivot", shifts=PIVOT_SHIFTS, *,
                 propeller: Propeller | None = None,
                 models: Sequence[str] = ("wingtip", "isolated"), **options) -> StudyTable:
    """§11.4, Tables 11.1–11.6: critical speed against the propeller pivot/CG position.

    variant (positions from the wing mid-chord, positive aft, shifts s [m]):
      "cg"       — every point mass moves by s, the pivots stay (§11.4.1: s = −0.40 is Table
                   11.1 case 1, s = +0.46 case 2);
      "pivot"    — both pivots move to l_θ = l_ψ = base + s, the masses stay (§11.4.2, Table 11.3);
      "cg+pivot" — masses and pivots move together by s: the pivoting length is unchanged but
                   S_α,P, I_α,P, I_θα,P about the wing elastic axis change (§11.4.3, Table 11.5).
    Columns: shift [m], pivot_length e_θ = hub − l_θ [m] (signed, negative for a tractor),
    I_theta_P [kg m²], S_theta_P [kg m].
    """
    if variant not in ("cg", "pivot", "cg+pivot"):
        raise v.InputError(f"variant = {variant!r} is invalid: must be 'cg', 'pivot' or 'cg+pivot'")
    s = parameter_grid("shifts", shifts, "m")
    base = _base(propeller)
    points: list[dict[str, float]] = []
    for x in s:
        x = float(x)
        point = {}
        if variant in ("cg", "cg+pivot"):   # every point mass moves by x
            point["rotor.x"] = base.rotor.x + x
            point.update({f"masses[{i}].x": q.x + x for i, q in enumerate(base.masses)})
        if variant in ("pivot", "cg+pivot"):
            point.update({"pivot_pitch": base.pivot_pitch + x, "pivot_yaw": base.pivot_yaw + x})
        points.append(point)
    props = _variant_propellers(base, points)
    inertia = [p.pivot_inertia() for p in props]
    cols = {"shift": s, "pivot_length": np.array([p.e_theta for p in props]),
            "I_theta_P": np.array([i["I_theta_P"] for i in inertia]),
            "S_theta_P": np.array([i["S_theta_P"] for i in inertia])}
    return propeller_study(f"pivot length ({variant} moved)", "shift", "m", cols, points,
                           propeller=base, models=models,
                           parameter_units={"pivot_length": "m", "I_theta_P": "kg m^2", "S_theta_P": "kg m"},
                           **options)


# ----------------------------------------------------------------------------- §11.5 spin inertia
#: Default rotor masses [kg] (baseline 8 kg → I_Ω = 1.55 kg m²)
ROTOR_MASSES = (2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0)


def spin_inertia(rotor_masses=ROTOR_MASSES, *, propeller: Propeller | None = None,
                 models: Sequence[str] = ("wingtip", "isolated"), **options) -> StudyTable:
    """§11.5, Figure 11.14: critical speed against I_Ω, varied through the rotor mass M_r [kg].

    I_Ω = M_r R²/3 (eq. 9.2) with R fixed; the rotor mass also raises the pitch/yaw inertia
    parameters (as in the thesis).  A base propeller with a given `spin_inertia` is switched to
    eq. 9.2.  x-axis: I_Omega [kg m²]; the column rotor_mass [kg] gives the input.
    """
    m = parameter_grid("rotor masses", rotor_masses, "kg", v.positive)
    base = _base(propeller)
    base = replace(base, spin_inertia=None)   # I_Omega from eq. 9.2
    points = [{"rotor.mass": x} for x in m]
    props = _variant_propellers(base, points)
    return propeller_study("spin inertia (rotor mass)", "I_Omega", "kg m^2",
                           {"rotor_mass": m, "I_Omega": np.array([p.I_Omega for p in props])}, points,
                           propeller=base, models=models, parameter_units={"rotor_mass": "kg"},
                           **options)


# ----------------------------------------------------------------------------- §11.6 blade angle
#: Default blade angles β_0.75 [deg] (baseline 35°; the critical mode switches near 73.5°)
BLADE_ANGLES = (20.0, 30.0, 35.0, 40.0, 50.0, 60.0, 70.0, 73.0, 74.0, 78.0)


def blade_angle(betas=BLADE_ANGLES, *, propeller: Propeller | None = None,
                models: Sequence[str] = ("wingtip", "isolated"), **options) -> StudyTable:
    """§11.6, Figure 11.15: critical speed against the blade angle β_0.75 [deg].

    Fixed-pitch windmilling: the advance ratio follows from β (eq. 9.1 as printed,
    J = π tan(β − 3°)); the column advance_ratio gives J.  β must give an inflow angle in
    (0°, 90°).
    """
    b = parameter_grid("blade angles", betas, "deg")
    base = _base(propeller)
    if base.operation != "fixed-pitch":
        raise v.InputError("the blade-angle study needs a fixed-pitch propeller (operation='fixed-pitch')")
    points = [{"beta_075_deg": x} for x in b]
    props = _variant_propellers(base, points)  # validates each angle
    J = np.array([np.pi * p.advance_ratio for p in props])
    return propeller_study("blade angle", "beta_075_deg", "deg", {"beta_075_deg": b, "advance_ratio": J},
                           points, propeller=base, models=models, **options)


@dataclass(frozen=True)
class ModeSwitch(Result):
    """Blade angle [deg] where the wingtip model's critical whirl mode changes sense (§11.6).

    beta: the switch angle, midpoint of the final bracket (β_forward, β_backward) [deg];
    evaluations: (β, V_forward, V_backward) of every analysis, sorted by β [deg, m/s, m/s]
    (NaN: no flutter of that mode in the speed range).

    Mechanism: the flutter itself is continuous in β (≈160.7 m/s,
    10.6 Hz on both sides); what changes is which low-speed whirl mode continues into it.  The
    two whirl branches coalesce (an exceptional point) near V ≈ 97 m/s, f ≈ 6.9 Hz at the switch
    angle; on either side of it the branches exchange identity differently.
    """

    beta: float
    bracket: tuple[float, float]
    evaluations: tuple[tuple[float, float, float], ...]

    # A Result of kind "mode-switch" (format propwhirl.mode-switch/1): save / load, checked;
    # a speed that is NaN (no flutter of that mode) is saved as null.
    KIND: ClassVar[str] = "mode-switch"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "mode-switch file"

    def encode(self) -> dict[str, Any]:
        return {"beta_deg": float(self.beta), "bracket_deg": [float(b) for b in self.bracket],
                "evaluations": [{"beta_deg": float(b), "V_forward_m_per_s": _or_null(f),
                                 "V_backward_m_per_s": _or_null(w)}
                                for b, f, w in self.evaluations]}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "ModeSwitch":
        """bracket [lo, hi] [deg] with beta inside it; each evaluation's beta [deg] and the
        two flutter speeds [m/s] (> 0, or null: no flutter of that mode).  InputError naming
        the key."""
        r = SavedDict(d, where, ("beta_deg", "bracket_deg", "evaluations"))
        lo, hi = r.bracket("bracket_deg")
        beta = r.number("beta_deg")
        if not lo <= beta <= hi:
            raise v.InputError(f"{r.name('beta_deg')} = {beta!r} is invalid: must lie in "
                               f"bracket_deg [{lo!r}, {hi!r}]")
        evals = []
        for w, e in r.items("evaluations"):
            q = SavedDict(e, w, ("beta_deg", "V_forward_m_per_s", "V_backward_m_per_s"))
            speeds = [q.number_or_nan(k) for k in ("V_forward_m_per_s", "V_backward_m_per_s")]
            bad = [k for k, V in zip(("V_forward_m_per_s", "V_backward_m_per_s"), speeds)
                   if V <= 0]
            if bad:
                raise v.InputError(f"{q.name(bad[0])}: must be a speed > 0 m/s or null")
            evals.append((q.number("beta_deg"), *speeds))
        return cls(beta, (lo, hi), tuple(evals))


def _or_null(x: float) -> float | None:
    """x, or None (JSON null) where it is not finite (NaN: no flutter of that mode)."""
    return float(x) if math.isfinite(x) else None


def whirl_flutter_speeds(beta: float, propeller: Propeller | None = None, speeds=None,
                         xtol: float = 0.01, method: str = "auto") -> tuple[float, float]:
    """Flutter onset speeds [m/s] of "forward 1" and "backward 1" of the wingtip model at blade
    angle `beta` [deg] (NaN where that mode does not flutter in the speed range); method: the
    analysis's (:func:`propwhirl.analysis.stability.analyse`)."""
    base = _base(propeller)
    model = P.set_value(build_model("wingtip", base), PROPELLER_PATHS["wingtip"] + "beta_075_deg", beta)
    a = analyse(model, speeds, xtol=xtol, method=method, compressibility_check=False)
    fw, bw = a.first("forward 1", "flutter"), a.first("backward 1", "flutter")
    return (float("nan") if fw is None else fw.V), (float("nan") if bw is None else bw.V)


def blade_angle_mode_switch(bracket: tuple[float, float] = (60.0, 80.0), *, xtol: float = 0.1,
                            propeller: Propeller | None = None, speeds=None,
                            method: str = "auto") -> ModeSwitch:
    """§11.6: the β_0.75 at which the wingtip model's whirl flutter changes from the forward to
    the backward whirl mode (the thesis: between 73° and 74°).

    Root of g(β) = V_fw(β) − V_bw(β), the flutter onset speeds of "forward 1" and "backward 1"
    (a mode without flutter in the speed range counts as the range's upper end, so g jumps from
    negative to positive where the flutter changes mode).  Bracketing + bisection
    (scipy.optimize.brentq on the step function), one wingtip analysis per evaluation;
    `bracket` [deg] must have the forward-whirl flutter first at its lower end and the backward
    at its upper end; `xtol` [deg]; method: the analyses' (the reproduction's: "dense").

    Parameters
    ----------
    bracket : tuple of float
        (β_forward, β_backward) [deg].
    xtol : float
        Accuracy of the switch angle [deg].
    propeller : Propeller, optional
        The propeller (default the baseline).
    speeds : array_like, optional
        Initial speed grid [m/s] of the analyses.
    method : str
        The analyses' method.

    Returns
    -------
    ModeSwitch
        The switch angle ``beta`` [deg], its final ``bracket`` [deg] and every evaluation
        (β [deg], V_forward, V_backward [m/s]).

    Examples
    --------
    The thesis's bracket 73°–74°, to 0.5°:

    >>> from propwhirl.studies import blade_angle_mode_switch
    >>> s = blade_angle_mode_switch((73.0, 74.0), xtol=0.5)
    >>> round(s.beta, 1), len(s.evaluations)
    (73.4, 4)
    """
    from scipy.optimize import brentq

    lo, hi = (float(x) for x in v.increasing("bracket", bracket, "deg"))
    v.positive("xtol", xtol, "deg")
    top = 350.0 if speeds is None else float(np.max(speeds))
    evals: dict[float, tuple[float, float]] = {}

    def g(beta: float) -> float:
        beta = float(beta)
        if beta not in evals:  # brentq re-evaluates the bracket ends
            evals[beta] = whirl_flutter_speeds(beta, propeller, speeds, method=method)
        Vf, Vb = evals[beta]
        if math.isnan(Vf) and math.isnan(Vb):
            raise v.InputError(f"no whirl flutter of the wingtip model at beta = {beta:g} deg "
                               f"below {top:g} m/s: cannot locate the mode switch")
        return (top if math.isnan(Vf) else Vf) - (top if math.isnan(Vb) else Vb)

    g_lo, g_hi = g(lo), g(hi)
    if not (g_lo < 0 < g_hi):
        raise v.InputError(f"bracket = ({lo:g}, {hi:g}) deg is invalid: the flutter must be forward whirl "
                           f"at the lower end and backward whirl at the upper end "
                           f"(V_fw − V_bw = {g_lo:.4g}, {g_hi:.4g} m/s)")
    root = float(brentq(g, lo, hi, xtol=xtol))
    gap = {b: g(b) for b in evals}
    neg = max(b for b, d in gap.items() if d < 0 and b <= root)
    pos = min(b for b, d in gap.items() if d > 0 and b >= root)
    return ModeSwitch(0.5 * (neg + pos), (neg, pos), tuple((b, *evals[b]) for b in sorted(evals)))
