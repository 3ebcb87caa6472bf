"""One model, one set of rules (issue 25, item 6): a Python Propeller must be given the values
a model file must give — pivots, rotation; the blade geometry for Houbolt–Reed derivatives; the
blade angles for fixed pitch — and one one-line InputError names every missing one."""
from __future__ import annotations

import dataclasses

import pytest

from propwhirl.io import schema
from propwhirl.model.propellers.propeller import REQUIRED, MeasuredDerivatives, PointMass, Propeller
from propwhirl.validate import InputError

#: A fixed-pitch propeller with Houbolt-Reed derivatives, every required value given.
FULL = dict(radius=0.762, rotor=PointMass(8.0, -1.16), f_theta=7.0, f_psi=7.0,
            pivot_pitch=0.0, pivot_yaw=0.0, rotation=1, n_blades=3, hub_radius=0.125,
            blade_chord=0.094, beta_075_deg=35.0, zero_lift_angle_deg=-3.0)


def _without(*names, **changes):
    return {**{k: x for k, x in FULL.items() if k not in names}, **changes}


def test_the_python_class_requires_what_the_file_requires():
    file = {f.name: f.required_when for f in schema.fields_of(Propeller)
            if f.name in REQUIRED or f.required_when or (f.required and f.default is not
                                                         dataclasses.MISSING)}
    assert file == REQUIRED


@pytest.mark.parametrize("name", sorted(REQUIRED))
def test_each_missing_value_is_a_one_line_error_naming_it(name):
    with pytest.raises(InputError) as exc:
        Propeller(**_without(name))
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith(f"Propeller: missing {name} (")
    assert "a value of the aircraft has no default" in msg


def test_every_missing_value_is_named_at_once():
    """The older script of the issue: it built a propeller with pivots 0, rotation +1,
    beta 35 deg and alpha_0L -3 deg that its file did not have."""
    with pytest.raises(InputError) as exc:
        Propeller(radius=0.762, rotor=PointMass(8.0, -1.16), f_theta=7.0, f_psi=7.0,
                  blade_chord=0.094, hub_radius=0.125, n_blades=3)
    msg = str(exc.value)
    assert "\n" not in msg
    for name in ("pivot_pitch", "pivot_yaw", "rotation", "beta_075_deg", "zero_lift_angle_deg"):
        assert f"{name} (" in msg
    assert "n_blades (" not in msg and "hub_radius (" not in msg


def test_values_are_required_only_where_they_are_used():
    cs = Propeller(**_without("beta_075_deg", "zero_lift_angle_deg", operation="constant-speed",
                              rpm=2000.0))
    assert cs.beta_075_deg is None and cs.rotational_speed([100.0])[0] == pytest.approx(
        2000.0 * 3.141592653589793 / 30.0)
    measured = Propeller(**_without("n_blades", "hub_radius", "blade_chord",
                                    derivatives=MeasuredDerivatives({"CZ_theta": -3.0})))
    assert measured.n_blades is None and measured.hub_radius is None
    assert Propeller(**FULL).advance_ratio > 0
