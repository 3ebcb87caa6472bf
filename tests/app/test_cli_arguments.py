"""CLI arguments: --speeds and --rpm bounded (one line, exit 2), model names printed safely."""
from __future__ import annotations

import pytest

from propwhirl import io, limits
from propwhirl.app import cli


@pytest.fixture(scope="module")
def tip_file(tmp_path_factory):
    from propwhirl.cases.registry import case_model

    path = tmp_path_factory.mktemp("models") / "wingtip.toml"
    io.save_model(case_model("wingtip"), path)
    return path


def _error(capsys, argv) -> str:
    assert cli.main(argv) == 2
    out, err = capsys.readouterr()
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1
    return err


@pytest.mark.parametrize("speeds, match", [
    (["1", "350", "0.0035"], "the analysis needs ≈ 124 GiB for 99,716 speeds × 204 states "
                             "(limit 2.0 GiB, set PROPWHIRL_MEMORY_LIMIT or pass fewer speeds)"),
    (["1", "350", "0.001"], "--speeds 1 350 0.001 gives 349,001 speeds: must be at most 100,000"),
    (["1", "inf", "10"], "--speeds STOP = inf m/s is invalid: must be finite"),
    (["1", "nan", "10"], "--speeds STOP = nan m/s is invalid: must be finite"),
    (["1", "350", "0"], "--speeds STEP = 0.0 m/s is invalid: must be > 0"),
])
def test_speeds_out_of_bounds(tip_file, capsys, monkeypatch, speeds, match):
    monkeypatch.setenv(limits.MEMORY_ENV, "2GiB")       # dense: the 204 states of the issue's
    assert match in _error(capsys, ["analyse", str(tip_file), "--speeds", *speeds,
                                    "--method", "dense"])


@pytest.mark.parametrize("rpm, match", [
    (["0", "1e300", "3"], "--rpm STOP = 1e+300 rev/min is outside the valid range [0, 1e5] rev/min"),
    (["0", "inf", "3"], "--rpm STOP = inf rev/min is invalid: must be finite"),
    (["-5", "100", "3"], "--rpm START = -5.0 rev/min is outside the valid range [0, 1e5] rev/min"),
    (["100", "0", "3"], "--rpm STOP = 0.0 rev/min is invalid: must be > START = 100.0"),
])
def test_rpm_out_of_bounds(tip_file, capsys, rpm, match):
    assert match in _error(capsys, ["campbell", str(tip_file), "--rpm", *rpm])


def test_rpm_at_the_bound_prints_finite_nonzero_frequencies(tip_file, capsys):
    assert cli.main(["campbell", str(tip_file), "--rpm", "0", "100000", "3", "--count", "4"]) == 0
    rows = capsys.readouterr().out.splitlines()[2:5]
    freqs = [float(x) for row in rows for x in row.split()[1:]]
    assert len(freqs) == 12 and all(0.0 < f < 1e3 for f in freqs)


def test_model_name_with_escape_sequences_is_printed_escaped(tmp_path, capsys):
    from propwhirl.cases.registry import case_model

    evil = "evil\x1b[2J\x1b]0;pwn\x07\x9b31m"
    path = tmp_path / "evil.toml"
    io.save_model(case_model("wingtip").with_(name=evil), path)
    assert cli.main(["modes", str(path), "--count", "2"]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out and "\x9b" not in out
    assert out.splitlines()[0].startswith("evil\\x1b[2J\\x1b]0;pwn\\x07\\x9b31m: in-vacuo modes")


def test_no_help_shows_docstring_markup(capsys):
    """Issue 35 item 8: ``certify --help`` started with ``:mod:`` and double back-quotes; no
    command's help shows reST markup."""
    import argparse

    parser = cli.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert {"certify", "import", "export", "analyse"} <= set(sub.choices)
    for name, p in sub.choices.items():
        text = p.format_help()
        assert ":mod:" not in text and ":func:" not in text and "``" not in text, name
