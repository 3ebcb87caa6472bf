"""Fuzz: the command line's outputs and option combinations (issue 20, items 6-8).  Each case
draws a command, a path (or none) for each of its outputs from a small set of names that
collide (``X``, ``./X``, ``sub/../X``, ``X.partial`` ...), and the options that can be refused
(--plot-modes, --animate, --grid, --warm-start, boundary's --contour/--thesis/--oscillatory).
An independent oracle says whether the options are acceptable; then either they are, and the
command reaches its work (the analysis entry point, replaced by a counter that raises), or
they are not, and the command exits 2 with one line on stderr without the entry point having
been called."""
from __future__ import annotations

import os

import pytest
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, record
from helpers.before_work import WorkStarted, count_work
from propwhirl.app.cli import main

#: Output names: some are one file (X, ./X, sub/../X), some a partial-results file of X,
#: one the model file, one in a folder that does not exist, some not a plot format.
NAMES = ["X", "./X", "sub/../X", "X.partial", "X.partial.fine", "Y.png", "sub/Y.png",
         "A.gif", "m.toml", "missing/W", "sub"]
PLOT_FORMATS = {"png", "gif", "svg", "pdf"}          # of the suffixes above: X has none (png)

OUTPUTS = {"analyse": ["--json", "--csv", "--summary-csv", "--events-csv", "--plot", "--animate"],
           "sweep": ["--json", "--csv", "--plot"], "map": ["--json", "--csv", "--plot"],
           "boundary": ["--json", "--csv", "--plot"], "clearance": ["--json", "--csv", "--plot"],
           "sensitivity": ["--json", "--plot"]}
HEAD = {"analyse": [], "sweep": ["--param", "propellers[0].propeller.f_psi", "4", "10", "3"],
        "map": ["--param", "propellers[0].propeller.f_psi", "4", "10", "3",
                "--param", "wing.EI*", "1", "2", "2"],
        "boundary": ["--params", "propellers[0].propeller.f_theta",
                     "propellers[0].propeller.f_psi", "--speed", "150"],
        "clearance": ["--vd", "100"], "sensitivity": []}


def _key(path: str) -> str:
    return os.path.realpath(path)


def _acceptable(command: str, outputs: dict[str, str], extra: dict) -> bool:
    """The oracle: may these outputs and options be used (written from the rules, not the code)."""
    for option, path in outputs.items():
        if path.startswith("missing/") or os.path.isdir(path):
            return False                            # no such folder / a folder, not a file
        suffix = os.path.splitext(path)[1][1:].lower() or "png"
        if option == "--plot" and suffix not in PLOT_FORMATS:
            return False
        if option == "--animate" and suffix != "gif":
            return False
    keys = [_key(p) for p in outputs.values()]
    if len(set(keys)) < len(keys) or _key("m.toml") in keys:
        return False                                # two outputs on one file, or on the model
    if command in ("sweep", "map") and "--json" in outputs:
        partial = _key(outputs["--json"]) + ".partial"
        passes = [partial + p for p in (".coarse", ".fine", ".full-range")]
        if any(k == partial or (extra.get("warm_start") and k in passes) for k in keys):
            return False
    n = extra.get("plot_modes")
    if n is not None and (n < 1 or not ("--plot" in outputs or extra.get("summary"))):
        return False
    if extra.get("thesis") and not extra.get("contour"):
        return False                                # --thesis has no effect without --contour
    if extra.get("oscillatory") and extra.get("contour"):
        return False                                # nor --oscillatory with it
    grid = extra.get("grid")
    if grid is not None and grid != 0 and not 2 <= grid <= 60:
        return False
    return True


@st.composite
def cases(draw):
    command = draw(st.sampled_from(sorted(OUTPUTS)))
    outputs = {}
    for option in OUTPUTS[command]:
        name = draw(st.one_of(st.none(), st.sampled_from(NAMES)))
        if name is not None:
            outputs[option] = name
    extra: dict = {}
    if command == "analyse":
        extra["plot_modes"] = draw(st.one_of(st.none(), st.integers(-3, 12)))
        extra["summary"] = draw(st.booleans())
    if command in ("sweep", "map"):
        extra["warm_start"] = draw(st.booleans())
    if command == "boundary":
        extra["grid"] = draw(st.one_of(st.none(), st.integers(-5, 1_000_000)))
        for flag in ("contour", "thesis", "oscillatory"):
            extra[flag] = draw(st.booleans())
    return command, outputs, extra


def _argv(command: str, outputs: dict[str, str], extra: dict) -> list[str]:
    argv = [command, "m.toml", *HEAD[command]]
    for option, path in outputs.items():
        argv += [option, path]
    if extra.get("plot_modes") is not None:
        argv += ["--plot-modes", str(extra["plot_modes"])]
    if extra.get("summary"):
        argv.append("--summary")
    if extra.get("warm_start"):
        argv.append("--warm-start")
    argv += [f"--{flag}" for flag in ("contour", "thesis", "oscillatory") if extra.get(flag)]
    if extra.get("grid") is not None:
        argv += ["--grid", str(extra["grid"])]
    return argv


@pytest.fixture(scope="module")
def folder(tmp_path_factory, base_text):
    """A folder with the model file m.toml and a subfolder sub."""
    path = tmp_path_factory.mktemp("cli-options")
    (path / "m.toml").write_text(base_text)
    (path / "sub").mkdir()
    return path


@FUZZ
@given(case=cases())
def test_cli_options_refused_before_the_work_or_accepted(folder, capsys, case):
    command, outputs, extra = case
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(folder)
        work = count_work(mp)
        ok = _acceptable(command, outputs, extra)
        argv = _argv(command, outputs, extra)
        try:
            code = main(argv)
        except WorkStarted:
            code = None
        err = capsys.readouterr().err
        before = sorted(p.name for p in folder.iterdir())
    assert before == ["m.toml", "sub"] and not any((folder / "sub").iterdir())  # nothing written
    if ok:
        assert code is None and len(work) == 1, (argv, err)
        record(f"cli options: {command}", "accepted")
    else:
        assert code == 2 and work == [], (argv, code, err)
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert len(lines) == 1 and lines[0].startswith("propwhirl: error:"), err
        record(f"cli options: {command}", "exit 2")
