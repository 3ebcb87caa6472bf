"""`propwhirl --version`, output into a pipe that closes early, `propwhirl docs`, and the one
default speed of sound of `propwhirl derivatives` (issue 11, items 6, 8 and friction 9)."""
from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from importlib import metadata
from pathlib import Path

import pytest

from propwhirl import documents
from propwhirl.app import cli
from propwhirl.model import atmosphere
from propwhirl.model.flight import DEFAULT_SPEED_OF_SOUND, FlightCondition

ROOT = Path(__file__).resolve().parents[2]
PROPWHIRL = [sys.executable, "-m", "propwhirl"]


# ----------------------------------------------------------------------------- --version
def test_version_prints_the_package_version(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out == f"propwhirl {metadata.version('propwhirl')}\n"


def test_version_of_a_source_checkout_without_an_installed_distribution(monkeypatch):
    def missing(name):
        raise metadata.PackageNotFoundError(name)

    monkeypatch.setattr(metadata, "version", missing)
    expected = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert cli.version() == f"{expected} (source)"


def test_version_from_the_command_line():
    run = subprocess.run(PROPWHIRL + ["--version"], capture_output=True, text=True, timeout=120)
    assert (run.returncode, run.stderr) == (0, "")
    assert run.stdout == f"propwhirl {metadata.version('propwhirl')}\n"


# ----------------------------------------------------------------------------- broken pipe
@pytest.mark.parametrize("argv", [["case", "wingtip"], ["docs", "validation"], ["--help"],
                                  ["reproduce", "--only", "t7.2"]])
def test_a_reader_gone_before_the_output_ends_quietly(argv):
    """The read end is closed before the command writes: every write meets a broken pipe."""
    proc = subprocess.Popen(PROPWHIRL + argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()
    stderr = proc.stderr.read().decode()
    code = proc.wait(timeout=300)
    assert stderr == ""                       # no "propwhirl: error: Broken pipe", no traceback
    # 141 = 128 + SIGPIPE; argparse's --help swallows the error itself and exits 0
    assert code == (0 if argv == ["--help"] else cli.EXIT_BROKEN_PIPE) and cli.EXIT_BROKEN_PIPE == 141


def test_head_on_the_reproduction_table():
    """The issue's command: `propwhirl reproduce | head -1` (one chapter: fast)."""
    run = subprocess.run(["bash", "-c", "set -o pipefail; " + " ".join(PROPWHIRL)
                          + " reproduce --only t7.2 | head -1"],
                         capture_output=True, text=True, timeout=300)
    assert run.stdout.startswith("id ") and run.stdout.count("\n") == 1
    assert run.stderr == "" and run.returncode in (0, cli.EXIT_BROKEN_PIPE)


# ----------------------------------------------------------------------------- docs
def test_docs_lists_the_pages_where_they_are_installed(capsys):
    assert cli.main(["docs"]) == 0
    out = capsys.readouterr().out
    for name in ("validation", "errata", "model-file"):
        assert f"  {name:14s} {documents.path(name)}\n" in out


def test_docs_prints_a_page_and_its_path(capsys):
    assert cli.main(["docs", "errata"]) == 0
    assert capsys.readouterr().out == (ROOT / "docs" / "errata.md").read_text(encoding="utf-8")
    assert cli.main(["docs", "validation.md", "--path"]) == 0
    assert capsys.readouterr().out == f"{documents.path('validation')}\n"


def test_docs_unknown_page_is_one_line_naming_the_pages(capsys):
    assert cli.main(["docs", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: error: document 'nope' is invalid: must be one of ")
    assert "validation" in err and err.count("\n") == 1


def test_no_output_names_the_repository_path_of_a_page(capsys):
    """Friction 9: the reproduction table referred to docs/validation.md, which a pip install
    does not contain; it now names the command and the installed file."""
    assert cli.main(["reproduce", "--only", "t7.3"]) == 0
    out = capsys.readouterr().out
    assert "docs/validation.md" not in out.replace(str(documents.path("validation")), "")
    assert documents.cite("validation") in out


# ----------------------------------------------------------------------------- derivatives
ARGS = ["derivatives", "--blades", "3", "--radius", "0.762", "--hub-ratio", "0.164", "--chord",
        "0.094", "--speed", "100", "221", "--blade-angle", "35", "--json"]


def _points(capsys, *extra: str) -> list[dict]:
    assert cli.main(ARGS + list(extra)) == 0
    return json.loads(capsys.readouterr().out)["points"]


def test_derivatives_default_speed_of_sound_is_the_one_default(capsys):
    """It was 340.294 m/s (sea level) while FlightCondition and the cases use 330.80 m/s."""
    assert DEFAULT_SPEED_OF_SOUND == FlightCondition(1.0).speed_of_sound
    assert DEFAULT_SPEED_OF_SOUND == atmosphere.isa(altitude_ft=8000.0).speed_of_sound
    default = _points(capsys)
    assert [p["mach"] for p in default] == pytest.approx([100 / DEFAULT_SPEED_OF_SOUND,
                                                          221 / DEFAULT_SPEED_OF_SOUND], rel=1e-12)
    assert _points(capsys, "--speed-of-sound", repr(DEFAULT_SPEED_OF_SOUND)) == default
    assert _points(capsys, "--altitude-ft", "8000") == default


def test_derivatives_at_an_isa_altitude(capsys):
    p = _points(capsys, "--altitude-m", "11000")
    assert p[0]["mach"] == pytest.approx(100 / atmosphere.speed_of_sound(11000.0), rel=1e-12)


@pytest.mark.parametrize("extra, message", [
    (["--altitude-m", "40000"], "--altitude-m = 40000.0 m is outside the valid range [-5000, 32000] m"),
    (["--altitude-ft", "1e6"], "--altitude-ft = 1000000.0 ft is outside the valid range"),
    (["--altitude-m", "1000", "--speed-of-sound", "340"], "not allowed with argument"),
    (["--altitude-m", "1000", "--mach", "0.3"], "not allowed with argument"),
])
def test_derivatives_air_options_are_checked(capsys, extra, message):
    assert cli.main(ARGS + extra) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
