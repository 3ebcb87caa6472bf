"""Every option the command line can refuse is refused before the work (issue 20, items 6-8):
the analysis entry points are replaced by a counter that raises, and a bad option must give
exit 2 (one line on stderr) with the counter at 0.  Two outputs on one path (also ``./X`` vs
``X``, the partial-results file ``X.partial`` of one output against another, an output on the
model file) are refused; a study whose every point failed exits 2, one with some failed points 0.
"""
from __future__ import annotations

import sys

import pytest

from helpers.before_work import count_work
from propwhirl.app import cli


@pytest.fixture
def work(monkeypatch):
    """Every analysis entry point counts its calls and raises; yields the calls."""
    return count_work(monkeypatch)


@pytest.fixture
def here(tmp_path, monkeypatch):
    """Run in a fresh folder (relative output paths land there)."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _refused(capsys, work, argv) -> str:
    code = cli.main(argv)
    err = capsys.readouterr().err
    assert work == [], f"the work started: {work}"
    assert code == 2, err
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1, err
    return err


SWEEP = ["--param", "propellers[0].propeller.f_psi", "4", "10", "3"]
BOUNDARY = ["--params", "propellers[0].propeller.f_theta", "propellers[0].propeller.f_psi",
            "--speed", "150"]


def _argv(small_file, command: str, tail: list[str]) -> list[str]:
    model = {"modes": [str(small_file)], "campbell": [str(small_file), "--rpm", "0", "100", "3"],
             "analyse": [str(small_file)], "sweep": [str(small_file), *SWEEP],
             "boundary": [str(small_file), *BOUNDARY], "clearance": [str(small_file), "--vd", "100"],
             "sensitivity": [str(small_file)]}.get(command, [])
    return [command, *model, *tail]


@pytest.mark.parametrize("argv", [
    ["analyse", "M", "--json", "a.json", "--plot", "a.png", "--animate", "a.gif", "--summary",
     "--plot-modes", "4"],
    ["modes", "M"],
    ["campbell", "M", "--rpm", "0", "100", "3", "--plot", "c.png"],
    ["sweep", "M", *SWEEP, "--json", "s.json", "--csv", "s.csv", "--plot", "s.png"],
    ["map", "M", *SWEEP, "--param", "wing.EI*", "1", "2", "2", "--plot", "m.png"],
    ["boundary", "M", *BOUNDARY, "--grid", "60", "--plot", "b.png"],
    ["boundary", "M", *BOUNDARY, "--contour", "--json", "b.json"],
    ["clearance", "M", "--vd", "100", "--json", "c.json"],
    ["sensitivity", "M", "--plot", "s.png"],
    ["reproduce", "--only", "t7", "--json", "r.json"],
    ["run", "--out", "out"],
    ["derivatives", "--blades", "3", "--radius", "1", "--chord", "0.2", "--speed", "50",
     "--rpm", "1000"],
])
def test_good_options_reach_the_work(small_file, here, capsys, work, argv):
    """The counter sees each command's work (so its 0 above is not vacuous)."""
    with pytest.raises(AssertionError, match="the work started"):
        cli.main([str(small_file) if a == "M" else a for a in argv])
    assert len(work) == 1


# ---------------------------------------------------------------- item 7: outputs on one path
@pytest.mark.parametrize("command, tail, match", [
    ("analyse", ["--json", "X", "--csv", "X"], "--csv X and --json X are the same file"),
    ("analyse", ["--json", "X", "--csv", "./X"], "--csv ./X and --json X are the same file"),
    ("analyse", ["--summary-csv", "S", "--events-csv", "S"],
     "--events-csv S and --summary-csv S are the same file"),
    ("analyse", ["--plot", "P.png", "--json", "sub/../P.png"], "are the same file"),
    ("analyse", ["--animate", "A.gif", "--events-csv", "A.gif"], "are the same file"),
    ("sweep", ["--json", "X", "--csv", "X"], "--csv X and --json X are the same file"),
    ("sweep", ["--json", "X", "--csv", "X.partial"],
     "--csv X.partial is the partial-results file of --json X"),
    ("sweep", ["--json", "X", "--csv", "./X.partial"],
     "--csv ./X.partial is the partial-results file of --json X"),
    ("sweep", ["--json", "X", "--csv", "X.partial.coarse", "--warm-start"],
     "--csv X.partial.coarse is the partial-results file of --json X"),
    ("boundary", ["--json", "B", "--csv", "./B"], "--csv ./B and --json B are the same file"),
    ("clearance", ["--json", "C", "--plot", "C"], "--json C and --plot C are the same file"),
    ("sensitivity", ["--json", "S.png", "--plot", "S.png"], "are the same file"),
])
def test_two_outputs_on_one_path_are_refused_before_the_work(small_file, here, capsys, work,
                                                             command, tail, match):
    (here / "sub").mkdir()
    err = _refused(capsys, work, _argv(small_file, command, tail))
    assert match in err
    assert not any(p.is_file() for p in here.iterdir())          # nothing written


def test_map_outputs_on_one_path_are_refused(small_file, here, capsys, work):
    err = _refused(capsys, work, ["map", str(small_file), *SWEEP, "--param", "wing.EI*", "1", "2",
                                  "2", "--json", "M", "--csv", "M.partial"])
    assert "--csv M.partial is the partial-results file of --json M" in err


def test_reproduce_output_folder_is_checked_before_the_cases(here, capsys, work):
    """reproduce has one output: its folder is checked before the cases run."""
    err = _refused(capsys, work, ["reproduce", "--only", "t7", "--json", "missing/r.json"])
    assert "does not exist" in err


@pytest.mark.parametrize("command, option", [
    ("analyse", "--json"), ("analyse", "--csv"), ("sweep", "--csv"), ("clearance", "--json"),
])
def test_an_output_on_the_model_file_is_refused(small_file, tmp_path, capsys, work, command,
                                                option):
    model = tmp_path / "m.toml"
    model.write_bytes(small_file.read_bytes())
    before = model.read_bytes()
    argv = _argv(small_file, command, [option, f"{tmp_path}/./m.toml"])
    argv[argv.index(str(small_file))] = str(model)
    err = _refused(capsys, work, argv)
    assert f"is the model file MODEL {model}" in err
    assert model.read_bytes() == before


def test_distinct_outputs_are_accepted(small_file, here, capsys):
    """The same names in different folders, and X beside X.json, are different files."""
    (here / "a").mkdir()
    code = cli.main(["analyse", str(small_file), "--speeds", "10", "350", "20", "--json", "X",
                     "--csv", "a/X", "--summary-csv", "X.json", "--events-csv", "X.partial"])
    assert code == 0, capsys.readouterr().err
    assert all((here / p).is_file() for p in ("X", "a/X", "X.json", "X.partial"))


# ----------------------------------------------------- items 6 and 8: options refused first
@pytest.mark.parametrize("tail, match", [
    (["--plot-modes", "-1", "--summary"], "--plot-modes = -1 is invalid: must be an integer >= 1"),
    (["--plot-modes", "0", "--plot", "p.png"], "--plot-modes = 0 is invalid: must be an integer >= 1"),
    (["--plot-modes", "3"], "--plot-modes 3 needs --plot or --summary"),
    (["--animate", "a.png"], "--animate a.png: must end in .gif"),
    (["--animate", "a"], "--animate a: must end in .gif"),
    (["--plot", "p.notaformat"], "format 'notaformat' is not supported"),
    (["--json", "missing/a.json"], "--json missing/a.json: the folder 'missing' does not exist"),
    (["--summary-csv", "missing/s.csv"], "--summary-csv missing/s.csv: the folder"),
    (["--events-csv", "."], "--events-csv .: is a folder, not a file"),
])
def test_analyse_options_are_refused_before_the_analysis(small_file, here, capsys, work, tail, match):
    assert match in _refused(capsys, work, ["analyse", str(small_file), *tail])


@pytest.mark.parametrize("argv, match", [
    (["boundary", "M", *BOUNDARY, "--grid", "1000000", "--plot", "b.png"],
     "--grid = 1000000 is invalid: must be 0 (none) or in [2, 60]"),
    (["boundary", "M", *BOUNDARY, "--grid", "1", "--plot", "b.png"], "--grid = 1 is invalid"),
    (["boundary", "M", *BOUNDARY, "--grid", "-3"], "--grid = -3 is invalid"),
    (["boundary", "M", *BOUNDARY, "--plot", "b.nope"], "format 'nope' is not supported"),
    (["map", "M", *SWEEP, "--param", "wing.EI*", "1", "1", "1", "--plot", "m.png"],
     "map --plot needs at least 2 values of each parameter: --param wing.EI* has N = 1"),
    (["boundary", "M", *BOUNDARY, "--thesis"], "--thesis is for --contour"),
    (["boundary", "M", *BOUNDARY, "--contour", "--oscillatory"],
     "--oscillatory is for the neutral-stability curve, it has no effect with --contour"),
    (["sweep", "M", *SWEEP, "--plot", "s.nope"], "format 'nope' is not supported"),
    (["sweep", "M", "--list-params", "--json", "s.json"],
     "sweep --list-params only lists the parameter paths: --json would be ignored"),
    (["reproduce", "--only", "t7", "zzz"], "--only zzz: no id of the thesis's values starts with it"),
    (["sweep", "M", *SWEEP, "--csv", "missing/s.csv"], "the folder 'missing' does not exist"),
    (["clearance", "M", "--vd", "100", "--plot", "missing/c.png"], "does not exist"),
    (["sensitivity", "M", "--top", "0"], "--top 0 is invalid"),
    (["sensitivity", "M", "--plot", "s.nope"], "format 'nope' is not supported"),
    (["campbell", "M", "--rpm", "0", "100", "3", "--count", "0"], "--count = 0 is invalid"),
    (["campbell", "M", "--rpm", "0", "100", "3", "--plot", "c.nope"], "is not supported"),
    (["modes", "M", "--count", "0"], "--count = 0 is invalid"),
    (["sweep", "M", *SWEEP, "--processes", "0"], "--processes = 0 is invalid"),
    (["reproduce", "--only", "t7", "--processes", "-2"], "--processes = -2 is invalid"),
    (["run", "--out", "M"], "is not a folder"),
    (["case", "wingtip", "--save", "missing/w.toml"], "does not exist"),
])
def test_study_options_are_refused_before_the_work(small_file, here, capsys, work, argv, match):
    argv = [str(small_file) if a == "M" else a for a in argv]
    if argv[0] == "run":
        argv[-1] = str(small_file)           # a file where the output folder is meant
    assert match in _refused(capsys, work, argv)


@pytest.mark.parametrize("argv", [
    ["analyse", "M", "--plot", "p.png"],
    ["analyse", "M", "--animate", "a.gif"],
    ["campbell", "M", "--rpm", "0", "100", "3", "--plot", "c.png"],
    ["sweep", "M", *SWEEP, "--plot", "s.png"],
    ["map", "M", *SWEEP, "--param", "wing.EI*", "1", "2", "2", "--plot", "m.png"],
    ["boundary", "M", *BOUNDARY, "--plot", "b.png"],
    ["clearance", "M", "--vd", "100", "--plot", "c.png"],
    ["sensitivity", "M", "--plot", "s.png"],
])
def test_plots_without_matplotlib_are_refused_before_the_work(small_file, here, capsys, work,
                                                              monkeypatch, argv):
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "matplotlib", None)       # import matplotlib fails
    argv = [str(small_file) if a == "M" else a for a in argv]
    err = _refused(capsys, work, argv)
    assert "needs matplotlib, which is not installed: pip install propwhirl[plots]" in err


# --------------------------------------------------------- item 6: a study whose points fail
def _failing(monkeypatch, fail_all: bool):
    """Every point's analysis (or only the first) raises, as a failing point does."""
    from propwhirl.studies import sweeps

    seen = []
    original = sweeps._evaluate

    def evaluate(task):
        seen.append(task)
        if fail_all or len(seen) == 1:
            raise RuntimeError(f"no convergence at point {len(seen)}")
        return original(task)
    monkeypatch.setattr(sweeps, "_evaluate", evaluate)


def test_a_sweep_whose_every_point_failed_exits_2(small_file, here, capsys, monkeypatch):
    _failing(monkeypatch, fail_all=True)
    code = cli.main(["sweep", str(small_file), *SWEEP, "--json", "s.json", "--csv", "s.csv"])
    out, err = capsys.readouterr()
    assert code == 2
    assert err == ("propwhirl: error: sweep: every one of the 3 points failed (first: "
                   "RuntimeError: no convergence at point 1): the outputs hold each point's "
                   "error (column error)\n")
    assert "wrote s.json" in out and "wrote s.csv" in out       # the errors are kept
    assert not (here / "s.json.partial").exists()


def test_a_map_whose_every_point_failed_exits_2(small_file, here, capsys, monkeypatch):
    _failing(monkeypatch, fail_all=True)
    code = cli.main(["map", str(small_file), *SWEEP, "--param", "wing.EI*", "1", "2", "2"])
    assert code == 2
    assert "map: every one of the 6 points failed" in capsys.readouterr().err


def test_a_sweep_with_some_failed_points_exits_0(small_file, here, capsys, monkeypatch):
    _failing(monkeypatch, fail_all=False)
    code = cli.main(["sweep", str(small_file), *SWEEP, "--speeds", "10", "350", "20"])
    err = capsys.readouterr().err
    assert code == 0
    assert err.startswith("propwhirl: warning: 1 points failed (column error):")


@pytest.mark.parametrize("command", ["sweep", "map"])
def test_the_exit_codes_of_failed_points_are_documented(capsys, command):
    with pytest.raises(SystemExit):
        cli.main([command, "--help"])
    text = capsys.readouterr().out
    assert "exit code 2 when every point failed" in " ".join(text.split())
    assert "0 when some failed" in " ".join(text.split())
    assert "every point failed" in cli.__doc__


# ------------------------------------------------------------- issue 33, items 1 and 2
CAMPAIGN = """
format = "propwhirl-campaign"
format_version = 1
model = "{model}"
[regulation]
name = "cs25"
[envelope]
airspeed = "TAS"
V_D_m_per_s = 50.0
altitudes_m = [0.0]
[[cases]]
name = "nominal"
"""


@pytest.fixture
def no_campaign(monkeypatch):
    """A campaign that starts fails the test (its analyses are the work)."""
    from propwhirl.studies import campaign

    monkeypatch.setattr(campaign, "run_campaign", lambda *a, **k: pytest.fail("the work started"))


@pytest.mark.parametrize("model_name", ["campaign.json", "campaign.csv", "report.html",
                                        "report.pdf", "campaign.json.partial"])
def test_certify_never_writes_over_its_model_file(small_file, here, capsys, work, no_campaign,
                                                   model_name):
    """Item 1: `certify C.toml --out .` with the model file named campaign.json (or
    report.html) exited 0, the model replaced by the results and hashed as the model."""
    (here / model_name).write_bytes(small_file.read_bytes())
    (here / "C.toml").write_text(CAMPAIGN.format(model=model_name))
    err = _refused(capsys, work, ["certify", "C.toml", "--out", ".", "--no-pdf"])
    assert err == (f"propwhirl: error: --out .: {model_name} is the model file of the campaign "
                   f"(model = '{model_name}'): give another path\n")
    assert (here / model_name).read_bytes() == small_file.read_bytes()


def test_certify_never_writes_over_its_campaign_file(small_file, here, capsys, work,
                                                     no_campaign):
    """Item 1: `certify campaign.csv --out .` overwrote the campaign file itself."""
    text = CAMPAIGN.format(model=small_file.as_posix())
    (here / "campaign.csv").write_text(text)
    err = _refused(capsys, work, ["certify", "campaign.csv", "--out", ".", "--no-report"])
    assert err == ("propwhirl: error: --out .: campaign.csv is the campaign file CAMPAIGN "
                   "campaign.csv: give another path\n")
    assert (here / "campaign.csv").read_text() == text


def test_certify_without_a_report_may_share_its_names(small_file, here, capsys, work,
                                                       no_campaign):
    """--no-report writes no report.html: a model of that name is no output's input."""
    (here / "report.html").write_bytes(small_file.read_bytes())
    (here / "C.toml").write_text(CAMPAIGN.format(model="report.html"))
    with pytest.raises(pytest.fail.Exception, match="the work started"):
        cli.main(["certify", "C.toml", "--out", ".", "--no-report"])


def test_certify_refuses_a_device_among_its_outputs(small_file, here, capsys, work,
                                                    no_campaign):
    """Item 2: a device node (our own) where campaign.csv goes: refused before the work."""
    from helpers.files import char_device, is_char_device

    (here / "C.toml").write_text(CAMPAIGN.format(model=small_file.as_posix()))
    (here / "r").mkdir()
    char_device(here / "r" / "campaign.csv")
    err = _refused(capsys, work, ["certify", "C.toml", "--out", "r", "--no-pdf"])
    assert err == ("propwhirl: error: cannot write --out r 'r/campaign.csv': it is a character "
                   "device, not a regular file (propwhirl writes regular files only)\n")
    assert is_char_device(here / "r" / "campaign.csv")


@pytest.mark.parametrize("option", ["--json", "--csv", "--summary-csv", "--plot"])
def test_an_output_on_a_device_is_refused_before_the_analysis(small_file, here, capsys, work,
                                                               option):
    """Item 2, on a device node of our own (never /dev/null itself)."""
    from helpers.files import char_device, is_char_device

    node = char_device(here / "out.png")
    err = _refused(capsys, work, ["analyse", str(small_file), option, str(node)])
    assert err == (f"propwhirl: error: {option} {node}: is a character device, not a regular "
                   "file (propwhirl writes regular files only)\n")
    assert is_char_device(node)


def test_an_output_on_a_hard_link_of_the_model_is_refused(small_file, here, capsys, work):
    """Item 1: paths compared as files — a hard link of the model is the model."""
    import os

    model = here / "m.toml"
    model.write_bytes(small_file.read_bytes())
    os.link(model, here / "same.json")
    err = _refused(capsys, work, ["analyse", str(model), "--json", "same.json"])
    assert err == (f"propwhirl: error: --json same.json is the model file MODEL {model}: give "
                   "another path\n")
