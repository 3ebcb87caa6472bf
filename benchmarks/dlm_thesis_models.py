"""The thesis's wingtip and two-propeller models (§10.1–10.2) with doublet-lattice wing
aerodynamics against the strips (issue 23, item 5(d)).

Run from the repository root (needs the ``dlm`` extra, PanelAero)::

    PROPWHIRL_DLM_CACHE=/tmp/dlmcache .venv/bin/python benchmarks/dlm_thesis_models.py
    ... --quick          # the coarse panels only (4 x 12)

For each model: the p-k events of the strips (C_lα = 2π, exact Theodorsen, incompressible) and
of the DLM panels (default panel counts and a coarse 4 x 12 set), on the speeds 100–290 m/s
every 10 and 296 m/s (the DLM tables stop at Mach 0.9 = 297.7 m/s at the model's 8000 ft), with
each run's CPU time (one BLAS thread). With ``PROPWHIRL_DLM_CACHE`` set every AIC is kept on
disk, so a rerun costs only the p-k iterations.

The "why" (:func:`lift_ratios`): on the default panels, (a) the steady lift per unit span under
a uniform twist of 1 rad, DLM against the strips' 2π c(y), at Mach 0 (the 3-D tip loss alone)
at stations along the span up to the outermost panel strip (the propeller station is the tip);
(b) the ratio of the DLM to the strip generalised aerodynamic stiffness of the clean wing's first
torsion mode at k = 0, at Mach 0 and at the Mach numbers of the events (the DLM compressibility,
≈ 1/√(1 − M²), which the strips do not have, multiplies the tip loss).
"""
from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np
from threadpoolctl import threadpool_limits

from propwhirl.analysis import analyse
from propwhirl.analysis.pk import pk_system
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.model.structure.assembly import free_dofs, wing_structure
from propwhirl.model.aerodynamics.dlm import dlm_aerodynamics
from propwhirl.model.aerodynamics.dlm_mesh import panel_counts

SPEEDS = np.r_[np.arange(100.0, 295.0, 10.0), 296.0]
COARSE = (4, 12)
#: (Mach, k) of the wingtip model's DLM forward whirl onset (204 m/s, 6.3 Hz, k on b_ref 0.625 m)
DAMPING_AT = (0.616, 0.122)
MODELS = {"wingtip": wingtip_propeller_wing, "two-propeller": two_propeller_wing}


def with_dlm(model, panels: tuple[int, int] | None = None):
    """The model with ``aero = "dlm"`` on its wing (``panels`` = (chordwise, spanwise) or the
    defaults)."""
    nc, ns = panels if panels is not None else (8, None)
    return model.with_(wing=dataclasses.replace(model.wing, aero="dlm", dlm_chordwise_panels=nc,
                                                dlm_spanwise_panels=ns))


def events(model, method: str = "auto") -> tuple[list[tuple[str, str, float, float]], float]:
    """((kind, label, V [m/s], f [Hz]) of every onset, CPU time [s]) of the p-k analysis."""
    t = time.process_time()
    a = analyse(model, speeds=SPEEDS, method=method)
    cpu = time.process_time() - t
    return [(e.kind, e.label, e.V, e.frequency_hz) for e in a.events if e.event == "onset"], cpu


def first_mode(wing, dof: int = 2) -> np.ndarray:
    """The clean wing's first in-vacuo mode with most of its kinetic energy in DOF ``dof`` of
    each node (0 heave: first bending, 2 twist: first torsion), on the free wing DOFs (h, φ, α
    per node), scaled to a largest value 1 of that DOF."""
    M, _, K = wing_structure(wing)
    keep = free_dofs(wing.n_nodes)
    M, K = M[np.ix_(keep, keep)], K[np.ix_(keep, keep)]
    w, X = np.linalg.eig(np.linalg.solve(M, K))
    for j in np.argsort(w.real):
        x = X[:, j].real
        part = np.zeros_like(x)
        part[dof::3] = x[dof::3]
        if part @ M @ part > 0.5 * (x @ M @ x):
            return x / np.max(np.abs(x[dof::3]))
    raise RuntimeError("no such mode")


def lift_ratios(model, machs, damping_at: tuple[float, float]) -> dict:
    """The tip-loss numbers of the module docstring on the default panels."""
    dlm_model = with_dlm(model)
    wing = dlm_model.wing
    aero = dlm_aerodynamics(wing)
    mesh = aero.mesh
    nc, ns = mesh.n_chord, mesh.n_span
    # (a) steady lift per unit span under α = 1 rad: w = slope = 1 at every collocation point
    cp = aero.aic(0.0, 0.0) @ np.ones(mesh.n)
    lift = (cp * mesh.area).reshape(ns, nc).sum(axis=1) / mesh.width.reshape(ns, nc)[:, 0]
    y = mesh.points(0.25)[:, 1].reshape(ns, nc)[:, 0]
    chord = mesh.length.reshape(ns, nc).sum(axis=1)
    ratio = np.abs(lift) / (wing.lift_slope * chord)
    stations = {f"{yy / wing.semi_span:.3f}": float(r) for yy, r in
                zip(y[[0, ns // 2, int(0.8 * ns), int(0.9 * ns), ns - 1]],
                    ratio[[0, ns // 2, int(0.8 * ns), int(0.9 * ns), ns - 1]])}
    total = float(np.sum(np.abs(lift) * mesh.width.reshape(ns, nc)[:, 0])
                  / np.sum(wing.lift_slope * chord * mesh.width.reshape(ns, nc)[:, 0]))
    # (b) generalised aerodynamic stiffness of the first torsion mode at k = 0, DLM / strips
    x = first_mode(wing, 2)
    keep = free_dofs(wing.n_nodes)
    n = keep.size
    V = 100.0
    q = 0.5 * model.flight.density * V ** 2
    dry = dataclasses.replace(model, wing_aero=False).second_order(np.array([V])).S3[0][:n, :n]
    Ka_strip = dry - pk_system(model, V)(1e-6 * V)[2][:n, :n]         # strips at k -> 0
    strip = x @ Ka_strip @ x / q
    gaf = {f"{m:.3f}": float(x @ aero.gaf(m, 0.0).real[np.ix_(keep, keep)] @ x / strip)
           for m in machs}
    # (c) generalised aerodynamic damping (Im Q / k) of the first bending and torsion modes at
    # the reduced frequency and Mach of a DLM event, DLM / strips
    Mw, kw = damping_at
    omega = kw * V / aero.b_ref
    dryC = dataclasses.replace(model, wing_aero=False).second_order(np.array([V])).S2[0][:n, :n]
    Ca_strip = dryC - pk_system(model, V)(omega)[1][:n, :n]
    Q = aero.gaf(Mw, kw)[np.ix_(keep, keep)]
    damping = {}
    for name, dof in (("bending", 0), ("torsion", 2)):
        z = first_mode(wing, dof)
        damping[name] = float((z @ Q.imag @ z / omega) / (z @ Ca_strip @ z / q))
    return {"panels": (nc, ns), "stations": stations, "total": total, "torsion_gaf": gaf,
            "damping": damping}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="the coarse panels only")
    args = p.parse_args()
    a_sound = wingtip_propeller_wing().flight.speed_of_sound
    with threadpool_limits(1):
        machs = [0.0]
        for name, build in MODELS.items():
            model = build()
            print(f"## {name} (default panels {panel_counts(with_dlm(model).wing)})")
            runs = [("strip", model, "pk")]
            if not args.quick:
                runs.append(("DLM default", with_dlm(model), "pk"))
            runs.append((f"DLM {COARSE[0]}x{COARSE[1]}", with_dlm(model, COARSE), "pk"))
            results = {}
            for label, m, method in runs:
                ev, cpu = events(m, method)
                results[label] = ev
                print(f"{label}: CPU {cpu:.1f} s")
                for kind, mode, V, f in ev:
                    print(f"  {kind:10s} {mode:12s} V = {V:7.2f} m/s  f = {f:6.3f} Hz"
                          f"  Mach {V / a_sound:.3f}")
            ref = results["strip"]
            for label, ev in results.items():
                if label == "strip":
                    continue
                for (kind, mode, V, f) in ev:
                    match = [r for r in ref if r[0] == kind and r[1] == mode]
                    if match:
                        Vs, fs = match[0][2], match[0][3]
                        df = f"{100 * (f / fs - 1):+.1f} %" if fs > 0 else "-"
                        print(f"  | {label} | {kind} | {mode} | {Vs:.2f} / {fs:.3f} | "
                              f"{V:.2f} / {f:.3f} | {100 * (V / Vs - 1):+.1f} % | {df} |")
                    machs.append(round(V / a_sound, 3))
        if not args.quick:
            print("## why: tip loss and compressibility (wingtip model, default panels)")
            t = time.process_time()
            r = lift_ratios(wingtip_propeller_wing(), sorted(set(machs)), DAMPING_AT)
            print(f"panels {r['panels']}; CPU {time.process_time() - t:.1f} s")
            print("steady lift per unit span DLM / strips (Mach 0) at y/s:", {
                k: round(v, 3) for k, v in r["stations"].items()})
            print(f"whole-wing lift DLM / strips (Mach 0): {r['total']:.3f}")
            print("first torsion mode generalised aero stiffness DLM / strips at k = 0, by Mach:",
                  {k: round(v, 3) for k, v in r["torsion_gaf"].items()})
            print(f"generalised aero damping DLM / strips at Mach {DAMPING_AT[0]}, "
                  f"k = {DAMPING_AT[1]}:", {k: round(v, 3) for k, v in r["damping"].items()})


if __name__ == "__main__":
    main()
