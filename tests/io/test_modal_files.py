"""Modal-model files (issue 22, items 2 and 5): a beam model's modes written to the open
format (.npz + TOML) and read back give the same model; every bad file is one line naming
the file, the key and the id, and nothing is half-imported."""
from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers.eigen import matched_gap
from propwhirl import InputError
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.io.modal_files import load_modal_model, load_modes, write_modes
from propwhirl.model.modal import ModalPropellerWing, ModalStructure


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    d = tmp_path_factory.mktemp("modal")
    return write_modes(wingtip_propeller_wing(), d / "wingtip.toml")


def test_the_written_modes_read_back_bit_for_bit(written):
    toml, npz = written
    assert npz.name == "wingtip.modes.npz"
    m = load_modal_model(toml)
    assert isinstance(m, ModalPropellerWing)
    ref = ModalStructure.from_wing(wingtip_propeller_wing().wing)
    for k in ("grid_ids", "xyz", "frequencies_hz", "modal_mass", "damping_ratio", "shapes"):
        assert np.array_equal(getattr(m.structure, k), getattr(ref, k)), k
    full = wingtip_propeller_wing()
    assert m.flight == full.flight
    assert m.propellers[0].propeller == full.propellers[0].propeller
    assert m.propellers[0].grid == 1 + full.nodes[0]
    V = np.array([150.0])
    assert matched_gap(full.state_matrix(V)[0], m.state_matrix(V)[0]) < 1e-6


def test_truncated_modes_and_two_propellers_round_trip(tmp_path):
    toml, _ = write_modes(two_propeller_wing(), tmp_path / "two.toml", n_modes=6)
    m = load_modal_model(toml)
    assert m.structure.n_modes == 6
    assert [p.grid for p in m.propellers] == [1 + n for n in two_propeller_wing().nodes]
    assert m.dof_map().n_dof == 6 + 4


def _edit(toml, old, new, count=1):
    text = toml.read_text()
    assert old in text, old
    toml.write_text(text.replace(old, new, count))


CASES = [
    # (edit of the TOML text, words the one-line error must hold)
    (('length = "m"', 'length = "mm"'), ["[units] length", "'mm'", "SI"]),
    (('mass = "kg"\n', ''), ["'mass'", "[units]", "stated"]),
    (('[units]\nlength = "m"\nmass = "kg"\ntime = "s"\nangle = "rad"\nfrequency = "Hz"\n', ''),
     ["'units'", "stated"]),
    (('grid = 26,', 'grid = 99,'), ["installations[0].grid = 99", "no hub grid 99",
                                   "wingtip.modes.npz"]),
    (('n_modes = 75', 'n_modes = 74'), ["wingtip.modes.npz", "frequencies_hz", "n_modes = 74"]),
    (('wing_grids = [\n    1,', 'wing_grids = [\n    77,'), ["wing_grids[0] = 77",
                                                             "not a grid"]),
    (('propeller = "p1"', 'propeller = "p9"'), ["installations[0]", "propeller", "p9"]),
    (('format_version = 1', 'format_version = 2'), ["format_version = 2"]),
    (('mount = "flexible"', 'mount = "rigid-on-grid"'), ["installations[0]", "mount"]),
]


def _refused_in_one_line(toml, edit, words) -> None:
    """The file ``toml`` with ``edit`` (old, new) made is refused in one line that starts with
    its path and holds every one of ``words``."""
    _edit(toml, *edit)
    with pytest.raises(InputError) as e:
        load_modal_model(toml)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(str(toml)), msg
    for w in words:
        assert w in msg, (w, msg)


@pytest.mark.parametrize("edit, words", CASES, ids=[c[0][1][:20] for c in CASES])
def test_a_bad_description_is_one_line_naming_file_key_and_id(tmp_path, edit, words):
    toml, _ = write_modes(wingtip_propeller_wing(), tmp_path / "wingtip.toml")
    _refused_in_one_line(toml, edit, words)


def _rewrite_npz(npz, **changes):
    with np.load(npz, allow_pickle=False) as f:
        arrays = {k: f[k] for k in f.files}
    arrays.update(changes)
    np.savez(npz, **arrays)


@pytest.mark.parametrize("change, words", [
    (lambda a: dict(frequencies_hz=np.r_[0.0, a["frequencies_hz"][1:]]),
     ["frequencies_hz[0]", "rigid-body mode"]),
    (lambda a: dict(grid_ids=np.r_[a["grid_ids"][:-1], a["grid_ids"][:1]]),
     ["grid_ids", "grid 1 twice"]),
    (lambda a: dict(grid_ids=a["grid_ids"].astype(np.float64)), ["grid_ids"]),
    (lambda a: dict(shapes=a["shapes"][:, :, :3]), ["shapes"]),
    (lambda a: dict(modal_mass=np.zeros_like(a["modal_mass"])), ["modal_mass[0]", "> 0"]),
])
def test_a_bad_modes_file_is_one_line_naming_it_and_the_array(tmp_path, change, words):
    toml, npz = write_modes(wingtip_propeller_wing(), tmp_path / "wingtip.toml")
    with np.load(npz, allow_pickle=False) as f:
        arrays = {k: f[k] for k in f.files}
    _rewrite_npz(npz, **change(arrays))
    with pytest.raises(InputError) as e:
        load_modal_model(toml)
    msg = str(e.value)
    assert "\n" not in msg and str(npz) in msg, msg
    for w in words:
        assert w in msg, msg


def test_a_modes_file_with_a_pickle_or_missing_is_refused(tmp_path):
    toml, npz = write_modes(wingtip_propeller_wing(), tmp_path / "wingtip.toml")
    np.savez(npz, grid_ids=np.array([object()], dtype=object))
    with pytest.raises(InputError, match="wingtip.modes.npz"):
        load_modal_model(toml)
    npz.unlink()
    with pytest.raises(InputError, match="not found"):
        load_modes(npz, 3, 3)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(line=st.integers(0, 400), junk=st.sampled_from(
    ["= 1", '= "x"', "= -1", "= []", "= [0.0]", "= true", "= 1e400", "= nan", "= 0"]))
def test_any_corrupted_line_gives_a_model_or_one_line(written, tmp_path_factory, line, junk):
    """Every line of a valid file replaced by a key with a bad value: a model, or one line
    starting with the file's name; nothing else (no traceback from NumPy)."""
    toml, npz = written
    d = tmp_path_factory.mktemp("fuzz")
    lines = toml.read_text().splitlines()
    i = line % len(lines)
    m = re.match(r"\s*([A-Za-z_]\w*)\s*=", lines[i])
    if m is None:
        return
    lines[i] = f"{m.group(1)} {junk}" + ("," if lines[i].rstrip().endswith(",") else "")
    bad = d / "wingtip.toml"
    bad.write_text("\n".join(lines) + "\n")
    (d / npz.name).write_bytes(npz.read_bytes())
    try:
        model = load_modal_model(bad)
    except InputError as exc:
        assert "\n" not in str(exc) and str(exc).startswith(str(bad)), str(exc)
    else:
        assert isinstance(model, ModalPropellerWing)


def test_write_modes_refuses_what_it_cannot_write(tmp_path):
    from propwhirl.cases.ch09_baseline import isolated_baseline_propeller

    with pytest.raises(InputError, match="only a PropellerWing"):
        write_modes(isolated_baseline_propeller(), tmp_path / "x.toml")
    assert not list(tmp_path.iterdir())


def test_the_whole_structures_modes_with_hub_grids_round_trip(tmp_path):
    """Way (b): the modes of the wing with the propellers' masses and mount springs, each
    propeller on a hub grid of its own, written and read back: the same A(V) as the model
    built in memory."""
    from propwhirl.model.modal import ModalStructure

    full = two_propeller_wing()
    toml, npz = write_modes(full, tmp_path / "two.toml", n_modes=12, mount="on-grid")
    m = load_modal_model(toml)
    s, hubs, _ = ModalStructure.with_mounts(full, 12)
    assert [p.grid for p in m.propellers] == list(hubs)
    assert all(p.mount == "on-grid" for p in m.propellers)
    assert np.array_equal(m.structure.shapes, s.shapes)
    assert m.dof_map().n_dof == 12
    with pytest.raises(InputError, match="mount = 'rigid' is invalid"):
        write_modes(full, tmp_path / "x.toml", mount="rigid")


def test_a_modal_model_given_as_a_model_file_says_how_to_read_it(written):
    from propwhirl.io import load_model

    toml, _ = written
    with pytest.raises(InputError, match="this is a modal model: read it with "
                                         "propwhirl.io.load_modal_model"):
        load_model(toml)


def test_more_modes_than_the_limit_are_refused_before_reading(written, tmp_path):
    toml, npz = written
    bad = tmp_path / "wingtip.toml"
    bad.write_text(toml.read_text().replace("n_modes = 75", "n_modes = 1000000"))
    with pytest.raises(InputError, match=r"\[modes\] n_modes = 1000000 is invalid: must be an "
                                         r"integer in \[1, 1000\]"):
        load_modal_model(bad)


# ----------------------------------------------------------- issue 33, items 1 and 3
def _modal_with_modes_file(written, tmp_path, file: str):
    """A copy of the written TOML whose [modes] file is `file` (absolute or relative)."""
    toml = tmp_path / "m.toml"
    toml.write_text(written[0].read_text().replace('file = "wingtip.modes.npz"',
                                                   f'file = "{file}"'))
    return toml


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_a_device_as_the_modes_file_is_refused_before_it_is_opened(written, tmp_path,
                                                                    monkeypatch, device):
    """Item 3: `[modes] file = "/dev/zero"` grew past 4 GB; now one line naming the key."""
    from helpers.files import never_opened

    toml = _modal_with_modes_file(written, tmp_path, device)
    never_opened(monkeypatch, device)
    with pytest.raises(InputError) as e:
        load_modal_model(toml)
    assert str(e.value) == (f"{toml}: cannot read [modes] file {device!r}: it is a character "
                            "device, not a regular file (propwhirl reads regular files only)")


def test_a_fifo_as_the_modes_file_is_refused_without_opening_it(written, tmp_path):
    """Item 3: a FIFO as the modes file waited for a writer for ever."""
    from helpers.files import FifoWriter

    toml = _modal_with_modes_file(written, tmp_path, "pipe.npz")
    with FifoWriter(tmp_path / "pipe.npz") as fifo:
        with pytest.raises(InputError, match=r"\[modes\] file '.*pipe\.npz': it is a FIFO"):
            load_modal_model(toml)
        assert not fifo.opened.is_set()


def test_a_modes_file_larger_than_its_arrays_is_refused_before_reading(written, tmp_path):
    toml = _modal_with_modes_file(written, tmp_path, "big.npz")
    with open(tmp_path / "big.npz", "wb") as fh:
        fh.truncate(2 ** 32)                           # sparse: 4 GiB of nothing
    with pytest.raises(InputError, match=r"big\.npz': it has 4,294,967,296 bytes, more than "
                                         r"[0-9,]+ \(its arrays take at most \(n_modes = 75"):
        load_modal_model(toml)


def test_a_modal_file_linked_to_a_device_is_refused(tmp_path, monkeypatch):
    """Item 3: a modal TOML that is a symbolic link to /dev/zero."""
    from helpers.files import never_opened

    from propwhirl.app import cli

    link = tmp_path / "wing.toml"
    link.symlink_to("/dev/zero")
    never_opened(monkeypatch, "/dev/zero")
    with pytest.raises(InputError, match=r"wing\.toml': it is a character device"):
        load_modal_model(link)
    assert cli.main(["analyse", str(link)]) == 2


def test_write_modes_refuses_the_beam_models_own_file(tmp_path):
    """Item 1: write_modes(model, "wing.toml") onto the beam model's file replaced it."""
    from propwhirl import io

    beam = tmp_path / "wing.toml"
    io.save_model(wingtip_propeller_wing(), beam)
    before = beam.read_bytes()
    model = io.load_model(beam)
    with pytest.raises(InputError) as e:
        write_modes(model, beam)
    assert str(e.value).startswith(f"write_modes: path {str(beam)!r} exists and is not a modal "
                                   "model file")
    assert beam.read_bytes() == before and not (tmp_path / "wing.modes.npz").exists()
    toml, npz = write_modes(model, tmp_path / "modal.toml")       # a new path
    write_modes(model, toml, n_modes=4)                             # its own file again
    assert load_modal_model(toml).structure.n_modes == 4


def test_an_analysis_output_on_the_modes_file_is_refused(written, tmp_path, capsys):
    """Item 1: the modes file is an input of `analyse` too."""
    from propwhirl.app import cli

    toml, npz = written
    before = npz.read_bytes()
    assert cli.main(["analyse", str(toml), "--json", str(npz)]) == 2
    err = capsys.readouterr().err
    assert err == (f"propwhirl: error: --json {npz} is the modes file of MODEL {toml} "
                   "([modes] file): give another path\n")
    assert npz.read_bytes() == before


# ----------------------------------------------------------- issue 33, item 10
@pytest.mark.parametrize("f", [1e300, 1e200, 1e154, 2e24])
def test_an_overflowing_frequency_is_the_error_alone(tmp_path, f):
    """Issue 33, item 10: frequencies_hz[9] = 1e300 printed numpy's RuntimeWarning (overflow)
    before the one-line error; now the file is refused when read, naming the array, the mode
    and the valid range, and nothing else is printed (warnings are errors here)."""
    import warnings

    toml, npz = write_modes(wingtip_propeller_wing(), tmp_path / "wingtip.toml")
    with np.load(npz, allow_pickle=False) as a:
        freq = a["frequencies_hz"].copy()
    freq[9] = f
    _rewrite_npz(npz, frequencies_hz=freq)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError) as e:
            load_modal_model(toml)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(str(toml)) and str(npz) in msg, msg
    assert f"frequencies_hz[9] = {f:.6g} Hz is outside the valid range [1e-3, 1e24] Hz" in msg


def test_a_structure_whose_stiffness_overflows_gives_the_state_matrix_error_alone():
    """A frequency within the range on a huge modal mass: m (2π f)² is inf, which the state
    matrix's own check names — without numpy's warning before it."""
    import warnings

    from propwhirl.model.modal_structure import MAX_FREQUENCY_HZ

    s = ModalStructure.from_wing(wingtip_propeller_wing().wing, 3)
    big = ModalStructure(s.grid_ids, s.xyz, np.r_[s.frequencies_hz[:2], MAX_FREQUENCY_HZ],
                         np.r_[1.0, 1.0, 1e300], s.damping_ratio, s.shapes)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        M, C, K = big.generalised()
    assert np.isinf(K[2, 2]) and np.isfinite(M).all()


def _dlm_beam():
    from dataclasses import replace
    m = wingtip_propeller_wing()
    return m.with_(wing=replace(m.wing, n_elements=6, aero="dlm", dlm_chordwise_panels=3,
                                dlm_spanwise_panels=5, dlm_mach=0.2))


def test_a_doublet_lattice_model_round_trips_with_its_planform(tmp_path):
    """write_modes of a beam DLM model writes aero and its [dlm] planform (the beam's own
    panels) and Mach; save_modal_model keeps them; a file without them keeps the strips."""
    from propwhirl.io.modal_files import save_modal_model
    from propwhirl.model.aerodynamics.planform import Planform
    b = _dlm_beam()
    toml, _ = write_modes(b, tmp_path / "dlm.toml")
    m = load_modal_model(toml)
    assert (m.aero, m.dlm_mach) == ("dlm", 0.2)
    assert np.array_equal(m.dlm_planform.mesh().corners,
                          Planform.from_wing(b.wing).mesh().corners)
    again = load_modal_model(save_modal_model(m, tmp_path / "again.toml")[0])
    assert (again.aero, again.dlm_mach, again.dlm_planform.counts()) == ("dlm", 0.2, (3, 5))
    assert np.array_equal(again.dlm_planform.leading_edge, m.dlm_planform.leading_edge)
    plain, _ = write_modes(wingtip_propeller_wing(), tmp_path / "plain.toml")
    assert "[dlm]" not in plain.read_text() and load_modal_model(plain).aero == "strip"


@pytest.mark.parametrize("edit, words", [
    (("leading_edge_y_m = [\n    0.0,", "leading_edge_y_m = [\n    -1.0,"),
     ["[dlm]: leading_edge[0] y = -1 m", ">= 0"]),
    (("    5.7,\n]\nleading_edge_z_m", "    9.0,\n]\nleading_edge_z_m"),
     ["[dlm]: leading_edge[5] y = 9 m is outside the wing grids' span"]),
    (("chord_m = [\n    1.25,", "chord_m = [\n    1.25,\n    1.0,"),
     ["[dlm] chord_m", "one per station"]),
    (("chordwise_panels = 3", "chordwise_panels = 0"), ["[dlm] chordwise_panels"]),
    (("mach = 0.2", "mach = 1.5"), ["[dlm] mach"]),
    (('aero = "dlm"', 'aero = "vlm"'), ["aero", "vlm"]),
])
def test_a_bad_planform_is_one_line_naming_the_key(tmp_path, edit, words):
    toml, _ = write_modes(_dlm_beam(), tmp_path / "dlm.toml")
    _refused_in_one_line(toml, edit, words)


def test_aero_dlm_without_a_planform_is_refused(tmp_path):
    toml, _ = write_modes(_dlm_beam(), tmp_path / "dlm.toml")
    text = toml.read_text()
    toml.write_text(text[:text.index("[dlm]")])
    with pytest.raises(InputError, match=r'aero = "dlm" needs the \[dlm\] table') as e:
        load_modal_model(toml)
    assert "\n" not in str(e.value)
