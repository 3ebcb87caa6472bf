"""Modal models through the command line's commands (issue 34 item 2): the modal model of
*all* the beam model's modes with a grid at every node (``write_modes``, own mounts) is the beam
model — the strips' spline is the beam element's own interpolation
(docs/modal-structures.md) — so every command gives the beam model's numbers: the in-vacuo and
Campbell frequencies to the printed digits, critical speeds within 0.02 m/s (each crossing is
refined to the engine's XTOL = 0.01 m/s on its own model: two brackets of that width)."""
from __future__ import annotations

import re

import numpy as np
import pytest

from propwhirl.app import cli
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io import load_modal_model, save_model, write_modes
from propwhirl.studies import sweeps

XTOL2 = 0.02     # [m/s] two crossings, each refined to XTOL = 0.01 m/s


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("modal_commands")
    beam = d / "beam.toml"
    save_model(wingtip_propeller_wing(), beam)
    write_modes(wingtip_propeller_wing(), d / "modal.toml")          # every mode, own mounts
    return beam, d / "modal.toml"


def _run(capsys, *argv) -> str:
    assert cli.main([str(a) for a in argv]) in (0, 1)
    return capsys.readouterr().out


def test_modes_of_a_modal_model_are_the_beam_models(files, capsys):
    beam, modal = files
    b = _run(capsys, "modes", beam, "--count", "6").splitlines()[2:]
    m = _run(capsys, "modes", modal, "--count", "6").splitlines()[2:]
    assert [ln.split()[:3] for ln in m] == [ln.split()[:3] for ln in b]   # name, f [Hz]
    assert [ln.split()[0] for ln in m[:3]] == ["wing", "backward", "forward"]


def test_campbell_of_a_modal_model_is_the_beam_models(files, capsys):
    beam, modal = files
    rows = [_run(capsys, "campbell", f, "--rpm", 0, 3000, 3, "--count", 5).splitlines()[1:]
            for f in (beam, modal)]
    assert rows[0] == rows[1]


def test_sweep_and_map_take_modal_paths(files, capsys, tmp_path):
    beam, modal = files
    speeds = np.arange(100.0, 351.0, 10.0)
    kw = dict(speeds=speeds, static_divergence=False, low_speed=False)
    path = "propellers[0].propeller.f_psi"
    b = sweeps.sweep(wingtip_propeller_wing(), path, [5.0, 9.0], **kw)
    m = sweeps.sweep(load_modal_model(modal), path, [5.0, 9.0], **kw)
    vb, vm = b.columns["critical_speed"], m.columns["critical_speed"]
    assert np.allclose(vm, vb, atol=XTOL2, rtol=0) and np.all(np.isfinite(vb))
    out = _run(capsys, "sweep", modal, "--param", "structure.frequencies_hz[0]", 2.5, 3, 2,
               "--speeds", 100, 350, 10, "--json", tmp_path / "s.json")
    assert "structure.frequencies_hz[0] [Hz]" in out and "lowest critical speed" in out
    out = _run(capsys, "map", modal, "--param", path, 5, 9, 2, "--param",
               "structure.damping_ratio[0]", 0, 0.02, 2, "--speeds", 100, 350, 10,
               "--processes", 2, "--quiet")
    assert "lowest critical speed" in out


def test_a_mode_frequency_outside_its_range_is_one_line(files, capsys):
    _, modal = files
    assert cli.main(["sweep", str(modal), "--param", "structure.frequencies_hz[0]", "0", "1",
                     "2"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "structure.frequencies_hz[0]: values = 0 Hz is outside the valid range" in err, err


def _critical(text: str) -> float:
    return float(re.search(r"critical: .* at ([\d.]+) m/s", text).group(1))


def test_clearance_of_a_modal_model_is_the_beam_models(files, capsys):
    beam, modal = files
    v = [_critical(_run(capsys, "clearance", f, "--vd", 130, "--thesis", "--no-minimum",
                        "--quiet")) for f in (beam, modal)]
    assert abs(v[1] - v[0]) <= XTOL2 and 150 < v[0] < 170


CAMPAIGN = """format = "propwhirl-campaign"
format_version = 1
model = "{model}"
[regulation]
name = "cs25"
[envelope]
airspeed = "EAS"
V_D_m_per_s = 100.0
altitudes_m = [{altitudes}]
[[cases]]
name = "nominal"
[[cases]]
name = "failed mount damper"
mount_damping = 0.0
[[cases]]
name = "wing damping x 2"
wing_damping = 2.0
[[cases]]
name = "rotation reversed"
reverse_rotation = true
"""


def test_certify_a_modal_campaign_with_its_report(files, capsys, tmp_path):
    import json

    beam, modal = files
    v = []
    for f in (beam, modal):
        camp = tmp_path / f"{f.stem}_campaign.toml"
        camp.write_text(CAMPAIGN.format(model=f, altitudes="0.0"))
        out = tmp_path / f.stem
        assert cli.main(["certify", str(camp), "--out", str(out), "--no-pdf", "--quiet",
                         "--processes", "2"]) in (0, 1)
        rows = json.loads((out / "campaign.json").read_text())["rows"]
        v.append([r["critical_speed"] for r in rows])
        assert (out / "report.html").is_file()
    capsys.readouterr()
    assert np.allclose(v[1], v[0], atol=XTOL2, rtol=0), v


def test_a_mount_factor_on_an_on_grid_mount_is_refused(tmp_path, capsys):
    write_modes(wingtip_propeller_wing(), tmp_path / "m.toml", 12, mount="on-grid")
    camp = tmp_path / "c.toml"
    camp.write_text(CAMPAIGN.format(model="m.toml", altitudes="0.0").split("[[cases]]\nname = "
                                                                           "\"wing")[0])
    assert cli.main(["certify", str(camp), "--out", str(tmp_path / "o"), "--no-report"]) == 2
    err = capsys.readouterr().err
    assert "mount factors are invalid for propeller 1: its mount is 'on-grid'" in err, err
