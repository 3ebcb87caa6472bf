"""Every instability of the default against the p-k method's, on the examples and the
NASTRAN-95 side-by-side cases (issue 37: "the default never reports a critical speed the p-k
does not have"; the note gives every critical speed default vs p-k).

For each case ``analyse(model)`` (the default: the finite-state strips' state space, or on a
doublet-lattice wing the modal Roger state space with its crossings converged by the p-k) and
``analyse(model, method="pk")`` (exact Theodorsen strips or Q(k, M) of the panels); each
onset (flutter, divergence, unstable at the first speed) of either is matched to the other's
of the same kind nearest in speed (within 5 %).  The table gives the criticals side by side
and the onsets only one of them has.  One BLAS thread; CPU seconds of each analysis.  From
the repository root::

    .venv/bin/python benchmarks/default_vs_pk.py --markdown docs/validation.md
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from markdown_section import replace_section  # noqa: E402

from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.engine import single_thread_blas  # noqa: E402
from propwhirl.io import load_model  # noqa: E402

BEGIN, END = "<!-- default-vs-pk:begin -->", "<!-- default-vs-pk:end -->"
#: onsets of one kind within this fraction of each other's speed are the same instability
SAME = 0.05
EXAMPLES = ("wingtip", "four_propeller", "x57_like", "x57_like_folded")


def cases():
    """(label, model, speeds or None) of every case."""
    for name in EXAMPLES:
        m = load_model(ROOT / "examples" / f"{name}.toml")
        lo, hi = m.flight.speeds()[[0, -1]]
        yield f"{name}, strips ({lo:g}-{hi:g} m/s)", m, None
    for name in ("wingtip", "x57_like"):
        m = load_model(ROOT / "examples" / f"{name}.toml")
        speeds = m.flight.speeds()           # the panels' tables: Mach <= 0.9; here <= 0.85
        speeds = speeds[speeds <= 0.85 * m.flight.speed_of_sound]
        yield (f"{name}, panels (Mach V/a, {speeds[0]:g}-{speeds[-1]:g} m/s)",
               m.with_(wing=dataclasses.replace(m.wing, aero="dlm")), speeds)
    import nastran95_side_by_side as nb
    for case, (label, _) in nb.CASES.items():
        model, speeds, _ = nb.build(case)
        yield label, model, speeds


def onsets(a) -> list:
    return [e for e in a.events if e.event in ("onset", "unstable-at-start")]


def row(label: str, model, speeds) -> str:
    t0 = time.process_time()
    d = analyse(model, speeds)
    t1 = time.process_time()
    p = analyse(model, speeds, method="pk")
    t2 = time.process_time()

    def crit(a) -> str:
        c = a.critical
        if c is None:
            return "none"
        f = f", {c.frequency_hz:.3f} Hz" if c.kind == "flutter" else ""
        return f"{c.kind} {c.V:.2f}{f}"

    dd, pp = onsets(d), onsets(p)
    only_d = [e for e in dd if not any(q.kind == e.kind and abs(q.V - e.V) <= SAME * e.V
                                       for q in pp)]
    only_p = [e for e in pp if not any(q.kind == e.kind and abs(q.V - e.V) <= SAME * e.V
                                       for q in dd)]
    dv = ("–" if d.critical is None or p.critical is None
          else f"{100 * (d.critical.V - p.critical.V) / p.critical.V:+.3f}")

    def listed(es) -> str:
        return ", ".join(f"{e.kind} {e.V:.1f}" for e in es) or "–"

    return (f"| {label} | {crit(d)} | {crit(p)} | {dv} | {len(dd)} / {len(pp)} | "
            f"{listed(only_d)} | {listed(only_p)} | {t1 - t0:.1f} / {t2 - t1:.1f} |")


def table() -> str:
    lines = ["| case | default critical [m/s] | p-k critical [m/s] | ΔV [%] | onsets default / "
             "p-k | only the default's | only the p-k's | CPU default / p-k [s] |",
             "|---|---|---|---:|---:|---|---|---:|"]
    for label, model, speeds in cases():
        lines.append(row(label, model, speeds))
        print(lines[-1], flush=True)
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--markdown", type=Path, help="write the table into this file")
    args = ap.parse_args()
    with single_thread_blas():
        body = table()
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END,
                        title="### Every example: the default against the p-k (issue 37)")


if __name__ == "__main__":
    main()
