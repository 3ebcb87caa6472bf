"""Valid ranges of the physical fields (issue 9, item 1): declared once in the field metadata
(model/fields.spec(range=...)), enforced on construction with one-line errors naming the
field, the value, the range and the unit."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
from propwhirl.model.fields import META_KEY, Range
from propwhirl.model.flight import FlightCondition
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.propellers.propeller_aero import AeroSettings, Distribution, PropellerGeometry
from propwhirl.model.systems import Installation, TypicalSection
from propwhirl.model.structure.wing import Wing
from propwhirl.validate import InputError

FLIGHT = FlightCondition(1.0, 340.0)


# ----------------------------------------------------------------------------- the cases
@pytest.mark.parametrize("build, message", [
    (lambda: dataclasses.replace(baseline_wing(4), EI=1e300),
     "EI = 1e+300 N m^2 is outside the valid range [1e-3, 1e12] N m^2"),
    (lambda: dataclasses.replace(baseline_wing(4), GJ=1e300),
     "GJ = 1e+300 N m^2 is outside the valid range [1e-3, 1e12] N m^2"),
    (lambda: dataclasses.replace(baseline_wing(4), rayleigh=(1e300, 0.0)),
     "rayleigh[0] = 1e+300 1/s is outside the valid range [0, 1000] 1/s"),
    (lambda: dataclasses.replace(baseline_wing(4), semi_span=1e300),
     "semi_span = 1e+300 m is outside the valid range [0.01, 1000] m"),
    (lambda: baseline_propeller(damping_theta=1e300),
     "damping_theta = 1e+300 is outside the valid range [0, 2]"),
    (lambda: baseline_propeller(damping_psi=1e300),
     "damping_psi = 1e+300 is outside the valid range [0, 2]"),
    (lambda: baseline_propeller(spin_inertia=1e300),
     "spin_inertia = 1e+300 kg m^2 is outside the valid range [0, 1e6] kg m^2"),
    (lambda: baseline_propeller(f_theta=1e300),
     "f_theta = 1e+300 Hz is outside the valid range [1e-3, 1000] Hz"),
    (lambda: baseline_propeller(f_psi=1e300),
     "f_psi = 1e+300 Hz is outside the valid range [1e-3, 1000] Hz"),
    (lambda: baseline_propeller(radius=1e300),
     "radius = 1e+300 m is outside the valid range [0.01, 20] m"),
    (lambda: baseline_propeller(blade_chord=1e300),
     "blade_chord = 1e+300 m is outside the valid range [1e-3, 5] m"),
    (lambda: baseline_propeller(rotor=PointMass(1e300, -1.16)),
     "mass = 1e+300 kg is outside the valid range [1e-4, 1e5] kg"),
    (lambda: baseline_propeller(n_blades=100), "n_blades = 100 is outside the valid range [3, 20]"),
    (lambda: dataclasses.replace(baseline_wing(4), lift_slope=0.0),
     "lift_slope = 0.0 1/rad is outside the valid range (0, 12.5664] 1/rad"),
    (lambda: FlightCondition(1.0, 50.0),
     "speed_of_sound = 50.0 m/s is outside the valid range [100, 1000] m/s"),
])
def test_huge_and_absurd_values_fail_at_construction_with_the_range(build, message):
    with pytest.raises(InputError) as exc:
        build()
    assert str(exc.value) == message
    assert "\n" not in str(exc.value)


def test_every_value_of_an_array_or_function_is_checked():
    w = baseline_wing(4)
    with pytest.raises(InputError, match=r"^EI = 1e\+300 N m\^2 is outside"):
        dataclasses.replace(w, EI=[7e5, 7e5, 1e300, 7e5])
    with pytest.raises(InputError, match=r"^GJ\(y = 4\.9875 m\) = 1e\+300 N m\^2 is outside"):
        dataclasses.replace(w, GJ=lambda y: np.where(y > 4.0, 1e300, 2e5))
    with pytest.raises(InputError, match=r"^chord\(y = .* m\) = 500\.0 m is outside"):
        dataclasses.replace(w, chord=lambda y: 500.0 + 0 * y)
    with pytest.raises(InputError, match=r"chord = 1e\+300 m is outside"):
        baseline_propeller(blade_chord=Distribution.tabulated([0.0, 1.0], [0.1, 1e300]))
    with pytest.raises(InputError, match=r"chord\(eta = 0\.992\) = 1e\+300 m is outside"):
        PropellerGeometry(4, 1.0, 0.2, lambda e: np.where(e > 0.99, 1e300, 0.1))
    with pytest.raises(InputError, match=r"inertia\['I_theta_P'\] = 1e\+300 kg m\^2 is outside"):
        baseline_propeller(inertia={"I_theta_P": 1e300})
    with pytest.raises(InputError, match=r"values\['CZ_q'\] = 1e\+300 is outside"):
        MeasuredDerivatives({"CZ_q": 1e300})
    with pytest.raises(InputError, match=r"speed_range\[1\] = 1e\+300 m/s is outside"):
        FlightCondition(1.0, 340.0, (1.0, 1e300, 10.0))


def test_errors_carry_the_field_path_for_file_readers():
    with pytest.raises(InputError) as exc:
        baseline_propeller(inertia={"M_P": -1.0})
    assert exc.value.path == ("inertia", "M_P") and exc.value.value == -1.0
    assert exc.value.reason == "outside the valid range [1e-4, 1e5] kg"


def test_every_thesis_case_constructs():
    from propwhirl.cases.ch06_isolated import bennett_bland_propeller
    from propwhirl.cases.registry import CASES

    for name in CASES:
        assert CASES[name].model() is not None, name
    for case in range(1, 14):  # Tables 6.1/6.2
        assert bennett_bland_propeller(case) is not None


# ----------------------------------------------------------------------------- all ranges
def _base(cls):
    return {
        Wing: lambda: baseline_wing(4),
        Propeller: baseline_propeller,
        PointMass: lambda: PointMass(8.0, -1.16),
        FlightCondition: lambda: FlightCondition(1.0, 340.0),
        Installation: lambda: Installation(baseline_propeller(), 2.0),
        PropellerGeometry: lambda: PropellerGeometry(4, 1.0, 0.2, 0.1),
        AeroSettings: AeroSettings,
        TypicalSection: lambda: TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=10.0,
                                               omega_h=5.0, omega_alpha=10.0, flight=FLIGHT),
        MeasuredDerivatives: lambda: MeasuredDerivatives({}),
    }[cls]()


CLASSES = (Wing, Propeller, PointMass, FlightCondition, Installation, PropellerGeometry,
           AeroSettings, TypicalSection, MeasuredDerivatives)


def _ranged():
    """(class, field, sub, Range) of every declared range (split entries, mapping entries)."""
    out = []
    for cls in CLASSES:
        for f in dataclasses.fields(cls):
            s = f.metadata.get(META_KEY)
            if s is None:
                continue
            if isinstance(s.range, tuple):
                out += [(cls, f.name, i, r) for i, r in enumerate(s.range)]
            elif s.form == "numbers":
                out += [(cls, f.name, i, s.range) for i in range(s.length or 1)]
            elif s.range is not None:
                out.append((cls, f.name, None, s.range))
            out += [(cls, f.name, e.name, e.range) for e in s.entries if e.range is not None]
    return out


RANGED = _ranged()


def test_every_physical_field_has_a_range():
    names = {(c.__name__, n) for c, n, _, _ in RANGED}
    for cls in CLASSES:
        for f in dataclasses.fields(cls):
            s = f.metadata.get(META_KEY)
            hint = str(f.type)
            numeric = any(t in hint for t in ("float", "Spanwise", "LiftSlope", "Mapping[str, float]"))
            if s is not None and numeric and s.unit != "" or f.name in ("n_blades",):
                assert (cls.__name__, f.name) in names, (cls.__name__, f.name)
    assert len(RANGED) >= 60


def _build(cls, name, sub, value):
    obj = _base(cls)
    if sub is not None and isinstance(sub, int):  # a "split" or "numbers" entry
        seq = list(getattr(obj, name) or (None,))  # a list of any length: one entry
        seq[sub] = value
        value = tuple(seq)
    elif sub is not None:  # a mapping entry
        value = {sub: value}
    changes = {name: value}
    if cls is Wing and name == "polar_inertia":
        changes["radius_of_gyration"] = None
    if cls is Wing and name == "chord":
        changes[name] = lambda y, c=value: c + 0 * y
    if cls is Propeller and name in ("K_theta", "K_psi"):
        changes["f" + name[1:]] = None
    if cls is Propeller and name == "rpm":
        changes["operation"] = "constant-speed"
    if (cls, name) in ((PropellerGeometry, "lift_slope"),):
        changes[name] = Distribution.constant(value)
    return dataclasses.replace(obj, **changes) if dataclasses.is_dataclass(obj) else None


class _Refused(dict):
    def __missing__(self, key):
        return "outside the valid range"


#: A Distribution refuses values <= 0 itself (before the geometry checks its range).
_REFUSED = _Refused({(PropellerGeometry, "lift_slope"): "outside the valid range|must be > 0"})


def _beyond(r: Range, end: str, factor: float) -> float:
    if end == "high":
        return r.high * factor if r.high > 0 else r.high + factor
    if r.low > 0:
        return r.low / factor
    return r.low * factor if r.low < 0 else -factor * 1e-3


@settings(max_examples=150, deadline=None)
@given(case=st.sampled_from(RANGED), end=st.sampled_from(["low", "high"]),
       factor=st.floats(10.0, 1e6))
def test_values_ten_times_beyond_the_range_are_refused(case, end, factor):
    cls, name, sub, r = case
    value = _beyond(r, end, factor)
    if isinstance(r.low, float) and float(r.low).is_integer() and name == "n_blades":
        value = int(round(value)) if abs(value) < 1e9 else 10**9
    with pytest.raises(InputError, match=_REFUSED[(cls, name)]) as exc:
        _build(cls, name, sub, value)
    assert str(r) in str(exc.value) or (cls, name) in _REFUSED


@pytest.mark.parametrize("case", RANGED, ids=[f"{c.__name__}.{n}{'' if s is None else f'[{s}]'}"
                                              for c, n, s, _ in RANGED])
def test_range_ends_are_accepted_or_refused_as_declared(case):
    cls, name, sub, r = case
    for end, bracket in ((r.low, r.ends[0]), (r.high, r.ends[1])):
        value = int(end) if name == "n_blades" else end
        if bracket in "()":
            with pytest.raises(InputError, match=_REFUSED[(cls, name)]):
                _build(cls, name, sub, value)
            inside = value + (1e-9 * max(1.0, abs(value))) * (1 if bracket == "(" else -1)
            value = inside
        try:
            _build(cls, name, sub, value)
        except InputError as exc:  # a cross-field check may refuse it, never the range
            assert "outside the valid range" not in str(exc), (name, value, str(exc))
