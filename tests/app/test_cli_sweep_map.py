"""`propwhirl sweep` and `propwhirl map`: a model file or a case name, --json/--csv/--plot
outputs that parse, the figures' content."""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from propwhirl import io
from propwhirl.analysis.stability import analyse
from propwhirl.app import cli
from propwhirl.studies import paths as P
from propwhirl.studies.sweeps import CriticalMap

PNG = b"\x89PNG\r\n\x1a\n"


def test_sweep_of_a_model_file_writes_json_csv_plot(small_file, tmp_path, capsys):
    out = {k: tmp_path / f"s.{k}" for k in ("json", "csv", "png")}
    code = cli.main(["sweep", str(small_file), "--param", "propellers[0].propeller.f_psi", "4", "10", "3",
                     "--speeds", "10", "350", "20", "--json", str(out["json"]), "--csv", str(out["csv"]),
                     "--plot", str(out["png"]), "--no-warm-start"])
    assert code == 0
    text = capsys.readouterr().out
    assert "critical speed over propellers[0].propeller.f_psi (3 values)" in text
    r = CriticalMap.load(out["json"])
    assert r.axes[0].values.tolist() == [4.0, 7.0, 10.0] and r.axes[0].design == 7.0
    # each point is the analysis of the model file's variant (over the whole range: not
    # warm-started; the warm-started map equals it to the crossing accuracy, test_cli_map_warm)
    model = io.load_model(small_file)
    for k, f in enumerate([4.0, 7.0, 10.0]):
        c = analyse(P.set_value(model, "propellers[0].propeller.f_psi", f),
                    np.arange(10.0, 351.0, 20.0)).critical
        assert r.critical_speed[k] == c.V
    rows = list(csv.DictReader(out["csv"].read_text().splitlines()[1:]))   # after the count
    assert len(rows) == 3 and float(rows[1]["critical_speed [m/s]"]) == r.critical_speed[1]
    assert out["png"].read_bytes()[:8] == PNG


def test_map_of_a_case_writes_json_csv_plot(tmp_path, capsys):
    out = {k: tmp_path / f"m.{k}" for k in ("json", "csv", "png")}
    code = cli.main(["map", "isolated-propeller", "--param", "propeller.f_theta", "4", "10", "3",
                     "--param", "propeller.f_psi", "4", "10", "3", "--speeds", "10", "600", "20",
                     "--json", str(out["json"]), "--csv", str(out["csv"]), "--plot", str(out["png"]),
                     "--processes", "2"])
    assert code == 0
    d = json.loads(out["json"].read_text())
    assert [a["path"] for a in d["axes"]] == ["propeller.f_theta", "propeller.f_psi"]
    assert len(d["columns"]["critical_speed"]) == 9
    rows = list(csv.DictReader(out["csv"].read_text().splitlines()[1:]))   # after the count
    assert len(rows) == 9 and rows[0]["propeller.f_theta [Hz]"] == "4.0"
    assert out["png"].read_bytes()[:8] == PNG
    assert "lowest critical speed" in capsys.readouterr().out


def test_list_params(capsys):
    assert cli.main(["sweep", "wingtip", "--list-params"]) == 0
    text = capsys.readouterr().out
    assert "propellers[0].propeller.f_theta [Hz] in [1e-3, 1000]: uncoupled pitch frequency" in text
    assert "wing.EI*: bending rigidity" in text


@pytest.mark.parametrize("argv, match", [
    (["sweep", "nowhere", "--param", "x", "1", "2", "2"], "neither a model file"),
    (["sweep", "wingtip", "--param", "wing.gj", "1", "2", "2"], "nearest valid paths: wing.GJ"),
    (["sweep", "wingtip", "--param", "wing.aero_model", "1", "2", "2"], "not a number"),
    (["sweep", "wingtip", "--param", "wing.GJ", "1", "2", "2.5"], "N = 2.5 is invalid"),
    (["sweep", "wingtip", "--param", "wing.GJ", "1", "x", "2"], "must be numbers"),
    (["sweep", "wingtip", "--param", "wing.GJ", "1", "1", "3"], "must differ from START"),
    (["sweep", "wingtip"], "give --param"),
    (["map", "wingtip", "--param", "wing.GJ*", "1", "2", "2"], "twice"),
])
def test_errors_are_one_line(argv, match, capsys):
    import re

    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("propwhirl: error:") and "\n" not in err
    assert re.search(match, err), err


def test_a_failing_point_is_reported_and_kept(tmp_path, capsys):
    """A value the model refuses at one point (issue 12.5): its row has kind "error" and the
    message, the others are analysed, stderr says how many failed; exit 0.  (A value outside
    the path's declared range stops the study before any analysis, issue 20.6.)"""
    import json

    out = tmp_path / "s.json"
    argv = ["sweep", "isolated-propeller", "--param", "propeller.hub_radius", "5", "0.125", "2",
            "--speeds", "100", "300", "100", "--json", str(out), "--quiet"]
    assert cli.main(argv) == 0
    err = capsys.readouterr().err
    assert "1 points failed" in err and "hub_radius = 5.0 m is invalid: must be < radius" in err
    cols = json.loads(out.read_text())["columns"]
    assert cols["kind"][0] == "error" and cols["kind"][1] != "error"
    assert not (tmp_path / "s.json.partial").exists()


# ----------------------------------------------------------------------------- figures
def _map_result(kinds):
    from propwhirl.studies.sweeps import RESULT_UNITS, Axis

    V = np.array([[150.0, 160.0, 170.0], [140.0, 155.0, np.nan], [130.0, 145.0, np.nan]])
    cols = {k: np.zeros((3, 3)) for k in RESULT_UNITS}
    cols["critical_speed"] = V
    cols["kind"] = np.array(kinds, dtype=object)
    cols["critical_mode"] = np.full((3, 3), "forward 1", dtype=object)
    axes = (Axis("propellers[0].propeller.f_theta", np.array([3.0, 6.0, 9.0]), "Hz", 7.0),
            Axis("propellers[0].propeller.f_psi", np.array([3.0, 6.0, 9.0]), "Hz", 5.0))
    return CriticalMap("test model", axes, cols)


def test_map_figure_content(tmp_path):
    pytest.importorskip("matplotlib")
    from propwhirl.app import plots

    kinds = [["flutter", "flutter", "flutter"], ["divergence", "flutter", "none"],
             ["divergence", "divergence", "none"]]
    fig = plots.critical_map(_map_result(kinds), path=tmp_path / "m.png")
    assert (tmp_path / "m.png").read_bytes()[:8] == PNG
    ax = fig.axes[0]
    assert ax.get_xlabel() == "propellers[0].propeller.f_theta [Hz]"
    assert ax.get_ylabel() == "propellers[0].propeller.f_psi [Hz]"
    assert fig.axes[1].get_ylabel() == "critical speed [m/s]"          # the colour bar
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["no instability in the speed range", "critical: divergence",
                      "critical: flutter (plain)", "design point (7, 5)"]
    star = [ln for ln in ax.get_lines() if ln.get_marker() == "*"]
    assert len(star) == 1 and star[0].get_xdata()[0] == 7.0 and star[0].get_ydata()[0] == 5.0
    hatches = {h for c in ax.collections for h in (getattr(c, "hatches", None) or []) if h}
    assert {"//", "xx"} <= hatches
    # without divergence and without a design point: neither is drawn
    r = _map_result([["flutter"] * 3] * 3)
    r = CriticalMap(r.model_name, tuple(type(a)(a.path, a.values, a.unit, None) for a in r.axes),
                    {**r.columns, "critical_speed": np.full((3, 3), 150.0)})
    fig2 = plots.critical_map(r)
    labels2 = [t.get_text() for t in fig2.axes[0].get_legend().get_texts()]
    assert labels2 == ["critical: flutter (plain)"]


def test_sweep_figure_content():
    pytest.importorskip("matplotlib")
    from propwhirl.app import plots
    from propwhirl.studies.sweeps import RESULT_UNITS, Axis

    cols = {k: np.zeros(4) for k in RESULT_UNITS}
    cols["critical_speed"] = np.array([120.0, 150.0, 170.0, np.nan])
    cols["kind"] = np.array(["divergence", "flutter", "flutter", "none"], dtype=object)
    cols["critical_mode"] = np.array(["backward 1", "forward 1", "forward 1", ""], dtype=object)
    r = CriticalMap("m", (Axis("wing.EI*", np.array([0.5, 1.0, 1.5, 2.0]), "", 1.0),), cols)
    fig = plots.critical_sweep(r)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "wing.EI* (factor)" and ax.get_ylabel() == "critical speed [m/s]"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["critical speed", "critical: flutter", "critical: divergence",
                      "no instability in the speed range", "design value 1"]
    assert [t.get_text() for t in ax.texts] == ["backward 1", "forward 1"]
    red = [ln for ln in ax.get_lines() if ln.get_label() == "critical: flutter"][0]
    assert red.get_xdata().tolist() == [1.0, 1.5]
    with pytest.raises(Exception, match="needs two parameters"):
        plots.critical_map(r)
