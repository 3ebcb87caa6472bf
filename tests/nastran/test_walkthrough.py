"""docs/modal-structures.md, "From a BDF to a V-g-f plot and a campaign" (issue 36): its
commands run as written, in a folder of their own, with its campaign file; what the page says
of the result holds."""
from __future__ import annotations

import csv
import re
import shlex
from pathlib import Path

from propwhirl.app import cli

PAGE = Path(__file__).resolve().parents[2] / "docs" / "modal-structures.md"
TITLE = "### From a BDF to a V-g-f plot and a campaign"


def _section() -> str:
    text = PAGE.read_text()
    start = text.index(TITLE)
    end = text.index("\n## ", start)
    return text[start:end]


def test_the_walkthrough_runs_as_written(tmp_path, monkeypatch, capsys):
    section = _section()
    commands = re.search(r"```sh\n(.*?)```", section, flags=re.S).group(1)
    campaign = re.search(r"```toml\n(.*?)```", section, flags=re.S).group(1)
    (tmp_path / "campaign.toml").write_text(campaign)
    monkeypatch.chdir(tmp_path)
    lines = [line.split("#")[0].strip() for line in commands.splitlines()]
    lines = [line for line in lines if line]
    assert len(lines) == 5 and all(line.startswith("propwhirl ") for line in lines)
    for line in lines:
        assert cli.main(shlex.split(line)[1:]) == 0, line
    said = capsys.readouterr().out
    assert "divergence of wing 1 (bending) at 143.15 m/s" in said
    assert "2 of 2 cases cleared" in said and re.search(r"nominal .* 5000 .* \+14\.53 ", said)
    with open("vgf.csv", newline="") as fh:
        rows = list(csv.reader(line for line in fh if not line.startswith("#")))
    assert len(rows) > 10
    assert {"campaign.json", "campaign.csv", "report.html"} <= {
        p.name for p in (tmp_path / "report").iterdir()}
