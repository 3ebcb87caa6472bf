"""`propwhirl sensitivity --verify` (issue 26, item 3): the exact sensitivities shown checked
against central differences, the 2N analyses on --processes with a progress bar (never with
--quiet), the same file from 1 and 2 processes, exit code 1 when a check is flagged."""
from __future__ import annotations

import io
import json
import sys
from dataclasses import replace

import pytest

from propwhirl import progress
from propwhirl.analysis import sensitivity as S
from propwhirl.app import cli
from propwhirl.studies import sensitivity_check as SC


class FakeTTY(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_verify_checks_the_top_n_and_writes_them(small_file, tmp_path, capsys, monkeypatch):
    """Exit code 0, the table after the sensitivities, exactly 2 analyses per parameter; the
    JSON holds the sensitivities checked and the checks; 2 processes write the same bytes."""
    calls = []
    real = SC.analyse
    monkeypatch.setattr(SC, "analyse", lambda *a, **k: calls.append(1) or real(*a, **k))
    one, two = tmp_path / "one.json", tmp_path / "two.json"
    assert cli.main(["sensitivity", str(small_file), "--verify", "--top", "3", "--quiet",
                     "--json", str(one)]) == 0
    out = capsys.readouterr().out
    assert len(calls) == 6
    assert out.index("sensitivities (normalised") < out.index("verification by central")
    assert "all 3 within tolerance" in out
    doc = json.loads(one.read_text())
    assert doc["format"] == "propwhirl.sensitivity-check/1" and doc["passed"] is True
    assert doc["analyses"] == 6 and len(doc["sensitivities"]["sensitivities"]) == 3
    assert [c["path"] for c in doc["checks"]] == \
        [s["path"] for s in doc["sensitivities"]["sensitivities"]]
    assert cli.main(["sensitivity", str(small_file), "--verify", "--top", "3", "--quiet",
                     "--processes", "2", "--json", str(two)]) == 0
    assert two.read_bytes() == one.read_bytes()


def test_without_verify_the_sensitivities_file_is_unchanged(small_file, tmp_path, capsys):
    path = tmp_path / "s.json"
    assert cli.main(["sensitivity", str(small_file), "--top", "2", "--json", str(path)]) == 0
    assert json.loads(path.read_text())["format"] == "propwhirl.sensitivities/2"
    assert "verification" not in capsys.readouterr().out


def test_a_wrong_exact_value_is_flagged_with_exit_code_1(small_file, capsys, monkeypatch):
    real = S.critical_sensitivities

    def wrong(*args, **kw):
        cs = real(*args, **kw)
        first = cs.ranked(1)[0]
        return replace(cs, sensitivities=tuple(
            replace(s, dV_dp=1.05 * s.dV_dp) if s.path == first.path else s
            for s in cs.sensitivities))

    monkeypatch.setattr(S, "critical_sensitivities", wrong)
    assert cli.main(["sensitivity", str(small_file), "--verify", "--top", "2", "--quiet"]) == 1
    out = capsys.readouterr().out
    assert "differs" in out and "1 of 2 flagged" in out


def test_the_param_ones_are_checked(small_file, capsys):
    assert cli.main(["sensitivity", str(small_file), "--verify", "--quiet",
                     "--param", "flight.density", "--param", "wing.GJ*"]) == 0
    out = capsys.readouterr().out.split("verification by central")[1]
    assert "4 analyses" in out and "flight.density" in out and "wing.GJ*" in out


def test_progress_on_a_terminal_and_none_with_quiet(small_file, monkeypatch, capsys):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    tty = FakeTTY()
    monkeypatch.setattr(sys, "stderr", tty)
    assert cli.main(["sensitivity", str(small_file), "--verify", "--top", "1"]) == 0
    assert "sensitivity checks" in tty.getvalue() and "2/2" in tty.getvalue()
    quiet = FakeTTY()
    monkeypatch.setattr(sys, "stderr", quiet)
    assert cli.main(["sensitivity", str(small_file), "--verify", "--top", "1", "--quiet"]) == 0
    assert quiet.getvalue() == ""


def test_execution_options_are_checked_before_the_analysis(small_file, capsys):
    assert cli.main(["sensitivity", str(small_file), "--verify", "--processes", "0"]) != 0
    assert "--processes" in capsys.readouterr().err


def test_processes_without_verify_are_refused_not_ignored(small_file, capsys):
    assert cli.main(["sensitivity", str(small_file), "--processes", "2"]) != 0
    err = capsys.readouterr().err
    assert "--processes 2 is for --verify" in err


def test_the_help_documents_the_exit_code(capsys):
    with pytest.raises(SystemExit):
        cli.main(["sensitivity", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--verify" in text and "exit code is then 1" in text
