"""The capability table — model kind × aerodynamics × method × command — generated from the
model contract (issue 34 item 1).

Every command and analysis method asks the model what it can do
(:func:`propwhirl.model.protocol.capabilities`, :func:`~propwhirl.model.protocol.refusal`);
this module asks the same of one small model of each kind (:data:`SAMPLES`) and writes what
they answer as the page docs/capabilities.md, so the page cannot drift from the code: the test
(tests/app/test_capability_table.py) checks the committed page is :func:`page` and that each
refused cell is what the command prints.  Regenerate with::

    python -m propwhirl.app.capability_table docs/capabilities.md
"""
from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from propwhirl import fileio
from propwhirl.cases.ch09_baseline import (baseline_flight, baseline_propeller, baseline_wing,
                                           isolated_baseline_propeller)
from propwhirl.model import (FlightCondition, Installation, ModalInstallation,
                             ModalPropellerWing, ModalStructure, PropellerWing, StripPlanform,
                             TypicalSection)
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.parameter_paths import parameter_families
from propwhirl.model.protocol import (COMMANDS, DERIVATIVE_ROUTES, METHODS, STRUCTURES,
                                     Capabilities, capabilities)


def _beam(aero: str = "strip", propellers: bool = True):
    wing = baseline_wing(4)
    if aero == "dlm":                       # few panels: the test runs every command on it
        wing = replace(wing, aero="dlm", dlm_chordwise_panels=2, dlm_spanwise_panels=4)
    props = (Installation(baseline_propeller(), float(wing.node_y[-1])),) if propellers else ()
    flight = replace(baseline_flight(), speed_range=(10.0, 250.0, 20.0))   # below Mach 0.9
    return PropellerWing(wing, flight, props, name=f"beam ({aero})")


def _modal(mount: str, aero: str = "strip"):
    beam = _beam(aero)
    if mount == "on-grid":
        s, hubs, _ = ModalStructure.with_mounts(beam, 6)
        grid = hubs[0]
    else:
        s, grid = ModalStructure.from_wing(beam.wing, 6), beam.wing.n_nodes
    grids = tuple(int(g) for g in s.grid_ids[: beam.wing.n_nodes])
    dlm = {} if aero == "strip" else dict(aero="dlm",
                                          dlm_planform=Planform.from_wing(beam.wing))
    return ModalPropellerWing(s, grids, StripPlanform.from_wing(beam.wing), beam.flight,
                              (ModalInstallation(baseline_propeller(), grid, mount),),
                              name=f"modal ({mount})" if aero == "strip" else
                              f"modal ({mount}, {aero})", **dlm)


def _isolated():
    return isolated_baseline_propeller()


def _section():
    return TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=100.0, omega_h=10.0,
                          omega_alpha=25.0, flight=FlightCondition(density=1.225))


#: One model of each kind: (key, what the row is, how a model file holds it, builder).  The
#: keys name the samples in the test, which writes each file kind and runs the commands.
SAMPLES: tuple[tuple[str, str, str, Callable[[], object]], ...] = (
    ("beam", "beam propeller-wing, strip aerodynamics", "`type = \"propeller-wing\"`",
     _beam),
    ("dlm", "beam propeller-wing, doublet lattice", "`[wing] aero = \"dlm\"`",
     lambda: _beam("dlm")),
    ("wing", "beam wing, no flexibly mounted propeller", "no `installations`",
     lambda: _beam(propellers=False)),
    ("modal", "modal propeller-wing, own mounts", "`write_modes(model, path)`",
     lambda: _modal("flexible")),
    ("on-grid", "modal propeller-wing, mounts in the modes",
     "`write_modes(model, path, mount=\"on-grid\")`", lambda: _modal("on-grid")),
    ("modal-dlm", "modal propeller-wing, doublet lattice",
     "`aero = \"dlm\"` and `[dlm]` (a planform)", lambda: _modal("flexible", "dlm")),
    ("isolated", "isolated propeller (rigid wing)", "`type = \"isolated-propeller\"`",
     _isolated),
    ("section", "typical section", "none (Python API)", _section),
)


def sample_capabilities() -> list[tuple[str, str, str, Capabilities]]:
    """(key, row, file, :class:`Capabilities`) of every sample, asked of the model."""
    return [(key, row, where, capabilities(build())) for key, row, where, build in SAMPLES]


def sample_parameters() -> list[tuple[str, str, tuple[tuple[str, str, int], ...]]]:
    """(key, row, (family, derivative, number of paths) ...) of every sample: the model
    contract's :func:`~propwhirl.model.parameter_paths.parameter_families`."""
    return [(key, row, parameter_families(build())) for key, row, _, build in SAMPLES]


def _parameter_rows(reasons: dict[str, int]) -> list[str]:
    """The table of each sample's parameter families, one row per derivative route."""
    out = ["| model | derivative | parameter paths (number of each in the sample) |",
           "|---|---|---|"]
    for (key, row, fams), (_, _, _, c) in zip(sample_parameters(), sample_capabilities()):
        if not fams:
            out.append(f"| {row} | — | {_cell(c, 'sensitivity', reasons, 'none')} |")
            continue
        for route in DERIVATIVE_ROUTES:
            cells = [f"`{f}` ({n})" if n > 1 else f"`{f}`" for f, d, n in fams if d == route]
            if cells:
                out.append(f"| {row} | {route} | {', '.join(cells)} |")
    return out


def _cell(c: Capabilities, feature: str, reasons: dict[str, int], yes: str = "yes") -> str:
    why = c.refusal(feature)
    if why is None:
        return yes
    n = reasons.setdefault(why, len(reasons) + 1)
    return f"— (R{n})"


def page() -> str:
    """The page docs/capabilities.md: what each model kind supports, every refusal with its
    reason (the text is deterministic: the samples' capabilities in a fixed order)."""
    rows = sample_capabilities()
    reasons: dict[str, int] = {}
    out = [
        "# What each model can do",
        "",
        "<!-- generated by `python -m propwhirl.app.capability_table docs/capabilities.md` "
        "from the model contract: do not edit (tests/app/test_capability_table.py checks it) "
        "-->",
        "",
        "Every command and analysis method asks the model what it supports through the model "
        "contract (`propwhirl.model.protocol.capabilities(model)`, a `Capabilities`: its "
        "structure, wing aerodynamics, derivatives, propellers and refusals), never its type. "
        "The tables below are that contract's answers for one model of each kind. A cell "
        "\"— (Rn)\" is a refusal: the command or method stops before any work with one line "
        "giving reason Rn (the command line prints `MODEL: propwhirl COMMAND cannot run this "
        "model: REASON`, a method `method = 'M' is invalid for this model: REASON`).",
        "",
        "## The models",
        "",
        "| model | in a model file | structure | wing aerodynamics | sensitivities | "
        "propellers |",
        "|---|---|---|---|---|---|",
    ]
    for _, row, where, c in rows:
        out.append(f"| {row} | {where} | {c.structure}: {STRUCTURES[c.structure]} | "
                   f"{c.aerodynamics} | {c.derivatives} | {c.propellers} |")
    out += ["", "## Methods (`propwhirl analyse --method`, `analyse(model, method=...)`)", "",
            "| model | " + " | ".join(METHODS) + " |",
            "|---|" + "---|" * len(METHODS)]
    for _, row, _, c in rows:
        cells = [_cell(c, m, reasons, f"yes: {c.aerodynamics_of(m)}") for m in METHODS]
        out.append(f"| {row} | " + " | ".join(cells) + " |")
    out += ["", "`auto` (the default) is `reduced` where the model supports it, else `dense`; "
            "on a doublet-lattice wing `reduced` is the modal Roger state space with every "
            "crossing converged by the p-k.", "", "## Commands", "",
            "| model | " + " | ".join(COMMANDS) + " |",
            "|---|" + "---|" * len(COMMANDS)]
    for _, row, _, c in rows:
        out.append(f"| {row} | " + " | ".join(_cell(c, f, reasons) for f in COMMANDS) + " |")
    out += ["", "## Parameters and their derivatives (`propwhirl sensitivity`)", "",
            "Each model lists the parameters it has sensitivities for and how each one's "
            "derivative is computed (`propwhirl.model.parameter_paths.parameter_paths(model)`, from its capabilities' `parameters`; "
            "`propwhirl sensitivity MODEL --list`), by family (`[i]`: an element, node, "
            "propeller or mode index from 0). "
            + " ".join(f"*{route}*: {how}." for route, how in DERIVATIVE_ROUTES.items()), ""]
    out += _parameter_rows(reasons)
    out += ["", "## Reasons", ""]
    out += [f"- **R{n}**: {why}." for why, n in reasons.items()]
    out += ["", "Finite-state strips: Theodorsen's strip theory with the Leishman-Nguyen or "
            "Wagner lag states (thesis §7.3); exact-Theodorsen strips: the same strips with "
            "the exact C(k), iterated on k by the p-k method; doublet lattice: panels (the dlm "
            "extra), a Roger state space for the finite-state methods, Q(k, Mach) for the "
            "p-k. Every model with propellers has their Houbolt-Reed loads.", ""]
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    """Write :func:`page` to the path given (default: print it)."""
    args = sys.argv[1:] if argv is None else argv
    text = page()
    if args:
        fileio.write_text(Path(args[0]), text, what="capability page")
    else:
        print(text, end="")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
