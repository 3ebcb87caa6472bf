"""`propwhirl upgrade-model OLD NEW` (issue 20, item 11): a model file of format version 1
rewritten in the current version with the values version 1 assumed written out; the same
model and analysis; the commands print the note naming the assumed values."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from propwhirl import io
from propwhirl.app import cli

DATA = Path(__file__).resolve().parents[1] / "io" / "data"
#: The first release's example (format 1) without the keys whose values were version 1's
#: defaults, as a user relying on them wrote it.
ASSUMED = ("elastic_axis_chord", "centre_of_gravity_chord", "speed_of_sound_m_per_s",
           "pivot_pitch_m", "pivot_yaw_m", "n_blades", "beta_075_deg", "zero_lift_angle_deg",
           "rotation")


@pytest.fixture
def old_file(tmp_path) -> Path:
    text = (DATA / "format1_wingtip_0.1.0.toml").read_text()
    lines = [ln for ln in text.splitlines(keepends=True)
             if not any(ln.startswith(f"{k} = ") for k in ASSUMED)]
    assert len(lines) == len(text.splitlines()) - len(ASSUMED)
    # a coarse initial grid and a 6-element wing: fast, the same comparison
    text = "".join(lines).replace("n_elements = 25", "n_elements = 6").replace(
        "[1.0, 350.0, 10.0]", "[1.0, 350.0, 50.0]")
    path = tmp_path / "old.toml"
    path.write_text(text)
    return path


def _one_line_error(capsys, argv) -> str:
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1
    return err


def test_upgrade_writes_the_current_version_with_the_assumed_values(old_file, tmp_path, capsys):
    new = tmp_path / "new.toml"
    assert cli.main(["upgrade-model", str(old_file), str(new)]) == 0
    out, err = capsys.readouterr()
    assert out == f"wrote {new} (format version 2)\n"
    assert err.count("\n") == 1 and err.startswith(
        f"propwhirl: note: {old_file}: format version 1: assumed the values version 1 gave")
    text = new.read_text()
    assert "\nformat_version = 2\n" in text
    for line in ("elastic_axis_chord = 0.5\n", "centre_of_gravity_chord = 0.5\n",
                 "speed_of_sound_m_per_s = 330.8027446243564\n", "pivot_pitch_m = 0.0\n",
                 "pivot_yaw_m = 0.0\n", "n_blades = 3\n", "beta_075_deg = 35.0\n",
                 "zero_lift_angle_deg = -3.0\n", "rotation = 1\n"):
        assert line in text
    notes: list[str] = []
    assert io.load_model(new, notes=notes) == io.load_model(old_file) and notes == []
    # upgrading the upgraded file: nothing assumed, the same text
    again = tmp_path / "again.toml"
    assert cli.main(["upgrade-model", str(new), str(again)]) == 0
    out, err = capsys.readouterr()
    assert out == f"wrote {again} (format version 2; no value assumed)\n" and err == ""
    assert again.read_text() == text


def test_the_analysis_of_the_old_file_is_that_of_the_upgraded_file(old_file, tmp_path, capsys):
    new = tmp_path / "new.toml"
    assert cli.main(["upgrade-model", str(old_file), str(new)]) == 0
    capsys.readouterr()
    results = []
    for path in (old_file, new):
        out_json = tmp_path / f"{path.stem}.json"
        assert cli.main(["analyse", str(path), "--json", str(out_json)]) == 0
        out, err = capsys.readouterr()
        # the old file's analysis prints the note naming the assumed values, once
        assert err.count("propwhirl: note: ") == (path == old_file)
        doc = json.loads(out_json.read_text())
        results.append((doc["events"], doc["sweep"]))
    assert results[0] == results[1] and results[0][0]  # the same instabilities, and some


def test_new_must_not_be_old_unless_forced(old_file, capsys):
    before = old_file.read_text()
    err = _one_line_error(capsys, ["upgrade-model", str(old_file), str(old_file)])
    assert f"NEW {old_file} is the file OLD" in err and "--force" in err
    assert old_file.read_text() == before  # untouched
    assert cli.main(["upgrade-model", str(old_file), str(old_file), "--force"]) == 0
    capsys.readouterr()
    assert "\nformat_version = 2\n" in old_file.read_text()


@pytest.mark.parametrize("case, message", [
    ("missing", "not found"),
    ("newer", "format_version = 3 is newer than this propwhirl reads (versions 1, 2)"),
    ("bad toml", "not valid TOML"),
    ("no folder", "the folder"),
])
def test_bad_input_is_one_line_and_writes_nothing(case, message, old_file, tmp_path, capsys):
    old, new = old_file, tmp_path / "new.toml"
    if case == "missing":
        old = tmp_path / "missing.toml"
    elif case == "newer":
        old.write_text(old.read_text().replace("format_version = 1", "format_version = 3"))
    elif case == "bad toml":
        old.write_text(old.read_text().replace("[wing]", "[wing"))
    else:
        new = tmp_path / "nowhere" / "new.toml"
    err = _one_line_error(capsys, ["upgrade-model", str(old), str(new)])
    assert message in err
    assert not new.exists()


# ------------------------------------------------------------- issue 33, items 2 and 3
@pytest.mark.parametrize("kind", ["device", "fifo", "socket"])
def test_new_as_a_device_fifo_or_socket_is_refused_and_kept(kind, old_file, tmp_path, capsys,
                                                            monkeypatch):
    """Item 2: `upgrade-model v1.toml /dev/null` exited 0 and, as root, the atomic rename put a
    regular file in place of the device node.  Tested on nodes of our own (never /dev/null):
    refused in one line before anything is written, the node still what it was."""
    import os
    import stat

    from helpers.files import char_device, unix_socket

    from propwhirl import fileio

    new, held = tmp_path / "new.toml", None
    if kind == "device":
        char_device(new)
    elif kind == "fifo":
        os.mkfifo(new)
    else:
        held = unix_socket(new)
    monkeypatch.setattr(fileio, "_create_temporary", lambda p: pytest.fail("a write began"))
    try:
        err = _one_line_error(capsys, ["upgrade-model", str(old_file), str(new)])
    finally:
        if held is not None:
            held.close()
    what = {"device": "a character device", "fifo": "a FIFO (named pipe)",
            "socket": "a socket"}[kind]
    assert err == (f"propwhirl: error: upgrade-model NEW {new}: is {what}, not a regular file "
                   "(propwhirl writes regular files only)\n")
    test = {"device": stat.S_ISCHR, "fifo": stat.S_ISFIFO, "socket": stat.S_ISSOCK}[kind]
    assert test(os.lstat(new).st_mode)


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_old_as_a_device_is_refused_before_it_is_opened(device, tmp_path, capsys, monkeypatch):
    """Item 3: `upgrade-model /dev/zero out.toml` grew past 4 GB."""
    from helpers.files import never_opened

    never_opened(monkeypatch, device)
    err = _one_line_error(capsys, ["upgrade-model", device, str(tmp_path / "out.toml")])
    assert err == (f"propwhirl: error: cannot read model file {device!r}: it is a character "
                   "device, not a regular file (propwhirl reads regular files only)\n")
    assert not (tmp_path / "out.toml").exists()


def test_a_hard_link_of_old_is_old(old_file, tmp_path, capsys):
    import os

    link = tmp_path / "link.toml"
    os.link(old_file, link)
    err = _one_line_error(capsys, ["upgrade-model", str(old_file), str(link)])
    assert f"NEW {link} is the file OLD" in err
