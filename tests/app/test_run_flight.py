"""`propwhirl run`: the flight line names the ISA altitude only when the flight is the ISA at
one; the V-g-f figure is computed from the model on a fine speed grid."""
from __future__ import annotations

import pytest

from propwhirl.app import run as mainjob
from propwhirl.model.flight import FlightCondition


def test_the_headline_flight_is_the_isa_at_8000_ft():
    line = next(ln for ln in mainjob.describe(mainjob.headline_model()) if "flight:" in ln)
    assert line.endswith("speed of sound 330.80 m/s (ISA, 8000 ft = 2438 m)")


@pytest.mark.parametrize("altitude_m", [-3000.0, 0.0, 2438.4, 6000.0, 10999.0])
def test_an_isa_flight_has_its_altitude(altitude_m):
    fc = FlightCondition.from_altitude(altitude_m)
    assert mainjob.isa_altitude(fc) == pytest.approx(altitude_m, abs=0.01)


@pytest.mark.parametrize("density, speed_of_sound", [
    (1.225, 330.80),                 # 8000-ft speed of sound, sea-level density: not the ISA
    (0.96287, 340.294),              # the converse
    (0.5, 295.07),                   # above 11 km the speed of sound fixes no altitude
])
def test_no_altitude_is_printed_when_it_is_not_known(density, speed_of_sound):
    fc = FlightCondition(density, speed_of_sound)
    assert mainjob.isa_altitude(fc) is None
    assert mainjob.altitude_text(fc) == ""
    model = mainjob.headline_model().with_(flight=fc)
    line = next(ln for ln in mainjob.describe(model) if "flight:" in ln)
    assert line.endswith(f"speed of sound {speed_of_sound:.2f} m/s") and "ft" not in line


def test_the_vgf_figure_is_drawn_from_the_model(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    from propwhirl.analysis import analyse
    from propwhirl.app import plots
    from propwhirl.cases.ch09_baseline import isolated_baseline_propeller

    model = isolated_baseline_propeller()
    a = analyse(model, speeds=[100.0, 200.0, 250.0])
    seen = []
    real = plots.vgf

    def vgf(analysis, *args, **kwargs):
        seen.append(args[0] if args else kwargs.get("model"))
        return real(analysis, *args, **kwargs)

    monkeypatch.setattr(plots, "vgf", vgf)
    mainjob.write_plots(a, model, tmp_path)
    assert seen == [model]
    assert (tmp_path / "wingtip_vgf.png").stat().st_size > 0
