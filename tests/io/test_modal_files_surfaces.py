"""A modal model file's further lifting surfaces (issue 36, item 4): ``[[surfaces]]``, each a
tail's grids and strips, declared once (io/modal_files.SURFACE); old files load without it."""
from __future__ import annotations

import numpy as np
import pytest

from helpers.op2_files import tailed_modal_model
from propwhirl import InputError
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io.modal_files import load_modal_model, save_modal_model, write_modes


@pytest.fixture(scope="module")
def tailed(tmp_path_factory):
    model, _ = tailed_modal_model(wingtip_propeller_wing(), 1e2)
    toml, _ = save_modal_model(model, tmp_path_factory.mktemp("tail") / "tail.toml")
    return model, toml


def test_a_free_model_with_a_tail_round_trips(tailed):
    model, toml = tailed
    text = toml.read_text()
    assert "[[surfaces]]" in text and 'name = "tail"' in text
    back = load_modal_model(toml)
    (a,), (b,) = model.surfaces, back.surfaces
    assert (b.name, b.grids) == (a.name, a.grids)
    for k in ("y", "width", "chord", "leading_edge_x", "elastic_axis", "aerodynamic_centre",
              "lift_slope"):
        np.testing.assert_array_equal(getattr(b.planform, k), getattr(a.planform, k))
    assert back.dof_map().w_labels == model.dof_map().w_labels
    # the refit of the rigid modes on reading rounds (1e-16 of the shapes): not bit for bit
    V = np.array([80.0])
    A, B = model.state_matrix(V), back.state_matrix(V)
    np.testing.assert_allclose(B, A, rtol=1e-9, atol=1e-9 * np.abs(A).max())


def test_old_files_load_with_the_wing_alone(tmp_path):
    toml, _ = write_modes(wingtip_propeller_wing(), tmp_path / "old.toml", n_modes=4)
    assert "surfaces" not in toml.read_text()
    assert load_modal_model(toml).surfaces == ()


def _set(key, value):
    def edit(doc):
        doc["surfaces"][0][key] = value
    return edit


@pytest.mark.parametrize("edit, words", [
    (_set("name", "strip"), r"\[surfaces\[0\]\] name = 'strip' is invalid"),
    (_set("grids", [1]), r"\[surfaces\[0\]\] grids = \[1\] is invalid: must be a list of two "
                         r"or more grid ids"),
    (_set("grids", [99999, 1]), r"surfaces\[0\]\.grids\[0\] = 99999 is not a grid"),
    (_set("chord_m", [0.7]), r"\[surfaces\[0\]\] chord_m = \[0\.7\] is invalid: .*a list of "
                             r"6 numbers \(one per strip"),
    (_set("span", 3.0), r"unknown key 'span' in \[surfaces\[0\]\]"),
    (lambda doc: doc["surfaces"].append(dict(doc["surfaces"][0])),
     r"surfaces\[1\]\.name = 'tail' is invalid: surfaces\[0\] has it already"),
    (lambda doc: doc.pop("surfaces"), r"rigid-body pitch: a wing alone has no tail.*add a "
                                      r"tail"),
])
def test_a_bad_surface_is_one_line_naming_file_and_key(tailed, tmp_path, edit, words):
    import tomllib

    import tomli_w

    _, toml = tailed
    doc = tomllib.loads(toml.read_text())
    edit(doc)
    bad = tmp_path / "bad.toml"
    bad.write_text(tomli_w.dumps(doc))
    npz = toml.with_name("tail.modes.npz")
    (tmp_path / npz.name).write_bytes(npz.read_bytes())
    with pytest.raises(InputError, match=words) as exc:
        load_modal_model(bad)
    msg = str(exc.value)
    assert msg.startswith(str(bad)) and "\n" not in msg
