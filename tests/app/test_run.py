"""`make run` (propwhirl run): the wingtip-mounted propeller wing — printout and files."""
from __future__ import annotations

import contextlib
import io as stdio
import re
from pathlib import Path

import numpy as np
import pytest

from propwhirl import io
from propwhirl.app import run as mainjob
from propwhirl.analysis.stability import load
from propwhirl.reproduce.harness import load_references
from propwhirl.analysis.vibration import label_modes

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """Run the main job once: (printed text, output folder)."""
    out = tmp_path_factory.mktemp("out")
    buf = stdio.StringIO()
    with contextlib.redirect_stdout(buf):
        assert mainjob.main(out) == 0
    return buf.getvalue(), out


def test_writes_every_output(run):
    _, out = run
    for name in ("wingtip_vgf.png", "wingtip_mode_critical.png",
                 "wingtip_mode_forward_whirl_flutter.png"):
        assert (out / name).read_bytes().startswith(PNG), name
    for name in ("wingtip_analysis.json", "wingtip_vgf.csv", "wingtip_model.toml", "report.txt"):
        assert (out / name).stat().st_size > 0, name


def test_saved_model_is_the_headline_model(run):
    _, out = run
    model = io.load_model(out / "wingtip_model.toml")
    V = np.array([50.0, 160.0])
    np.testing.assert_array_equal(model.state_matrix(V), mainjob.headline_model().state_matrix(V))
    assert model.propeller_aero and model.wing_aero and model.rotating  # full aerodynamics
    assert model.propellers[0].y == model.wing.semi_span  # at the tip
    assert model.propellers[0].propeller.operation == "fixed-pitch"


def test_in_vacuo_modes_are_printed_first(run):
    text, _ = run
    assert text.index("In-vacuo modes") < text.index("Instabilities")
    thesis = {r.id: r.thesis for r in load_references()}
    for label, f in label_modes(mainjob.headline_model())[:7]:
        row = next(ln for ln in text.splitlines() if ln.strip().startswith(label + " "))
        values = row.split()[len(label.split()):]
        assert float(values[0]) == pytest.approx(f, abs=5e-4)
        assert float(values[1]) == thesis[mainjob.THESIS_MODES[label]]


def test_every_instability_and_the_critical_one_are_printed(run):
    text, out = run
    a = load(out / "wingtip_analysis.json")
    assert a.events
    rows = [ln for ln in text.splitlines() if re.match(r"\s+(flutter|divergence) ", ln)]
    assert len(rows) == len(a.events)
    for row, e in zip(rows, a.events):
        assert row.split()[:2] == [e.kind, e.event]
        assert a.describe(e.label) in row
        assert f"{e.V:8.2f}" in row and f"{e.frequency_hz:7.3f}" in row
        assert (e.whirl or "-") in row
    c = a.critical
    assert f"Critical: {c.kind} of {a.describe(c.label)} at {c.V:.2f} m/s" in text
    report = (out / "report.txt").read_text()
    for row in rows:
        assert row in report


def test_thesis_values_are_shown_next_to_the_events(run):
    text, out = run
    a = load(out / "wingtip_analysis.json")
    thesis = {r.id: r.thesis for r in load_references()}
    fw = a.first("forward 1", "flutter")
    row = next(ln for ln in text.splitlines() if re.match(r"\s+flutter\s+onset\s+forward 1", ln))
    assert f"{fw.V:8.2f}" in row
    assert f"{thesis['t10.4/full/fw_whirl_flutter_speed']:g} m/s" in row


def test_divergence_note_appears_exactly_when_the_divergence_is_critical(run):
    text, out = run
    a = load(out / "wingtip_analysis.json")
    c, fw = a.critical, a.first("forward 1", "flutter")
    noted = "it does not report this static divergence" in text
    assert noted == (c.kind == "divergence" and fw is not None and fw.V > c.V)
    if noted:
        assert "`propwhirl docs validation`" in text    # the installed page, by command
        heading = "The wingtip models have a static divergence the thesis does not report"
        assert heading in text
        docs = Path(__file__).resolve().parents[2] / "docs" / "validation.md"
        assert heading in docs.read_text()  # the pointer leads somewhere


def test_csv_and_json_hold_the_same_vgf_table(run):
    _, out = run
    a = load(out / "wingtip_analysis.json")
    table = a.sweep.table()
    back = io.read_vgf_csv(out / "wingtip_vgf.csv")
    for key in ("V", "frequency_hz", "damping_ratio", "real", "imag"):
        np.testing.assert_array_equal(back[key], table[key])
    assert list(back["label"]) == list(table["label"])
