"""Every error of a model file at once (issue 25, item 6): one line per error, each naming the
file and the key, in the file's order; a table that cannot be read causes no further error."""
from __future__ import annotations

from pathlib import Path

import pytest

from propwhirl import io
from propwhirl.app import cli
from propwhirl.io import model_files
from propwhirl.validate import InputError

X57 = Path(__file__).parents[2] / "examples" / "x57_like.toml"

#: Three errors in three tables: [wing], [flight], [propellers.cruise].
THREE = [("semi_span_m = 4.8", "semi_span_m = -4.8"),
         ("altitude_ft = 8000.0", "altitude_ft = 8000.0\ndensty = 1.0"),
         ('f_psi_hz = 8.0', 'f_psi_hz = "8"')]
LINES = ["x57.toml: [wing] semi_span_m = -4.8 is outside the valid range [0.01, 1000] m",
         "x57.toml: unknown key 'densty' in [flight]",
         "x57.toml: [propellers.cruise] f_psi_hz = '8' is invalid: must be a number"]


def _text(changes) -> str:
    text = X57.read_text()
    for old, new in changes:
        assert old in text
        text = text.replace(old, new, 1)
    return text


def test_three_errors_in_three_tables_are_reported_at_once():
    with pytest.raises(InputError) as exc:
        io.loads(_text(THREE), "x57.toml")
    lines = exc.value.errors
    assert str(exc.value) == "\n".join(lines) and len(lines) == 3
    for line, start in zip(lines, LINES):
        assert line.startswith(start), line


def test_the_command_line_prints_every_error_one_line_each_exit_2(tmp_path, capsys):
    path = tmp_path / "x57.toml"
    path.write_text(_text(THREE))
    assert cli.main(["analyse", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3
    for line, start in zip(err, LINES):
        assert line.startswith(f"propwhirl: error: {tmp_path / start}"), line


def test_one_error_is_one_line():
    with pytest.raises(InputError) as exc:
        io.loads(_text(THREE[:1]), "x57.toml")
    assert "\n" not in str(exc.value) and str(exc.value).startswith(LINES[0])


def test_every_entry_of_a_list_and_every_propeller_table_is_read():
    text = _text([("y_m = 4.8", "y_m = -4.8"), ("y_m = 2.15", "y_m = 2.15, colour = 1"),
                  ("radius_m = 0.29", "radius_m = 0.0"), ("n_elements = 24", "n_elements = 0")])
    with pytest.raises(InputError) as exc:
        io.loads(text, "f.toml")
    lines = exc.value.errors
    assert len(lines) == 4, lines
    assert lines[0].startswith("f.toml: [wing] n_elements = 0 is")
    assert lines[1].startswith("f.toml: unknown key 'colour' in [installations[2]]")
    assert lines[2].startswith("f.toml: [installations[6]] y_m = -4.8 is outside")
    assert lines[3].startswith("f.toml: [propellers.high_lift] radius_m = 0.0 is outside")


def test_no_error_follows_from_another():
    # a misspelled key is reported once, not also as the missing keys it stands for
    text = _text([("altitude_ft = 8000.0", "altitude_km = 2.4")])
    with pytest.raises(InputError) as exc:
        io.loads(text, "f.toml")
    assert exc.value.errors == ["f.toml: unknown key 'altitude_km' in [flight] (did you mean "
                                "altitude_m?): valid keys are density_kg_per_m3, "
                                "speed_of_sound_m_per_s, speed_range_m_per_s, altitude_m, "
                                "altitude_ft"]
    # a propeller table that cannot be read is not referred to again by its installations
    text = _text([("radius_m = 0.29", "radius_m = -1.0")])
    with pytest.raises(InputError) as exc:
        io.loads(text, "f.toml")
    assert len(exc.value.errors) == 1 and "[propellers.high_lift] radius_m" in str(exc.value)


def test_at_most_max_errors_lines():
    text = X57.read_text().replace("[wing]\n", "[wing]\n" + "".join(
        f"bad_{i} = 1\n" for i in range(model_files.MAX_ERRORS + 5)), 1)
    with pytest.raises(InputError) as exc:
        io.loads(text, "f.toml")
    lines = exc.value.errors
    assert len(lines) == model_files.MAX_ERRORS + 1
    assert lines[-1] == "f.toml: and 5 more errors"
