"""`propwhirl certify` (issue 24.2): exit 0 when every case clears, 1 when one does not, 2 on
bad input (before any analysis); the report folder's campaign.json and campaign.csv; the
summary table; --processes 2 gives the result of 1; an interrupted run resumes."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from propwhirl.app import cli
from propwhirl.studies import campaign as C

CAMPAIGN = """
format = "propwhirl-campaign"
format_version = 1
name = "small"
model = "{model}"
[regulation]
name = "cs25"
[envelope]
airspeed = "TAS"
V_D_m_per_s = {vd}
altitudes_m = [0.0, 2438.4]
[[cases]]
name = "nominal"
[[cases]]
name = "mount at 50 %"
mount_stiffness = 0.5
[[cases]]
name = "failed damper"
mount_damping = 0.0
"""


def _write(tmp_path: Path, model: Path, vd: float) -> Path:
    path = tmp_path / "c.toml"
    path.write_text(CAMPAIGN.format(model=model.as_posix(), vd=vd))
    return path


@pytest.fixture(scope="module")
def vcrit(small_file) -> float:
    """The least V_crit of the small campaign's cases and points (a run of its own)."""
    from propwhirl.io.campaign_files import loads

    c = C.from_spec(loads(CAMPAIGN.format(model=Path(small_file).as_posix(), vd=50.0), "c.toml"))
    return min(r.critical_speed for r in C.run_campaign(c).rows)


def test_cleared_exits_0_and_writes_the_report(small_file, vcrit, tmp_path, capsys):
    out = tmp_path / "report"
    assert cli.main(["certify", str(_write(tmp_path, small_file, vcrit / 1.15 / 1.01)),
                     "--out", str(out), "--quiet", "--no-pdf"]) == 0
    text = capsys.readouterr().out
    assert "3 of 3 cases cleared" in text and "CLEARED" in text and "failed damper" in text
    r = C.CampaignResult.load(out / "campaign.json")
    assert r.cleared and len(r.rows) == 6 and r.factor == 1.15
    doc = json.loads((out / "campaign.json").read_text())
    assert doc["format"] == "propwhirl.campaign/2" and doc["cleared"] is True
    lines = (out / "campaign.csv").read_text().splitlines()
    assert len(lines) == 7 and lines[0].split(",")[:3] == ["case", "description", "altitude_m"]
    assert not (out / "campaign.json.partial").exists()
    assert (out / "report.html").exists() and not (out / "report.pdf").exists()


def test_not_cleared_exits_1(small_file, vcrit, tmp_path, capsys):
    out = tmp_path / "report"
    assert cli.main(["certify", str(_write(tmp_path, small_file, vcrit / 1.15 / 0.99)),
                     "--out", str(out), "--quiet", "--no-report"]) == 1
    text = capsys.readouterr().out
    assert "NOT CLEARED" in text
    assert not C.CampaignResult.load(out / "campaign.json").cleared


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace('name = "cs25"', 'name = "cs26"'), ["c.toml", "[regulation] name", "cs26"]),
    (lambda t: t.replace("mount_damping = 0.0", "mount_damping = -1.0"),
     ["c.toml", "[cases[2]] mount_damping", "-1.0"]),
    (lambda t: t.replace("mount_damping = 0.0", "rpm_factor = 1.1"),
     ["c.toml", "[cases[2]]", "rpm_factor", "fixed-pitch"]),
])
def test_bad_input_exits_2_before_any_analysis(small_file, tmp_path, capsys, monkeypatch, edit,
                                               words):
    monkeypatch.setattr(C, "evaluate_point", lambda t: pytest.fail("an analysis ran"))
    path = _write(tmp_path, small_file, 50.0)
    path.write_text(edit(path.read_text()))
    assert cli.main(["certify", str(path), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and all(w in err for w in words), err
    assert not (tmp_path / "r").exists()


def test_bad_options_exit_2(small_file, tmp_path, capsys):
    path = _write(tmp_path, small_file, 50.0)
    assert cli.main(["certify", str(path), "--out", str(tmp_path / "r"), "--processes", "0"]) == 2
    assert "--processes" in capsys.readouterr().err
    (tmp_path / "file").write_text("x")
    assert cli.main(["certify", str(path), "--out", str(tmp_path / "file")]) == 2
    assert "must be a folder" in capsys.readouterr().err
    assert cli.main(["certify", str(tmp_path / "none.toml"), "--out", str(tmp_path / "r")]) == 2


def test_two_processes_give_the_result_of_one(small_file, vcrit, tmp_path):
    path = _write(tmp_path, small_file, vcrit / 1.15 / 1.01)
    for n in ("1", "2"):
        assert cli.main(["certify", str(path), "--out", str(tmp_path / n), "--quiet",
                         "--processes", n, "--no-report"]) == 0
    assert (tmp_path / "1" / "campaign.json").read_text() == \
        (tmp_path / "2" / "campaign.json").read_text()
    assert (tmp_path / "1" / "campaign.csv").read_text() == \
        (tmp_path / "2" / "campaign.csv").read_text()


def test_an_interrupted_campaign_resumes(small_file, vcrit, tmp_path, capsys, monkeypatch):
    path = _write(tmp_path, small_file, vcrit / 1.15 / 1.01)
    plain = tmp_path / "plain"
    assert cli.main(["certify", str(path), "--out", str(plain), "--quiet", "--no-report"]) == 0
    real = C.evaluate_point
    seen = []

    def interrupted_at_the_third(task):
        seen.append(task)
        if len(seen) == 3:
            raise KeyboardInterrupt
        return real(task)

    monkeypatch.setattr(C, "evaluate_point", interrupted_at_the_third)
    out = tmp_path / "report"
    assert cli.main(["certify", str(path), "--out", str(out), "--quiet"]) == cli.EXIT_INTERRUPTED
    assert "2 of 6 points finished kept in" in capsys.readouterr().err
    partial = out / "campaign.json.partial"
    assert partial.exists() and not (out / "campaign.json").exists()
    seen.clear()
    monkeypatch.setattr(C, "evaluate_point", lambda t: (seen.append(t), real(t))[1])
    assert cli.main(["certify", str(path), "--out", str(out), "--quiet", "--resume",
                     "--no-report"]) == 0
    assert len(seen) == 4                   # only the points the partial file lacked
    assert (out / "campaign.json").read_text() == (plain / "campaign.json").read_text()
    assert not partial.exists()


def test_a_dask_scheduler_gives_the_result_of_one_process(small_file, vcrit, tmp_path):
    """--scheduler (the Dask route, the distributed extra) on an in-process LocalCluster: the
    same campaign.json and campaign.csv as --processes 1."""
    distributed = pytest.importorskip("distributed", reason="the [distributed] extra is not "
                                                           "installed")
    path = _write(tmp_path, small_file, vcrit / 1.15 / 1.01)
    assert cli.main(["certify", str(path), "--out", str(tmp_path / "one"), "--quiet",
                     "--processes", "1", "--no-report"]) == 0
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        assert cli.main(["certify", str(path), "--out", str(tmp_path / "dask"), "--quiet",
                         "--scheduler", cluster.scheduler_address, "--no-report"]) == 0
    for name in ("campaign.json", "campaign.csv"):
        assert (tmp_path / "dask" / name).read_text() == (tmp_path / "one" / name).read_text()
    assert len(C.CampaignResult.load(tmp_path / "dask" / "campaign.json").rows) == 6
