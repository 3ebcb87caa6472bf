"""The cases of a clearance campaign: :class:`Case`, a named transformation of the model (mount
stiffness and damping factors, the wing's structural damping, windmilling, feathered or stopped
rotors, overspeed, reversed rotation, added masses, any parameter path of
:mod:`propwhirl.studies.paths`) on the chosen propellers, whether it is a failure condition of
CS/14 CFR 25.629(d) (:data:`FAILURE_KINDS`), and :func:`product`, the combinations of groups of
cases.  The campaign that runs them is :mod:`propwhirl.studies.campaign` (which re-exports
these names)."""
from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from propwhirl import validate as v
from propwhirl.certification import CASE_FACTORS, OPERATIONS, STATES
from propwhirl.model.propellers.propeller import PointMass
from propwhirl.studies import paths as P


#: The transformations that make a case a failure condition of 25.629(d) unless it says
#: ``failure = false`` (:attr:`Case.is_failure`), with the paragraph of 25.629(d).
FAILURE_KINDS = ("mount_stiffness < 1: (d)(4), (d)(5)", "mount_damping < 1: (d)(2)",
                 "state feathered or stopped: (d)(6)", "rpm_factor > 1: (d)(7)")


# ============================================================================== cases
def _number_in(case: str, key: str, x: Any, low: float, high: float) -> None:
    """`x` a finite real number in [low, high] (a plain int or float checked at once, as the
    many cases of a product are; anything else by :func:`propwhirl.validate.in_range`, whose
    error names the case and `key`)."""
    if type(x) in (float, int) and low <= x <= high:
        return
    name = f"case {case!r}: {key}"
    v.in_range(name, x, low, high)
    if not v.is_finite_number(x):                  # an array or list: one number
        raise v.fail(name, x, f"invalid: must be one number in [{low:g}, {high:g}], got "
                     f"{type(x).__name__}")


def _sequence(case: str, key: str, x: Any, what: str) -> tuple:
    """`x` (a tuple or list) as a tuple; anything else (a mapping, a string, None ...) is an
    InputError naming the case and `key`."""
    if isinstance(x, tuple):
        return x
    if isinstance(x, list):
        return tuple(x)
    raise v.fail(f"case {case!r}: {key}", x, f"invalid: must be a tuple of {what}, got "
                 f"{type(x).__name__}")


def _pair(case: str, key: str, x: Any, j: int, what: str, text: bool = False) -> tuple:
    """Entry `j` of `key`: a pair (number, number), or with `text` (non-empty str, number)."""
    ok = isinstance(x, (tuple, list)) and len(x) == 2 and v.is_finite_number(x[1]) and (
        isinstance(x[0], str) and bool(x[0].strip()) if text else v.is_finite_number(x[0]))
    if not ok:
        raise v.fail(f"case {case!r}: {key}[{j}]", x, f"invalid: must be a pair {what} of "
                     + ("a path and a finite number" if text else "finite numbers"))
    return (x[0] if text else float(x[0]), float(x[1]))


@dataclass(frozen=True)
class Case:
    """A named model transformation (one failure case of a campaign).

    name:             the case's name in the report (unique in a campaign);
    propellers:       the propellers the propeller transformations act on, numbered from 1
                      (empty: every propeller);
    mount_stiffness:  factor on the pitch and yaw mount stiffness K_θ, K_ψ [-] (a frequency
                      f_θ, f_ψ given instead is multiplied by its square root);
    mount_damping:    factor on the mount damping (damping_theta, damping_psi) [-] (0: a failed
                      damper);
    wing_damping:     factor on the wing's Rayleigh structural damping (μ, λ) [-];
    operation:        "windmilling": a constant-speed propeller switched to fixed-pitch
                      windmilling (its blade angle kept); "" keeps the operation;
    state:            the installations' state (:data:`STATES`): "feathered" (Ω = 0, the
                      feathered blades' side forces), "stopped" (Ω = 0, no propeller
                      aerodynamics), "operating"; "" keeps each installation's;
    rpm_factor:       overspeed: the rpm of constant-speed propellers times this [-];
    reverse_rotation: the sense of rotation reversed (the installation's ``rotation``, so
                      propellers sharing a table are reversed one by one);
    added_masses:     (mass [kg], x [m]) point masses added on each chosen propeller's shaft
                      (a battery or a tank in the nacelle);
    values:           (parameter path, value) pairs set on the model
                      (:func:`propwhirl.studies.paths.set_values`), after the rest;
    failure:          a failure, malfunction or adverse condition of 25.629(d), held to the
                      failure-case envelope of 25.629(b)(2) under "cs25"/"far25"
                      (:meth:`Campaign.required_speed`); None (default): :attr:`is_failure`
                      decides from the transformation (:data:`FAILURE_KINDS`).

    Parameters
    ----------
    name : str
        The case's name in the report (unique in a campaign).
    propellers : tuple of int
        The propellers the propeller transformations act on, numbered from 1 (empty: every
        propeller).
    mount_stiffness : float
        Factor [-] on the pitch and yaw mount stiffness K_θ, K_ψ (a frequency f_θ, f_ψ given
        instead is multiplied by its square root).
    mount_damping : float
        Factor [-] on the mount damping (0: a failed damper).
    wing_damping : float
        Factor [-] on the wing's Rayleigh structural damping (μ, λ).
    operation : {"", "windmilling"}
        "windmilling": a constant-speed propeller switched to fixed-pitch windmilling; ""
        keeps the operation.
    rpm_factor : float
        Overspeed: the rpm of constant-speed propellers times this [-].
    reverse_rotation : bool
        The sense of rotation reversed.
    added_masses : tuple of (float, float)
        (mass [kg], x [m]) point masses added on each chosen propeller's shaft.
    values : tuple of (str, float)
        (parameter path, value [its unit]) pairs set on the model, after the rest.
    state : {"", "operating", "feathered", "stopped"}
        The installations' state; "" keeps each installation's.
    failure : bool, optional
        A failure case of 25.629(d) (held to 25.629(b)(2)); None: decided from the
        transformation.

    Examples
    --------
    >>> from propwhirl.studies import Case
    >>> soft = Case("mounts at 50 %", mount_stiffness=0.5)
    >>> soft.is_failure, Case("nominal").is_failure
    (True, False)
    """

    name: str
    propellers: tuple[int, ...] = ()
    mount_stiffness: float = 1.0
    mount_damping: float = 1.0
    wing_damping: float = 1.0
    operation: str = ""
    rpm_factor: float = 1.0
    reverse_rotation: bool = False
    added_masses: tuple[tuple[float, float], ...] = ()
    values: tuple[tuple[str, float], ...] = ()
    state: str = ""
    failure: bool | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip() or not self.name.isprintable():
            raise v.InputError(f"case name = {v.short_repr(self.name)} is invalid: must be a "
                               "non-empty printable string")
        name = self.name            # the checks cheap when all is well: a product has many
        props = _sequence(name, "propellers", self.propellers,
                          "propeller numbers from 1, e.g. (1, 2)")
        for i in props:
            if type(i) is not int or i < 1:
                v.integer_at_least(f"case {name!r}: propellers", i, 1)
        masses = _sequence(name, "added_masses", self.added_masses,
                           "(mass [kg], x [m]) pairs, e.g. ((20.0, -0.5),)")
        masses = tuple(_pair(name, "added_masses", m, j, "(mass [kg], x [m])")
                       for j, m in enumerate(masses)) if masses else masses
        values = _sequence(name, "values", self.values,
                           "(parameter path, value) pairs, e.g. (('wing.EI*', 0.9),)")
        values = tuple(_pair(name, "values", x, j, "(parameter path, value)", text=True)
                       for j, x in enumerate(values)) if values else values
        for key, x in (("propellers", props), ("added_masses", masses), ("values", values)):
            if x is not getattr(self, key):
                object.__setattr__(self, key, x)
        for key, (low, high) in CASE_FACTORS.items():
            _number_in(name, key, getattr(self, key), low, high)
        if not isinstance(self.reverse_rotation, bool):
            raise v.fail(f"case {name!r}: reverse_rotation", self.reverse_rotation, "invalid: "
                         f"must be True or False, got {type(self.reverse_rotation).__name__}")
        if not (isinstance(self.operation, str) and self.operation in ("", *OPERATIONS)):
            raise v.InputError(f"case {name!r}: operation = {v.short_repr(self.operation)} is "
                               f"invalid: must be one of {', '.join(OPERATIONS)} (feathered or "
                               "stopped rotors: state)")
        if not (isinstance(self.state, str) and self.state in ("", *STATES)):
            raise v.InputError(f"case {name!r}: state = {v.short_repr(self.state)} is invalid: "
                               f"must be one of {', '.join(STATES)}")
        if self.failure is not None and not isinstance(self.failure, bool):
            raise v.InputError(f"case {name!r}: failure = {v.short_repr(self.failure)} is "
                               "invalid: must be true or false")

    @property
    def is_failure(self) -> bool:
        """Whether the case is a failure condition of 25.629(d) (held to 25.629(b)(2)): its
        `failure` when given, else whether it is one of the :data:`FAILURE_KINDS` — a mount
        degraded (mount_stiffness < 1), a damper degraded or failed (mount_damping < 1), a
        feathered or stopped rotor, overspeed (rpm_factor > 1)."""
        if self.failure is not None:
            return self.failure
        return (self.mount_stiffness < 1.0 or self.mount_damping < 1.0
                or self.state in ("feathered", "stopped") or self.rpm_factor > 1.0)

    def describe(self) -> str:
        """The transformation in words ("nominal" when it changes nothing)."""
        on = ("" if not self.propellers else
              " on propeller" + "s" * (len(self.propellers) > 1) + " "
              + ", ".join(str(i) for i in self.propellers))
        parts = []
        if self.mount_stiffness != 1.0:
            parts.append(f"mount stiffness x {self.mount_stiffness:g}{on}")
        if self.mount_damping != 1.0:
            parts.append(f"mount damping x {self.mount_damping:g}{on}")
        if self.wing_damping != 1.0:
            parts.append(f"wing structural damping x {self.wing_damping:g}")
        if self.operation:
            parts.append(f"{self.operation}{on}")
        if self.state:
            parts.append(f"{self.state}{on}")
        if self.rpm_factor != 1.0:
            parts.append(f"rpm x {self.rpm_factor:g}{on}")
        if self.reverse_rotation:
            parts.append(f"rotation reversed{on}")
        for m, x in self.added_masses:
            parts.append(f"+{m:g} kg at x = {x:g} m{on}")
        for path, value in self.values:
            parts.append(f"{path} = {value:g}")
        return "; ".join(parts) or "nominal"

    def combine(self, other: "Case") -> "Case":
        """This case followed by `other` (a product of cases): the names joined with " + ",
        the factors multiplied, the masses and values appended, a failure when either is; the
        two must act on the same propellers when both transform propellers."""
        if self.propellers != other.propellers and _acts_on_propellers(self) \
                and _acts_on_propellers(other):
            raise v.InputError(f"cases {self.name!r} and {other.name!r} cannot be combined: they "
                               "transform different propellers (give them the same propellers)")
        props = self.propellers if _acts_on_propellers(self) else other.propellers
        return Case(f"{self.name} + {other.name}", props,
                    self.mount_stiffness * other.mount_stiffness,
                    self.mount_damping * other.mount_damping,
                    self.wing_damping * other.wing_damping,
                    other.operation or self.operation, self.rpm_factor * other.rpm_factor,
                    self.reverse_rotation != other.reverse_rotation,
                    self.added_masses + other.added_masses, self.values + other.values,
                    other.state or self.state,
                    None if self.failure is None and other.failure is None
                    else self.is_failure or other.is_failure)

    def apply(self, model: Any) -> Any:
        """The model transformed (every change checked by the model's own validation; an error
        names the case)."""
        try:
            return self._apply(model)
        except v.InputError as exc:
            raise v.InputError(f"case {self.name!r}: {exc}") from None

    def check(self, model: Any) -> None:
        """What :meth:`apply` refuses without building a model — a propeller the model does
        not have, overspeed of a propeller that is not constant-speed (one switched to
        windmilling too) — as its one-line error; the rest (the model's own ranges) only
        :meth:`apply` finds."""
        try:
            for i in self._chosen(model):
                if self.rpm_factor != 1.0:
                    prop = model.propellers[i].propeller
                    self._check_overspeed(i, "fixed-pitch" if self.operation == "windmilling"
                                          else prop.operation)
        except v.InputError as exc:
            raise v.InputError(f"case {self.name!r}: {exc}") from None

    def _chosen(self, model: Any) -> list[int]:
        """The indices (from 0) of the installations the case transforms."""
        installs = getattr(model, "propellers", None)
        if not isinstance(installs, tuple):
            raise v.InputError("a campaign needs a propeller-wing model (a wing with propellers)")
        n = len(installs)
        for i in self.propellers:
            if i > n:
                raise v.InputError(f"propellers = {list(self.propellers)} is invalid: the model "
                                   f"has {n} propeller{'s' * (n != 1)} (numbered 1 to {n})")
        return [i - 1 for i in self.propellers] or list(range(n))

    def _check_overspeed(self, i: int, operation: str) -> None:
        if operation != "constant-speed":
            raise v.InputError(f"rpm_factor = {self.rpm_factor:g} is invalid for propeller "
                               f"{i + 1}: it is a fixed-pitch windmilling propeller, whose "
                               "rpm follows the airspeed (overspeed needs operation = "
                               "'constant-speed')")

    def _apply(self, model: Any) -> Any:
        # each changed object rebuilt once (its own validation runs): the propellers' mounts,
        # operation, rpm and masses in one Propeller, then the installations, the wing's
        # damping and the model in one PropellerWing; the parameter paths after the rest
        chosen = self._chosen(model)
        new = list(model.propellers)
        for i in chosen:
            inst = new[i]
            mount = getattr(inst, "mount", "flexible")
            if mount != "flexible" and (self.mount_stiffness != 1.0 or self.mount_damping != 1.0):
                raise v.InputError(f"mount factors are invalid for propeller {i + 1}: its mount "
                                   f"is {mount!r} (no pitch and yaw springs of its own"
                                   + ("; a modal model's on-grid mount is in the modes)"
                                      if mount == "on-grid" else ")"))
            if self.state and not hasattr(inst, "state"):
                raise v.InputError(f"state = {self.state!r} is invalid for propeller "
                                   f"{i + 1}: a modal model's installations turn always "
                                   "(no stopped or feathered state)")
            changes: dict[str, Any] = {}
            prop = self._propeller(inst.propeller, i)
            if self.reverse_rotation and not hasattr(inst, "sense"):   # a modal model's
                prop = dataclasses.replace(prop, rotation=-int(prop.rotation))   # propeller's own
            if prop is not inst.propeller:
                changes["propeller"] = prop
            if self.reverse_rotation and hasattr(inst, "sense"):   # the installation's sense,
                changes["rotation"] = -int(inst.sense)              # not the shared table
            if self.state:
                changes["state"] = self.state
            if changes:
                new[i] = dataclasses.replace(inst, **changes)
        changes = {}
        if any(a is not b for a, b in zip(new, model.propellers)):
            changes["propellers"] = tuple(new)
        if self.wing_damping != 1.0 and hasattr(model, "wing"):
            mu, lam = model.wing.rayleigh
            changes["wing"] = dataclasses.replace(model.wing, rayleigh=(
                self.wing_damping * float(mu), self.wing_damping * float(lam)))
        elif self.wing_damping != 1.0:     # a modal structure: each mode's damping ratio (the
            # same factor as on a beam's Rayleigh μ, λ: ζ_i = (μ/ω_i + λ ω_i)/2 is linear in them)
            s = model.structure
            changes["structure"] = dataclasses.replace(
                s, damping_ratio=self.wing_damping * np.asarray(s.damping_ratio, dtype=float))
        if changes:
            model = dataclasses.replace(model, **changes)
        if self.values:
            model = P.set_values(model, dict(self.values))
        return model

    def _propeller(self, prop: Any, i: int) -> Any:
        """Propeller `i` (from 0) transformed: its mounts, operation, rpm and masses (the
        propeller itself when nothing changes)."""

        changes: dict[str, Any] = {}
        if self.mount_stiffness != 1.0:     # K x factor, or f x sqrt(factor) where f is given
            for f, k in (("f_theta", "K_theta"), ("f_psi", "K_psi")):
                if getattr(prop, k, None) is not None:
                    changes[k] = float(getattr(prop, k)) * self.mount_stiffness
                else:
                    changes[f] = float(getattr(prop, f)) * math.sqrt(self.mount_stiffness)
        if self.mount_damping != 1.0:
            for k in ("damping_theta", "damping_psi"):
                changes[k] = self.mount_damping * float(getattr(prop, k))
        if self.operation == "windmilling" and prop.operation != "fixed-pitch":
            changes.update(operation="fixed-pitch", rpm=None)
        if self.rpm_factor != 1.0:
            self._check_overspeed(i, changes.get("operation") or prop.operation)
            changes["rpm"] = float(prop.rpm) * self.rpm_factor
        if self.added_masses:
            changes["masses"] = tuple(prop.masses) + tuple(PointMass(m, x)
                                                           for m, x in self.added_masses)
        if not changes:
            return prop
        try:
            return dataclasses.replace(prop, **changes)
        except v.InputError as exc:
            raise v.InputError(f"propeller {i + 1}: {exc}") from None


def _acts_on_propellers(c: Case) -> bool:
    return (c.mount_stiffness != 1.0 or c.mount_damping != 1.0 or bool(c.operation)
            or c.rpm_factor != 1.0 or c.reverse_rotation or bool(c.added_masses)
            or bool(c.state))


def product(groups: Sequence[Sequence[Case]]) -> tuple[Case, ...]:
    """Every combination of one case from each group (:meth:`Case.combine`), in order."""
    out = []
    for combo in itertools.product(*groups):
        c = combo[0]
        for other in combo[1:]:
            c = c.combine(other)
        out.append(c)
    return tuple(out)
