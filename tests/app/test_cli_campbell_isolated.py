"""`propwhirl campbell`: an isolated propeller, the tracked result passed to the figure
(families, each propeller's 1P/2P lines) and the propellers' speed ratio printed."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from propwhirl import io
from propwhirl.analysis.campbell import CampbellResult, campbell
from propwhirl.app import cli
from propwhirl.cases.registry import case_model

pytest.importorskip("matplotlib")


@pytest.fixture
def recorded(monkeypatch):
    """Every call of plots.campbell_diagram (its arguments), then the real drawing."""
    from propwhirl.app import plots

    calls = []
    real = plots.campbell_diagram

    def record(*args, **kwargs):
        calls.append((args, kwargs))
        return real(*args, **kwargs)

    monkeypatch.setattr(plots, "campbell_diagram", record)
    return calls


def test_an_isolated_propeller_has_its_campbell_diagram(tmp_path, capsys, recorded):
    path = tmp_path / "iso.toml"
    assert cli.main(["case", "isolated-propeller", "--save", str(path)]) == 0
    png = tmp_path / "c.png"
    capsys.readouterr()
    assert cli.main(["campbell", str(path), "--rpm", "0", "3000", "4", "--plot", str(png)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1].split() == ["RPM", "backward", "1", "forward", "1"]
    c = campbell(io.load_model(path), np.linspace(0.0, 3000.0, 4))
    rows = np.array([[float(x) for x in ln.split()] for ln in out[2:6]])
    np.testing.assert_allclose(rows[:, 0], c.rpm)
    np.testing.assert_allclose(rows[:, 1:], c.frequency_hz, atol=5e-4)
    assert rows[-1, 1] < rows[0, 1] < rows[-1, 2]          # backward falls, forward rises
    (args, kwargs), = recorded
    result = args[0]
    assert isinstance(result, CampbellResult) and len(args) == 1   # the tracked result itself
    assert result.families == ("backward whirl", "forward whirl")
    assert png.read_bytes().startswith(b"\x89PNG")


def _two_speeds(tmp_path):
    """The two-propeller wing with its propellers at constant 2000 and 3000 rev/min."""
    m = case_model("two-propeller")
    props = tuple(replace(inst, propeller=replace(inst.propeller, operation="constant-speed",
                                                  rpm=rpm))
                  for inst, rpm in zip(m.propellers, (2000.0, 3000.0)))
    return io.save_model(m.with_(propellers=props), tmp_path / "two.toml")


def test_propellers_at_different_speeds_get_their_own_excitation_lines(tmp_path, capsys,
                                                                       recorded):
    path = _two_speeds(tmp_path)
    capsys.readouterr()
    assert cli.main(["campbell", str(path), "--rpm", "0", "4000", "3", "--count", "4",
                     "--plot", str(tmp_path / "c.png")]) == 0
    out = capsys.readouterr().out
    assert "RPM of propeller 1; propeller 2 at 1.5 x RPM" in out
    (args, _), = recorded
    assert args[0].rpm_ratio == pytest.approx((1.0, 1.5))
    from propwhirl.app import plots

    fig = plots.campbell_diagram(args[0], n_modes=4)      # what the command drew
    excitation = [ln for ln in fig.axes[0].get_lines() if ln.get_linestyle() in ("--", ":")]
    assert len(excitation) == 4                              # 1P and 2P of each speed
