"""Issue 20.4: a 5,000-character file name is one line naming it (shortened), never a raw
OSError — here for the places that ask whether a file exists: the MODEL argument of a study,
a partial-results file to resume from, upgrade-model's files, the reference values."""
from __future__ import annotations

import pytest

from propwhirl import fileio
from propwhirl.app import cli
from propwhirl.reproduce import harness
from propwhirl.studies.partial import Checkpoint
from propwhirl.validate import InputError


@pytest.fixture
def long_name(tmp_path):
    return str(tmp_path / ("a" * 5000 + ".toml"))


def test_exists_names_a_too_long_path_in_one_line(long_name, tmp_path):
    with pytest.raises(InputError, match=r"cannot read model file .*characters\): File name too long") as e:
        fileio.exists(long_name, "model file")
    assert "\n" not in str(e.value) and len(str(e.value)) < 300
    assert fileio.exists(tmp_path, "folder") and not fileio.exists(tmp_path / "x", "file")


@pytest.mark.parametrize("argv", [
    ["sweep", "{long}", "--param", "propeller.f_theta", "4", "5", "2"],
    ["upgrade-model", "{long}", "{short}"],
    ["upgrade-model", "{short}", "{long}"],
])
def test_the_command_line_names_a_too_long_path_in_one_line(long_name, tmp_path, capsys, argv):
    short = tmp_path / "m.toml"
    assert cli.main(["case", "wingtip", "--save", str(short)]) == 0
    capsys.readouterr()
    argv = [a.format(long=long_name, short=short) for a in argv]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and len(err) < 400, err


def test_a_partial_file_of_a_too_long_name_is_one_line(long_name):
    with pytest.raises(InputError, match="File name too long"):
        Checkpoint(long_name + ".partial", resume=True).load(["a", "b"])


def test_reference_values_of_a_too_long_name_are_one_line(long_name):
    with pytest.raises(InputError, match="reference values file .*File name too long"):
        harness.load_references(long_name)
