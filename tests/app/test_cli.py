"""Command line: analyse, modes, campbell, case; bad input is one line on stderr, exit 2."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from propwhirl.app import cli
from propwhirl import io
from propwhirl.cases import registry
from propwhirl.analysis.stability import analyse, load
from propwhirl.analysis.vibration import campbell, label_modes

ROOT = Path(__file__).resolve().parents[2]


def small_tip_model():
    """Baseline wing with 5 elements and the baseline propeller at the tip (fast)."""
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    from propwhirl.model.systems import Installation, PropellerWing

    return PropellerWing(baseline_wing(5), baseline_flight(),
                         (Installation(baseline_propeller(), 5.7),), name="small tip model")
EXAMPLE = ROOT / "examples" / "wingtip.toml"
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def small_file(tmp_path_factory):
    """A 5-element wingtip-propeller model file (fast to analyse)."""
    path = tmp_path_factory.mktemp("models") / "small.toml"
    io.save_model(small_tip_model(), path)
    return path


@pytest.mark.parametrize("name", list(registry.CASES))
def test_case_export_round_trips(name, tmp_path, capsys):
    path = tmp_path / f"{name}.toml"
    assert cli.main(["case", name, "--save", str(path)]) == 0
    assert f"wrote {path}" in capsys.readouterr().out
    model = registry.case_model(name)
    back = io.load_model(path)
    V = np.array([10.0, 200.0])
    np.testing.assert_array_equal(back.state_matrix(V), model.state_matrix(V))
    assert cli.main(["case", name]) == 0  # without --save: the TOML on stdout
    assert io.loads(capsys.readouterr().out).name == model.name


def test_example_file_is_what_case_wingtip_writes(capsys):
    assert cli.main(["case", "wingtip"]) == 0
    assert capsys.readouterr().out == EXAMPLE.read_text(), (
        "examples/wingtip.toml is stale: regenerate it with "
        "`propwhirl case wingtip --save examples/wingtip.toml`")


def test_analyse_prints_the_summary_and_writes_results(small_file, tmp_path, capsys):
    out_json, out_csv, out_png = tmp_path / "a.json", tmp_path / "a.csv", tmp_path / "a.png"
    argv = ["analyse", str(small_file), "--speeds", "1", "350", "10", "--json", str(out_json),
            "--csv", str(out_csv), "--plot", str(out_png), "--plot-modes", "5"]
    assert cli.main(argv) == 0
    text = capsys.readouterr().out
    ref = analyse(io.load_model(small_file), np.append(np.arange(1.0, 350.0, 10.0), 350.0), vgf=True)
    assert ref.summary() in text
    saved = load(out_json)
    assert saved.events == ref.events
    assert np.array_equal(io.read_vgf_csv(out_csv)["V"], ref.sweep.table()["V"])
    assert out_png.read_bytes().startswith(PNG)


def test_speed_grid():
    np.testing.assert_array_equal(cli.speed_grid(1.0, 350.0, 10.0),
                                  np.append(np.arange(1.0, 350.0, 10.0), 350.0))
    np.testing.assert_array_equal(cli.speed_grid(10.0, 30.0, 10.0), [10.0, 20.0, 30.0])
    np.testing.assert_array_equal(cli.speed_grid(1.0, 2.5, 1.0), [1.0, 2.0, 2.5])


def test_modes_prints_the_named_in_vacuo_modes(capsys):
    assert cli.main(["modes", str(EXAMPLE), "--count", "7"]) == 0
    text = capsys.readouterr().out
    rows = [ln.split() for ln in text.splitlines()[2:]]
    expect = label_modes(io.load_model(EXAMPLE))[:7]
    assert len(rows) == 7
    for row, (label, f) in zip(rows, expect):
        assert " ".join(row[:2]) == label
        assert float(row[2]) == pytest.approx(f, abs=5e-5)
        shares = [float(x) for x in row[3:]]
        assert sum(shares) == pytest.approx(1.0, abs=3e-3)
    forward = next(r for r in rows if r[:2] == ["forward", "1"])
    assert float(forward[-1]) > 0.99  # the forward (yaw) mode at Ω = 0 is pure propeller yaw


def test_modes_of_an_isolated_propeller(tmp_path, capsys):
    path = tmp_path / "iso.toml"
    assert cli.main(["case", "isolated-propeller", "--save", str(path)]) == 0
    capsys.readouterr()
    assert cli.main(["modes", str(path)]) == 0
    rows = [ln.split() for ln in capsys.readouterr().out.splitlines()[2:]]
    assert sorted(r[0] for r in rows) == ["pitch", "yaw"]
    assert all(float(r[1]) == pytest.approx(7.0) for r in rows)  # f_theta = f_psi = 7 Hz


def test_campbell_prints_the_vibration_data(small_file, tmp_path, capsys):
    png = tmp_path / "c.png"
    assert cli.main(["campbell", str(small_file), "--rpm", "0", "5000", "3", "--count", "4",
                     "--plot", str(png)]) == 0
    lines = capsys.readouterr().out.splitlines()
    rows = [[float(x) for x in ln.split()] for ln in lines[2:5]]
    c = campbell(io.load_model(small_file), np.array([0.0, 2500.0, 5000.0]))
    rpm, f = c.rpm, c.frequency_hz
    for row, r, fr in zip(rows, rpm, f):
        assert row[0] == r
        np.testing.assert_allclose(row[1:], fr[:4], atol=5e-4)
    assert png.read_bytes().startswith(PNG)


def test_commands_run_reproduce_derivatives_are_kept(capsys):
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    text = capsys.readouterr().out
    for cmd in ("run", "reproduce", "derivatives", "analyse", "modes", "campbell", "case"):
        assert cmd in text


# ----------------------------------------------------------------------------- bad input
def _bad_files(tmp_path: Path) -> dict[str, Path]:
    text = EXAMPLE.read_text()
    files = {
        "bad toml": "x = [\n",
        "unknown field": text.replace("semi_span_m = 5.7", "semispan_m = 5.7"),
        "invalid value": text.replace("GJ_N_m2 = 200000.0", "GJ_N_m2 = -2.0"),
        "wrong type": text.replace("n_blades = 3", "n_blades = \"three\""),
        "not a model": io.dumps(io.load_model(EXAMPLE).propellers[0].propeller),
    }
    out = {}
    for name, content in files.items():
        p = tmp_path / (name.replace(" ", "_") + ".toml")
        p.write_text(content)
        out[name] = p
    return out


@pytest.mark.parametrize("case, argv_tail, message", [
    ("missing file", None, "not found"),
    ("bad toml", None, "not valid TOML"),
    ("unknown field", None, "unknown key 'semispan_m' in [wing]"),
    ("invalid value", None, "[wing] GJ_N_m2 = -2.0 is outside the valid range [1e-3, 1e12] N m^2"),
    ("wrong type", None, "[propellers.p1] n_blades = 'three' is invalid"),
    ("not a model", None, "holds a Propeller"),
    ("speeds", ["--speeds", "0", "10", "1"], "--speeds START = 0.0 m/s is invalid"),
    ("speeds", ["--speeds", "10", "5", "1"], "--speeds STOP = 5.0 m/s is invalid"),
    ("output folder", ["--json", "/nonexistent-folder/a.json"], "does not exist"),
    ("plot modes", ["--plot", "PNG", "--plot-modes", "0"], "--plot-modes = 0 is invalid"),
])
def test_analyse_bad_input_is_one_line_and_exit_2(case, argv_tail, message, tmp_path, capsys):
    files = _bad_files(tmp_path)
    model = {"missing file": tmp_path / "missing.toml"}.get(case, files.get(case, EXAMPLE))
    tail = list(argv_tail or [])
    if "PNG" in tail:
        tail[tail.index("PNG")] = str(tmp_path / "p.png")
        model = str(tmp_path / "small.toml")
        io.save_model(small_tip_model(), model)
        tail = ["--speeds", "1", "50", "25"] + tail
    assert cli.main(["analyse", str(model)] + tail) == 2
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1
    assert message in err
    assert "Traceback" not in err


@pytest.mark.parametrize("argv, message", [
    (["modes", "missing.toml"], "not found"),
    (["modes", str(EXAMPLE), "--count", "0"], "--count = 0 is invalid"),
    (["campbell", str(EXAMPLE), "--rpm", "0", "100", "2.5"], "--rpm N = 2.5 is invalid"),
    (["campbell", str(EXAMPLE), "--rpm", "-5", "100", "3"], "--rpm START = -5.0 rev/min is outside the valid range [0, 1e5] rev/min"),
    (["campbell", str(EXAMPLE), "--rpm", "0", "100", "3", "--plot", "/nonexistent-folder/c.png"],
     "does not exist"),
    (["case", "wingtip", "--save", "/nonexistent-folder/w.toml"], "does not exist"),
])
def test_other_commands_bad_input(argv, message, capsys):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1
    assert message in err


def test_campbell_needs_a_flexibly_mounted_propeller(tmp_path, capsys):
    """A wing whose propellers are all rigidly mounted has no whirl modes to follow (an
    isolated propeller is accepted: tests/app/test_cli_campbell_isolated.py)."""
    from dataclasses import replace

    from propwhirl.cases.registry import case_model

    m = case_model("wingtip")
    path = io.save_model(m.with_(propellers=tuple(replace(i, mount="rigid")
                                                  for i in m.propellers)), tmp_path / "r.toml")
    assert cli.main(["campbell", str(path), "--rpm", "0", "100", "2"]) == 2
    assert "needs a flexibly mounted propeller" in capsys.readouterr().err


def test_unknown_case_is_one_line_listing_the_names(capsys):
    assert cli.main(["case", "concorde", "--save", "/nonexistent-folder/w.toml"]) == 2
    err = capsys.readouterr().err
    assert err == ("propwhirl: error: case = 'concorde' is invalid: must be one of patil, "
                   "baseline-wing, isolated-propeller, inboard, wingtip, two-propeller\n")


def test_case_help_lists_every_named_case(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "1000")  # argparse wraps the help to the terminal width
    with pytest.raises(SystemExit) as exc:
        cli.main(["case", "--help"])
    assert exc.value.code == 0
    text = " ".join(capsys.readouterr().out.split())
    for case in registry.CASES.values():
        assert f"{case.name}: {case.summary}" in text


def test_json_output_is_valid(small_file, tmp_path, capsys):
    out = tmp_path / "x.json"
    assert cli.main(["analyse", str(small_file), "--speeds", "1", "100", "33", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["model_name"] == "small tip model" and "events" in d
