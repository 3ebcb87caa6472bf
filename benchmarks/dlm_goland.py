"""The Goland wing's flutter with doublet-lattice aerodynamics against published
three-dimensional results (issue 23, item 5(c)).

Run from the repository root (needs the ``dlm`` extra, PanelAero; about 3 min, one BLAS
thread; writes its tables into docs/validation.md, "Doublet-lattice aerodynamics")::

    .venv/bin/python benchmarks/dlm_goland.py --markdown docs/validation.md
    ... --quick          # the coarse panels only (no markdown)

The wing (Goland 1945; the common "Goland wing" beam): semi-span 20 ft = 6.096 m, chord
6 ft = 1.8288 m, EI = 23.65e6 lb ft² = 9.77e6 N m², GJ = 2.39e6 lb ft² = 0.987e6 N m²,
m = 0.746 slug/ft = 35.71 kg/m, torsional inertia about the elastic axis 8.64 kg m, elastic
axis 33 %, centre of gravity 43 % chord, clamped, 10 beam elements. The p-k method follows the
lowest :data:`N_MODES` in-vacuo modes (the source's count where it states one).

Like for like with the one quotable three-dimensional source found (SHARPy's UVLM Goland
flutter test, ρ = 1.02 kg/m³, incompressible potential flow, 16 chordwise × 32 spanwise
vortex rings over the whole span = 16 × 16 on the half-wing, 4 modes; see the validation page
for the sources and what could not be read) the DLM tables are evaluated at **Mach 0** here
(the wing key ``dlm_mach = 0``, one Mach for every speed; propwhirl's default ``"speed"`` uses
Mach V/a of each speed, whose effect is one row of the experiment table).
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from markdown_section import replace_section  # noqa: E402

from propwhirl.analysis.pk import pk_sweep  # noqa: E402
from propwhirl.engine import single_thread_blas  # noqa: E402
from propwhirl.model import FlightCondition, PropellerWing, Wing  # noqa: E402

#: airspeeds of the p-k sweeps [m/s]
SPEEDS = np.arange(120.0, 201.0, 10.0)
#: in-vacuo modes the p-k method follows (SHARPy's test: 4)
N_MODES = 4
#: SHARPy's density [kg/m^3] (about 1870 m ISA) and sea level
RHO_SHARPY, RHO_SEA = 1.02, 1.225
#: panel convergence (chordwise, spanwise on the half-wing), panel aspect ratio ≈ 1.9
CONVERGENCE = [(4, 7), (8, 14), (16, 28)]
#: the spanwise and chordwise counts apart
EXTRA = [(8, 28), (16, 16), (16, 32)]
BEGIN = "<!-- dlm_goland: begin (benchmarks/dlm_goland.py writes this block) -->"
END = "<!-- dlm_goland: end -->"
TITLE = "### The Goland wing against published three-dimensional results (item 5(c))"


def goland_wing(aero: str = "strip", panels: tuple[int, int] | None = None,
                n_elements: int = 10) -> Wing:
    """The Goland wing (module docstring) with ``aero`` and ``panels`` = (chordwise,
    spanwise on the half-wing)."""
    nc, ns = panels if panels is not None else (8, None)
    return Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71, polar_inertia=8.64,
                EI=9.77e6, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43,
                n_elements=n_elements, aero=aero, dlm_chordwise_panels=nc,
                dlm_spanwise_panels=ns)


@dataclasses.dataclass(frozen=True)
class Flutter:
    """The critical p-k crossing: V [m/s], ω [rad/s], k (root semichord) and CPU time [s]."""

    V: float
    omega: float
    k: float
    cpu: float

    @property
    def f(self) -> float:
        return self.omega / (2 * np.pi)


def flutter(wing: Wing, density: float, *, mach: float | None = 0.0, n_modes: int = N_MODES,
            speed_of_sound: float = 340.0) -> Flutter:
    """The wing's p-k flutter at ``density`` [kg/m³]: Mach ``mach`` for the panels at every
    speed (the wing's ``dlm_mach``; None: "speed", V / ``speed_of_sound`` of each speed)."""
    if wing.aero == "dlm":
        wing = dataclasses.replace(wing, dlm_mach="speed" if mach is None else mach)
    model = PropellerWing(wing, FlightCondition(density, speed_of_sound=speed_of_sound),
                          name="goland")
    t = time.process_time()
    sweep = pk_sweep(model, SPEEDS, n_modes=n_modes)
    c = sweep.critical
    if c is None or c.kind != "flutter":
        raise RuntimeError(f"no flutter of the Goland wing on {SPEEDS[0]}-{SPEEDS[-1]} m/s")
    return Flutter(c.V, c.frequency, c.k, time.process_time() - t)


def pct(a: float, b: float) -> str:
    return f"{100 * (a / b - 1):+.1f} %"


def convergence_table(quick: bool) -> tuple[list[str], dict]:
    rows = ["| aerodynamics | panels (chord × half-span) | V_f [m/s] | f_f [Hz] | ω_f [rad/s] "
            "| k | ΔV, Δf from previous | CPU [s] |", "|---|---|---:|---:|---:|---:|---:|---:|"]
    out = {}
    s = flutter(goland_wing(), RHO_SHARPY)
    out["strip"] = s
    rows.append(f"| strips, C_lα = 2π (p-k) | – | {s.V:.2f} | {s.f:.3f} | {s.omega:.2f} | "
                f"{s.k:.3f} | | {s.cpu:.1f} |")
    prev = None
    for p in CONVERGENCE[:2] if quick else CONVERGENCE:
        r = flutter(goland_wing("dlm", p), RHO_SHARPY)
        out[p] = r
        d = f"{pct(r.V, prev.V)}, {pct(r.f, prev.f)}" if prev else ""
        rows.append(f"| DLM, Mach 0 | {p[0]} × {p[1]} | {r.V:.2f} | {r.f:.3f} | {r.omega:.2f} | "
                    f"{r.k:.3f} | {d} | {r.cpu:.1f} |")
        prev = r
        print(rows[-1], flush=True)
    if not quick:
        for p in EXTRA:
            r = flutter(goland_wing("dlm", p), RHO_SHARPY)
            out[p] = r
            rows.append(f"| DLM, Mach 0 | {p[0]} × {p[1]} | {r.V:.2f} | {r.f:.3f} | "
                        f"{r.omega:.2f} | {r.k:.3f} | | {r.cpu:.1f} |")
            print(rows[-1], flush=True)
    return rows, out


def published_table(conv: dict) -> list[str]:
    """The sources side by side with propwhirl's value on the source's own mesh and modes."""
    rows = ["| source (method, structure) | ρ [kg/m³] | Mach | published V_f | propwhirl, same "
            "mesh and modes | difference |", "|---|---:|---:|---:|---:|---:|"]
    r = conv.get((16, 16)) or flutter(goland_wing("dlm", (16, 16)), RHO_SHARPY)
    rows.append("| SHARPy UVLM flutter test, current (`tests/linear/goland_wing`: 16 × 32 rings "
                "over the span, wake 10 chords, beam, 4 modes; its reference, tolerance 1 %) | "
                f"1.02 | 0 (incompressible) | 166 m/s | DLM 16 × 16, 4 modes: {r.V:.2f} m/s, "
                f"{r.omega:.2f} rad/s | {pct(r.V, 166.0)} |")
    r8 = flutter(goland_wing("dlm", (14, 16)), RHO_SHARPY, n_modes=8)
    rows.append("| SHARPy UVLM flutter test, earlier version (14 × 32 rings, 8 modes; tolerance "
                f"1 %) | 1.02 | 0 | 169 m/s | DLM 14 × 16, 8 modes: {r8.V:.2f} m/s, "
                f"{r8.omega:.2f} rad/s | {pct(r8.V, 169.0)} |")
    s = flutter(goland_wing(), RHO_SEA)
    rows.append("| Goland & Luke (1948), exact 2-D strips (Theodorsen), the classical value, "
                f"*not* 3-D | 1.225 | 0 | 137.2 m/s, 70.7 rad/s | strips (p-k): {s.V:.2f} m/s, "
                f"{s.omega:.2f} rad/s | {pct(s.V, 137.2)}, {pct(s.omega, 70.7)} |")
    return rows


def experiments(conv: dict) -> list[str]:
    """What moves the comparison: Mach, modes, beam elements, density (8 × 14 panels)."""
    base = conv[(8, 14)]
    rows = ["| experiment (DLM 8 × 14, ρ = 1.02 unless said) | V_f [m/s] | ω_f [rad/s] "
            "| ΔV | Δω |", "|---|---:|---:|---:|---:|",
            f"| reference: Mach 0, 4 modes, 10 elements | {base.V:.2f} | {base.omega:.2f} | | |"]
    cases = [("Mach V/a of each speed (a = 340 m/s; Mach 0.49 at flutter)",
              dict(wing=goland_wing("dlm", (8, 14)), mach=None)),
             ("6 modes", dict(wing=goland_wing("dlm", (8, 14)), n_modes=6)),
             ("20 beam elements", dict(wing=goland_wing("dlm", (8, 14), n_elements=20)))]
    for label, kw in cases:
        wing = kw.pop("wing")
        r = flutter(wing, RHO_SHARPY, **kw)
        rows.append(f"| {label} | {r.V:.2f} | {r.omega:.2f} | {pct(r.V, base.V)} | "
                    f"{pct(r.omega, base.omega)} |")
        print(rows[-1], flush=True)
    sea = flutter(goland_wing("dlm", (8, 14)), RHO_SEA)
    strip_sea = flutter(goland_wing(), RHO_SEA)
    rows.append(f"| ρ = 1.225 (sea level), Mach 0 | {sea.V:.2f} | {sea.omega:.2f} | "
                f"{pct(sea.V, base.V)} | {pct(sea.omega, base.omega)} |")
    rows.append(f"| strips instead of panels, ρ = 1.225 | {strip_sea.V:.2f} | "
                f"{strip_sea.omega:.2f} | {pct(strip_sea.V, sea.V)} (of the panels at 1.225) | |")
    return rows


def lift_deficit(conv: dict) -> tuple[list[str], dict]:
    """Why the panels fly faster than the strips: the 3-D lift deficit. The DLM's tip-loss
    numbers (:func:`dlm_thesis_models.lift_ratios` on the default 8 × 14 panels), then the
    strips with their C_lα scaled by the DLM's whole-wing lift ratio and with the elliptic
    C_lα (the thesis's §7.5 approximation), against the converged panels."""
    from dlm_thesis_models import lift_ratios

    model = PropellerWing(goland_wing(), FlightCondition(RHO_SHARPY, speed_of_sound=340.0),
                          name="goland")
    base = conv[(8, 14)]
    why = lift_ratios(model, [0.0, round(base.V / 340.0, 2)], (0.0, round(base.k, 3)))
    fine = conv.get(CONVERGENCE[-1])
    rows = ["| strips (ρ = 1.02) with | C_lα [1/rad] | V_f [m/s] | ω_f [rad/s] "
            f"| ΔV from the DLM {CONVERGENCE[-1][0]} × {CONVERGENCE[-1][1]} |",
            "|---|---:|---:|---:|---:|"]
    for label, slope in (("2π (the strips above)", 2 * np.pi),
                         ("2π × the DLM's whole-wing lift ratio", 2 * np.pi * why["total"]),
                         ("elliptic, 2π√(1 − (y/L)²)", "elliptic")):
        r = flutter(dataclasses.replace(goland_wing(), lift_slope=slope), RHO_SHARPY)
        shown = f"{slope:.3f}" if isinstance(slope, float) else slope
        rows.append(f"| {label} | {shown} | {r.V:.2f} | {r.omega:.2f} | {pct(r.V, fine.V)} |")
        print(rows[-1], flush=True)
    return rows, why


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="the coarse panels only, no markdown")
    p.add_argument("--markdown", type=Path, help="write the tables into this file")
    args = p.parse_args()
    t0 = time.time()
    with single_thread_blas():
        conv_rows, conv = convergence_table(args.quick)
        print("\n".join(conv_rows))
        if args.quick:
            return
        pub_rows = published_table(conv)
        print("\n".join(pub_rows))
        exp_rows = experiments(conv)
        print("\n".join(exp_rows))
        why_rows, why = lift_deficit(conv)
        print("\n".join(why_rows))
        print(why)
    print(f"wall time {time.time() - t0:.0f} s")
    if args.markdown:
        body = "\n".join([
            "Panel convergence (ρ = 1.02 kg/m³, Mach 0, p-k on the lowest 4 modes, speeds "
            f"{SPEEDS[0]:.0f}–{SPEEDS[-1]:.0f} m/s every 10; CPU of `pk_sweep` with its "
            "AICs, one BLAS thread):", "", *conv_rows, "",
            "Published values side by side (propwhirl on the source's own panel counts, modes, "
            "density and Mach):", "", *pub_rows, "",
            "Numerical experiments (what else moves the comparison):", "", *exp_rows, "",
            "The strips against the panels: the DLM's tip loss (8 × 14 panels, Mach 0, "
            "uniform twist of 1 rad): steady lift per unit span DLM / strips "
            + ", ".join(f"{v:.2f} at y/L = {k}" for k, v in why["stations"].items())
            + f"; {why['total']:.3f} over the whole wing. Generalised aerodynamic stiffness of "
            "the first torsion mode at k = 0, DLM / strips: "
            + ", ".join(f"{v:.2f} at Mach {k}" for k, v in why["torsion_gaf"].items())
            + f"; generalised aerodynamic damping at Mach 0, k = {conv[(8, 14)].k:.3f} (the "
            f"flutter's), DLM / strips: bending {why['damping']['bending']:.2f}, torsion "
            f"{why['damping']['torsion']:.2f}. The strips with their C_lα scaled by the "
            "whole-wing ratio:", "", *why_rows])
        replace_section(args.markdown, body, BEGIN, END, TITLE)


if __name__ == "__main__":
    main()
