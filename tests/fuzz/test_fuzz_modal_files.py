"""Fuzz: modal-model files (propwhirl.io.modal_files, issue 22) — an entry of one of the
``.npz`` arrays replaced by a value of any size (issue 33, item 10: ``frequencies_hz[9] =
1e300`` printed numpy's overflow warning before the one-line error), and the TOML description
mutated as the model files are: the file read, or one InputError line naming it; then the
model's state matrix at two speeds finite, or one InputError line — never a warning."""
from __future__ import annotations

import dataclasses
import tomllib

import numpy as np
import pytest
import tomli_w
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from fuzz.test_fuzz_model_files import mutate
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io.modal_files import load_modal_model, write_modes

ARRAYS = ("xyz", "frequencies_hz", "modal_mass", "damping_ratio", "shapes")
EXTREMES = [0.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, 1e308, 1e200, 1e154, 1e100, 1e30, 1e24,
            2e24, 1e15, 1e-9, float("inf"), float("nan")]
NUMBER = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(EXTREMES),
                   st.floats(-1e3, 1e3))


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """A small modal model (the wingtip wing of 4 elements): its TOML text and arrays."""
    m = wingtip_propeller_wing()
    m = m.with_(wing=dataclasses.replace(m.wing, n_elements=4))
    toml, npz = write_modes(m, tmp_path_factory.mktemp("modal") / "w.toml")
    with np.load(npz, allow_pickle=False) as f:
        arrays = {k: f[k] for k in f.files}
    return toml.read_text(), arrays


def _check(toml, category: str) -> None:
    """The file read (an error names it), then its model's state matrix at two speeds (an
    error of the model: one line)."""
    model = None
    with held_to_the_rule(f"{category}: read", str(toml)):
        model = load_modal_model(toml)
    if model is not None:
        with held_to_the_rule(f"{category}: state matrix"):
            assert np.isfinite(model.state_matrix(np.array([10.0, 150.0]))).all()


@pytest.mark.parametrize("value", EXTREMES)
@pytest.mark.parametrize("key", ARRAYS)
def test_every_array_at_every_extreme(written, tmp_path, key, value):
    """Each array's entry 9 (of the flattened array) at each extreme value, systematically."""
    text, arrays = written
    changed = {k: a.copy() for k, a in arrays.items()}
    changed[key].flat[9] = value
    np.savez(tmp_path / "w.modes.npz", **changed)
    (tmp_path / "w.toml").write_text(text)
    _check(tmp_path / "w.toml", "modal: extremes")


@FUZZ
@given(data=st.data())
def test_an_array_entry_of_any_value(written, tmp_path_factory, data):
    text, arrays = written
    folder = tmp_path_factory.mktemp("case")
    changed = {k: a.copy() for k, a in arrays.items()}
    for _ in range(data.draw(st.integers(1, 2), label="entries")):
        key = data.draw(st.sampled_from(ARRAYS), label="array")
        i = data.draw(st.integers(0, changed[key].size - 1), label="index")
        changed[key].flat[i] = data.draw(NUMBER, label="value")
    np.savez(folder / "w.modes.npz", **changed)
    (folder / "w.toml").write_text(text)
    _check(folder / "w.toml", "modal: array entries")


@FUZZ
@given(data=st.data())
def test_mutated_description(written, tmp_path_factory, data):
    text, arrays = written
    folder = tmp_path_factory.mktemp("case")
    np.savez(folder / "w.modes.npz", **arrays)
    doc = tomllib.loads(text)
    mutate(doc, data, ("scaled", "value", "delete", "unknown"))
    try:
        (folder / "w.toml").write_text(tomli_w.dumps(doc))
    except (TypeError, ValueError):                  # a value TOML cannot hold
        return
    _check(folder / "w.toml", "modal: mutated description")
