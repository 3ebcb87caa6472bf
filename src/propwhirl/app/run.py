"""`make run` / `propwhirl run`: the main analysis — the wingtip-mounted propeller wing.

The thesis's headline configuration (§10.1): the baseline wing of Table 9.1 (25 elements,
Leishman–Nguyen strip aerodynamics) with the baseline propeller of Tables 9.3–9.4 flexibly
mounted at the tip, windmilling at fixed pitch (β_0.75 = 35°, Ω ∝ V), Houbolt–Reed propeller
derivatives, 8000 ft, airspeeds 1–350 m/s (the engine refines the grid and every crossing to
0.01 m/s).

Printed (and written to ``report.txt``): the in-vacuo modes with their thesis names and the
Table 10.3 values, every instability (type, event, mode, whirl sense, speed, frequency,
benignity, the thesis's value where it reports one), the propellers' participation at each
event (:mod:`propwhirl.analysis.participation`) and the critical one.  Written to the
output folder: the V-g-f plot, the mode shapes of the critical instability and of the forward
whirl flutter, the analysis as JSON, the V-g-f table, the events with each propeller's
participation and the flutter summary (V, k, ζ, g, f, density, Mach per mode and speed) as CSV,
and the model as a TOML model file.
"""
from __future__ import annotations

import importlib.util
import time
from pathlib import Path

import numpy as np

from propwhirl import documents, fileio, io
from propwhirl.limits import printable
from propwhirl.analysis.participation import participation_lines
from propwhirl.analysis.stability import Instability, ModelAnalysis, analyse, describe_critical
from propwhirl.analysis.summary import text_table
from propwhirl.cases.registry import case_model
from propwhirl.model import atmosphere
from propwhirl.model.flight import FlightCondition
from propwhirl.model.systems import PropellerWing
from propwhirl.reproduce.harness import load_references
from propwhirl.analysis.vibration import label_modes
from propwhirl.app import plots

#: The named case (propwhirl.cases.registry) this analysis runs: the wingtip-mounted propeller wing.
MAIN_CASE = "wingtip"

#: Modes drawn in the V-g-f plot (the thesis's Tables 10.3/10.4 name these).
VGF_MODES = 7

#: Thesis ids (thesis_values.toml) of the events Table 10.4 reports: (label, kind, event).
THESIS_EVENTS = {
    ("forward 1", "flutter", "onset"): ("t10.4/full/fw_whirl_flutter_speed",
                                        "t10.4/full/fw_whirl_flutter_frequency"),
    ("backward 1", "flutter", "onset"): ("t10.4/full/bw_whirl_flutter_speed",
                                         "t10.4/full/bw_whirl_flutter_frequency"),
    ("forward 1", "divergence", "frequency-zero"): ("t10.4/full/fw_divergence_speed", None),
}
THESIS_MODES = {"wing 1": "t10.3/wing1", "wing 2": "t10.3/wing2", "wing 3": "t10.3/wing3",
                "wing 4": "t10.3/wing4", "wing 5": "t10.3/wing5",
                "backward 1": "t10.3/backward", "forward 1": "t10.3/forward"}


def headline_model() -> PropellerWing:
    """The wingtip-mounted propeller wing with full aerodynamics (§10.1, Table 10.4 'full'):
    the named case MAIN_CASE of :mod:`propwhirl.cases.registry`."""
    return case_model(MAIN_CASE).with_(name="wingtip-mounted propeller wing (thesis 10.1)")


def describe(model: PropellerWing) -> list[str]:
    """Header lines: the configuration in SI units."""
    w, inst = model.wing, model.propellers[0]
    p = inst.propeller
    first, last, step = model.flight.speed_range
    return [
        f"{printable(model.name)}",
        f"  wing: {printable(w.name)}; semi-span {w.semi_span:g} m, chord {w.root_chord:g}-{w.tip_chord:g} m, "
        f"{w.element_count} elements, {w.aero_model} strip aerodynamics",
        f"  propeller: {printable(p.name)} at y = {inst.y:g} m ({inst.mount} mount), R = {p.radius:g} m, "
        f"f_theta = {p.f_theta:g} Hz, f_psi = {p.f_psi:g} Hz, {p.damping} = {p.damping_theta:g}",
        f"  operation: {p.operation}, beta_0.75 = {p.beta_075_deg:g} deg, "
        f"J = pi mu = {np.pi * p.advance_ratio:.3f} (Omega proportional to V), Houbolt-Reed "
        "derivatives",
        f"  flight: density {model.flight.density:g} kg/m^3, speed of sound "
        f"{model.flight.speed_of_sound:.2f} m/s{altitude_text(model.flight)}",
        f"  airspeeds {first:g}-{last:g} m/s (initial step {step:g} m/s, refined automatically; "
        "V = 0 is excluded: the strip aerodynamics carry 1/V)",
    ]


def isa_altitude(flight: FlightCondition, rtol: float = 1e-6) -> float | None:
    """The ISA altitude [m] of a flight condition, or None when it is not an ISA condition.

    The troposphere's speed of sound falls strictly with altitude (−5 to 11 km), so the speed
    of sound gives the one candidate altitude; it is the flight's altitude when the ISA
    density there is the flight's density too (both within `rtol`).  Above 11 km (constant
    temperature) the altitude is not determined by the speed of sound: None.
    """
    # a = sqrt(gamma R T), T = T0 + L h with the troposphere's lapse rate L = -6.5 K/km
    T = flight.speed_of_sound ** 2 / (atmosphere.GAMMA * atmosphere.R_AIR)
    h = (T - atmosphere.SEA_LEVEL_TEMPERATURE) / -0.0065
    if not atmosphere.MIN_ALTITUDE <= h <= 11000.0:
        return None
    air = atmosphere.isa(h)
    same = (abs(air.speed_of_sound - flight.speed_of_sound) <= rtol * flight.speed_of_sound
            and abs(air.density - flight.density) <= rtol * flight.density)
    return float(h) if same else None


def altitude_text(flight: FlightCondition) -> str:
    """' (ISA, 8000 ft = 2438 m)' when the flight is the ISA at some altitude, else ''."""
    h = isa_altitude(flight)
    return "" if h is None else f" (ISA, {round(h / atmosphere.FT):d} ft = {round(h):d} m)"


def _thesis_values() -> dict[str, float]:
    return {r.id: r.thesis for r in load_references()}


def mode_lines(model: PropellerWing, thesis: dict[str, float], count: int = 10) -> list[str]:
    """In-vacuo modes (V = 0, Ω = 0) with their names and Table 10.3's values."""
    rows = []
    for label, f in label_modes(model)[:count]:
        ref = thesis.get(THESIS_MODES.get(label, ""), None)
        rows.append([label, f"{f:.3f}", "" if ref is None else f"{ref:.2f}"])
    table = text_table(rows, ["mode", "f [Hz]", "thesis (Table 10.3)"], "lrr")
    return ["", "In-vacuo modes (V = 0, not rotating):"] + ["  " + t for t in table.splitlines()]


def _fmt_thesis(e: Instability, thesis: dict[str, float], seen: set) -> str:
    key = (e.label, e.kind, e.event)
    if key not in THESIS_EVENTS or key in seen:
        return "not reported" if e.event != "recovery" else ""
    seen.add(key)
    v_id, f_id = THESIS_EVENTS[key]
    text = f"{thesis[v_id]:g} m/s"
    if f_id is not None:
        text += f", {thesis[f_id]:g} Hz"
    return text + " (Table 10.4)"


def event_lines(a: ModelAnalysis, thesis: dict[str, float]) -> list[str]:
    """Every instability, the critical one, and the note on the thesis's critical speed."""
    lines = ["", f"Instabilities between {a.sweep.V[0]:g} and {a.sweep.V[-1]:g} m/s "
             "(crossings refined to 0.01 m/s):"]
    seen: set = set()
    rows = [[e.kind, e.event, a.describe(e.label), e.whirl or "-", f"{e.V:.2f}",
             f"{e.frequency_hz:.3f}", "" if e.benignity is None else f"{e.benignity:.1f}",
             _fmt_thesis(e, thesis, seen)] for e in a.events]
    table = text_table(rows, ["type", "event", "mode (content)", "whirl", "V [m/s]", "f [Hz]",
                              "benignity", "thesis"], "llllrrrl")
    lines += ["  " + t for t in table.splitlines()]
    lines.append("  content: dominant kinetic-energy share at the first speed; whirl: sense of the "
                 "propeller's theta-psi orbit\n  at the event; benignity [m/s] = (d zeta/dV)^-1 at "
                 "flutter onsets (eq. 5.13)")
    lines += participation_lines(a.events, "  ")
    for note in a.warnings:      # the aerodynamics' validity (propwhirl.model.aerodynamics.validity)
        lines.append(f"Warning: {printable(note)}")
    c = a.critical
    if c is None:
        lines.append("Critical: no instability in the speed range")
        return lines
    lines.append("Critical: " + describe_critical(c, a.describe))
    fw = a.first("forward 1", "flutter")
    if c.kind == "divergence" and fw is not None and fw.V > c.V:
        thesis_fw = thesis[THESIS_EVENTS[("forward 1", "flutter", "onset")][0]]
        lines.append(
            f"Note: the thesis reports the forward whirl flutter ({thesis_fw:g} m/s; here "
            f"{fw.V:.2f} m/s) as critical; it does not report this static divergence (a real root "
            "through zero) - see "
            + documents.cite("validation", "'The wingtip models have a static divergence the "
                             "thesis does not report'") + ".")
    return lines


def write_plots(a: ModelAnalysis, model: PropellerWing, out: Path) -> list[Path]:
    """V-g-f plot and the mode shapes of the critical instability and the forward whirl
    flutter; skipped with a note when matplotlib is not installed."""
    if importlib.util.find_spec("matplotlib") is None:
        print("plots skipped: matplotlib is not installed (pip install propwhirl[plots])")
        return []

    # the model: the curves on a fine speed grid (the analysis's sweep holds the engine's nodes)
    paths = [plots.save(plots.vgf(a, model, n_modes=VGF_MODES), out / "wingtip_vgf.png")]
    if a.critical is not None:
        paths.append(plots.save(plots.event_mode_shape(a, a.critical),
                                out / "wingtip_mode_critical.png"))
    fw = a.first("forward 1", "flutter")
    if fw is not None:
        paths.append(plots.save(plots.event_mode_shape(a, fw),
                                out / "wingtip_mode_forward_whirl_flutter.png"))
    return paths


def main(out: Path) -> int:
    """Run the main analysis, print the report and write the results to `out`."""
    t0 = time.perf_counter()
    out = Path(out)
    fileio.check_writable(out, folder=True, create=True, what="--out")  # before computing
    model = headline_model()
    thesis = _thesis_values()
    lines = describe(model) + mode_lines(model, thesis)
    print("\n".join(lines), flush=True)
    a = analyse(model, xtol=0.01, vgf=True)  # every grid speed of model.flight.speed_range (1-350 m/s)
    more = event_lines(a, thesis)
    print("\n".join(more), flush=True)
    lines += more
    written = [
        io.save_model(model, out / "wingtip_model.toml"),
        _save_json(a, out / "wingtip_analysis.json"),
        io.write_vgf_csv(a, out / "wingtip_vgf.csv"),
        _write(out / "wingtip_events.csv", a.events_csv),
        _write(out / "wingtip_flutter_summary.csv", a.flutter_summary().to_csv),
    ]
    written += write_plots(a, model, out)
    written.append(fileio.write_text(out / "report.txt", "\n".join(lines) + "\n",
                                     what="report"))
    print("\nWrote " + ", ".join(str(p) for p in written))
    print(f"Done in {time.perf_counter() - t0:.1f} s")
    return 0


def _write(path: Path, writer) -> Path:
    writer(path)
    return path


def _save_json(a: ModelAnalysis, path: Path) -> Path:
    a.save(path)  # the V-g-f table, labels, instabilities (eigenvectors: include_eigenvectors=True, ~25 MB .npz)
    return path
