"""The modal model's Python constructors (ModalPropellerWing, ModalInstallation, ModalStructure,
StripPlanform) refuse a value of a wrong type with a one-line InputError, as the beam model's
do (tests/model/test_fields_coercion.py): never an AttributeError or TypeError from inside,
and never a complex or boolean array cast to real numbers silently."""
from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pytest

from propwhirl import InputError
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io.modal_files import load_modal_model, write_modes

AWKWARD = (np.array([[1.0, 2.0]]), np.array(["a"]), np.array([]), np.bool_(True),
           np.complex128(1 + 2j), (), [], {}, b"x", float("nan"), object(), None, "x", -1, 0)


@pytest.fixture(scope="module")
def parts(tmp_path_factory):
    m = load_modal_model(write_modes(wingtip_propeller_wing(),
                                     tmp_path_factory.mktemp("m") / "w.toml")[0])
    return {"model": m, "structure": m.structure, "installation": m.propellers[0],
            "planform": m.planform}


@pytest.mark.parametrize("part", ["model", "structure", "installation", "planform"])
def test_every_field_takes_awkward_values_cleanly(parts, part):
    obj = parts[part]
    cls = type(obj)
    base = {f.name: getattr(obj, f.name) for f in dataclasses.fields(cls) if f.init}
    for f in dataclasses.fields(cls):
        if not f.init:
            continue
        for value in AWKWARD:
            with warnings.catch_warnings():
                warnings.simplefilter("error")         # a cast that warns is a silent change
                try:
                    cls(**{**base, f.name: value})
                except InputError as exc:
                    assert "\n" not in str(exc) and len(str(exc)) < 600, (f.name, value)


@pytest.mark.parametrize("key", ["frequencies_hz", "modal_mass", "damping_ratio", "xyz",
                                 "shapes"])
@pytest.mark.parametrize("kind", [complex, bool])
def test_a_complex_or_boolean_array_is_refused_by_name(parts, key, kind):
    s = parts["structure"]
    base = {f.name: getattr(s, f.name) for f in dataclasses.fields(s) if f.init}
    with pytest.raises(InputError, match=f"{key} has dtype"):
        type(s)(**{**base, key: np.asarray(base[key]).astype(kind)})
