"""Generated code: one shared CSE per derivation vs one CSE per matrix (issue 8, item 9).

    python benchmarks/generator_cse.py                      # print the tables
    python benchmarks/generator_cse.py --markdown docs/performance.md   # and rewrite its section

Needs the codegen extra (SymPy, jinja2: ``pip install -e ".[codegen]"``).  Three forms of the
generated NumPy code are compared, all rendered by `derivations/generate.py` from the same
derivations:

* ``per-matrix`` — one function per matrix, each with its own ``sympy.cse`` and its own
  broadcast of its arguments; the assembly calls one function per matrix (the form before
  issue 8).
* ``shared`` — one function per block group (`Derivation.blocks`: the matrices the assembly
  uses together, e.g. the twelve propeller aerodynamic matrices A_a … P_6) with one
  ``sympy.cse`` over all entries of all its matrices, as PyDy's code generator does.
* ``merged`` — one function per block group whose code is each matrix's own ``sympy.cse``
  with identical subexpressions computed once: every entry is evaluated by the same
  floating-point operations as in the per-matrix function, so results are bit-identical.

Measured, in one run, with BLAS limited to one thread (threadpoolctl):

(a) generation time (render step; ``derive()`` is common to all forms) and module size;
(b) evaluation time of each block group at realistic argument shapes;
(c) the assembly that matters — `PropellerWing.second_order(V)` and `.state_matrix(V)` of the
    wingtip model (`propwhirl.cases.ch10_other_wings.wingtip_propeller_wing`) at 36 speeds and
    at one speed, and `propwhirl.analysis.analyse(model)` — with each form wired in: the block
    functions of `propwhirl.generated` that the runtime calls (`model.assembly.call_blocks`)
    are replaced, for the duration of a measurement, by the form under test (``per-matrix``:
    a function calling the per-matrix functions one by one, as the runtime did before).

Every timing is the median of ``--repeats`` (≥ 7) samples of process CPU time (steadier than
wall time on a shared machine; the wall-clock medians of (c) are in the ``--json`` output); the
forms alternate within each repeat (in rotating order) so that they sample the same spells of
machine load.
"""
from __future__ import annotations

import argparse
import importlib
import importlib.util
import json
import os
import platform
import re
import sys
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Callable

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:  # derivations/ is a top-level folder, not an installed package
    sys.path.insert(0, str(ROOT))

FORMS = ("per-matrix", "shared", "merged")
#: the block form that generated/ holds (found by `variant_modules`)
SHIPPED: list[str] = []
BEGIN = "<!-- generator_cse:begin -->"
END = "<!-- generator_cse:end -->"
TITLE = "## Generated code: one shared CSE per derivation vs one CSE per matrix"


# ---------------------------------------------------------------------------------- timing
def sample(fn: Callable[[], object], inner: int = 1) -> tuple[float, float]:
    """(wall, CPU) time [s] of one call of `fn`, the mean over `inner` calls."""
    wall, cpu = time.perf_counter(), time.process_time()
    for _ in range(inner):
        fn()
    return (time.perf_counter() - wall) / inner, (time.process_time() - cpu) / inner


def median_cpu(fn: Callable[[], object], repeats: int, inner: int = 1) -> float:
    """Median over `repeats` samples of the CPU time of one call [s]."""
    return float(np.median([sample(fn, inner)[1] for _ in range(repeats)]))


def machine() -> dict[str, str]:
    """nproc, CPU model (/proc/cpuinfo), load and library versions."""
    import scipy
    import sympy
    from threadpoolctl import threadpool_info

    cpu = platform.processor() or "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    blas = ", ".join(f"{i['internal_api']} {i['version']}" for i in threadpool_info()) or "?"
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    return {
        "nproc": str(os.cpu_count()),
        "cpu": cpu,
        "load average (1, 5, 15 min)": load,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "sympy": sympy.__version__,
        "blas": blas,
    }


# ------------------------------------------------------------------------- (a) generation
def generation(repeats: int) -> list[dict]:
    """Render time [s], module size [bytes, lines] and number of CSE assignments per form."""
    from sympy.core.cache import clear_cache

    from derivations.generate import (_Printer, _render_blocks, _render_function, discover,
                                      environment, render)

    env = environment()
    rows = []
    for name in discover():
        clear_cache()
        start = time.perf_counter()
        d = importlib.import_module(f"derivations.{name}").derive()
        derive_s = time.perf_counter() - start
        members = [o for o in d.outputs if any(o.name in m for m in d.blocks.values())]
        printer = _Printer({"fully_qualified_modules": True})
        n_cse = {
            "per-matrix": sum(len(_render_function(o, d, printer)["cse"]) for o in members),
            **{
                cse: sum(len(_render_blocks(g, m, d, printer, cse)["cse"]) for g, m in d.blocks.items())
                for cse in ("shared", "merged")
            },
        }
        variants = {
            "per-matrix": dict(forms=("matrices",)),
            "shared": dict(forms=("blocks",), block_cse="shared"),
            "merged": dict(forms=("blocks",), block_cse="merged"),
            "shipped": dict(),  # what `make generate` writes: per-matrix and merged blocks
        }
        for form, kwargs in variants.items():
            times = []
            for _ in range(repeats):
                clear_cache()  # every render from a cold SymPy cache, as in `make generate`
                start = time.perf_counter()
                text = render(d, env, **kwargs)
                times.append(time.perf_counter() - start)
            rows.append({
                "module": name, "form": form, "derive_s": derive_s,
                "render_s": float(np.median(times)), "bytes": len(text.encode()),
                "lines": text.count("\n"), "functions": len(re.findall(r"^def ", text, re.M)),
                "cse": n_cse.get(form, n_cse["merged"]),
            })
    return rows


def variant_modules(tmp: Path) -> dict[str, dict[str, object]]:
    """The generated modules rendered with shared and with merged block functions, loaded
    from `tmp` (not installed): {form: {module name: module}}."""
    from derivations.generate import generate

    out: dict[str, dict[str, object]] = {}
    for form in ("shared", "merged"):
        written = generate(tmp / form, verbose=False, block_cse=form)
        if all((ROOT / "generated" / f).read_text() == text for f, text in written.items()):
            SHIPPED.append(form)
        mods = {}
        for fname in sorted(written):
            if fname == "__init__.py":
                continue
            name = fname[:-3]
            spec = importlib.util.spec_from_file_location(f"_cse_{form}_{name}", tmp / form / fname)
            mod = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(mod)
            mods[name] = mod
        out[form] = mods
    return out


def per_matrix_blocks(module, group: str) -> Callable[..., dict[str, np.ndarray]]:
    """A block function made of the per-matrix functions of `module` (the pre-issue-8 calls)."""
    members = module.BLOCKS[group][1]
    table = module.OUTPUTS

    def blocks(**values):
        return {m: getattr(module, m)(**{a: values[a] for a in table[m][0]}) for m in members}

    return blocks


def block_function(form: str, variants, module, group: str) -> Callable[..., dict]:
    if form == "per-matrix":
        return per_matrix_blocks(module, group)
    return getattr(variants[form][module.__name__.rsplit(".", 1)[-1]], group)


# ------------------------------------------------------------------------- (b) evaluation
#: (module, block group, description, argument -> leading shape); other arguments are scalars
EVALUATIONS = [
    ("beam_element", "blocks", "25 elements", lambda a: (25,)),
    ("strip_aero", "ln_blocks", "1 speed x 26 nodes",
     lambda a: (1, 1) if a == "V" else (26,) if a in "b a Cla ac".split() else ()),
    ("strip_aero", "ln_blocks", "36 speeds x 26 nodes",
     lambda a: (36, 1) if a == "V" else (26,) if a in "b a Cla ac".split() else ()),
    ("strip_aero", "wagner_blocks", "36 speeds x 26 nodes",
     lambda a: (36, 1) if a == "V" else (26,) if a in "b a Cla ac".split() else ()),
    ("prop_flexwing", "structure_blocks", "36 speeds", lambda a: (36,) if a == "Omega" else ()),
    ("prop_flexwing", "aero_blocks", "1 speed", lambda a: (1,) if a == "V" or a.startswith("C") else ()),
    ("prop_flexwing", "aero_blocks", "36 speeds", lambda a: (36,) if a == "V" or a.startswith("C") else ()),
    ("prop_flexwing", "aero_blocks", "400 speeds", lambda a: (400,) if a == "V" or a.startswith("C") else ()),
    ("prop_rigid", "aero_blocks", "36 speeds", lambda a: (36,) if a == "V" or a.startswith("C") else ()),
    ("prop_rigid", "aero_blocks", "400 speeds", lambda a: (400,) if a == "V" or a.startswith("C") else ()),
    ("typical_section", "blocks", "scalars", lambda a: ()),
]


def evaluation(variants, repeats: int) -> list[dict]:
    """Time [s] of one evaluation of each block group per form, and the largest difference
    of the forms' matrices relative to the per-matrix ones (scaled by each matrix's max)."""
    rng = np.random.default_rng(20240908)
    rows = []
    for modname, group, what, shape_of in EVALUATIONS:
        module = importlib.import_module(f"propwhirl.generated.{modname}")
        argnames = module.BLOCKS[group][0]
        values = {a: rng.uniform(0.5, 2.0, shape_of(a)) for a in argnames}
        fns = {f: block_function(f, variants, module, group) for f in FORMS}
        reference = fns["per-matrix"](**values)
        row = {"module": modname, "group": group, "shape": what}
        for f in FORMS:
            got = fns[f](**values)
            row[f"{f}_s"] = median_cpu(lambda fn=fns[f]: fn(**values), repeats, inner=100)
            row[f"{f}_diff"] = max(
                float(np.max(np.abs(np.broadcast_to(reference[m], got[m].shape) - got[m]))
                      / max(float(np.max(np.abs(got[m]))), 1e-300))
                for m in got
            )
        rows.append(row)
    return rows


# --------------------------------------------------------------------------- (c) assembly
@contextmanager
def wired(form: str, variants):
    """Make the runtime's block functions those of `form` while the block runs."""
    from propwhirl.generated import MODULES

    saved = []
    try:
        for name in MODULES:
            module = importlib.import_module(f"propwhirl.generated.{name}")
            for group in getattr(module, "BLOCKS", {}):
                saved.append((module, group, getattr(module, group)))
                setattr(module, group, block_function(form, variants, module, group))
        yield
    finally:
        for module, group, fn in saved:
            setattr(module, group, fn)


def assembly(variants, repeats: int) -> dict:
    """Median times [s] of the wingtip model's assembly and analysis with each form, and
    how far each form's state matrices and instability speeds are from the per-matrix ones."""
    from propwhirl.analysis import analyse
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    model = wingtip_propeller_wing()
    V36 = np.linspace(1.0, 350.0, 36)
    V1 = np.array([150.0])
    measures = {
        "second_order(V), 36 speeds": (lambda: model.second_order(V36), 5),
        "state_matrix(V), 36 speeds": (lambda: model.state_matrix(V36), 3),
        "second_order(V), 1 speed": (lambda: model.second_order(V1), 50),
        "state_matrix(V), 1 speed": (lambda: model.state_matrix(V1), 50),
        "analyse(model)": (lambda: analyse(model), 1),
    }
    check = {}
    for f in FORMS:
        with wired(f, variants):
            A = model.state_matrix(V36)
            speeds = np.array([e.V for e in analyse(model).events])
            for fn, _ in measures.values():
                fn()  # warm-up
        check[f] = (A, speeds)
    A0, s0 = check["per-matrix"]
    agreement = {
        f: {
            "state_matrix_identical": bool(np.array_equal(A, A0)),
            "state_matrix_max_rel_diff": float(np.max(np.abs(A - A0)) / np.max(np.abs(A0))),
            "event_speeds_max_rel_diff": (
                float(np.max(np.abs(s - s0) / np.abs(s0))) if s.shape == s0.shape else float("nan")
            ),
        }
        for f, (A, s) in check.items()
    }
    samples: dict[str, dict[str, list[tuple[float, float]]]] = {
        k: {f: [] for f in FORMS} for k in measures
    }
    for r in range(repeats):
        order = FORMS[r % len(FORMS):] + FORMS[: r % len(FORMS)]
        for f in order:
            with wired(f, variants):
                for key, (fn, inner) in measures.items():
                    samples[key][f].append(sample(fn, inner))
    def stat(reduce, which):
        return {k: {f: float(reduce([x[which] for x in v])) for f, v in per.items()}
                for k, per in samples.items()}

    return {
        "times": stat(np.median, 1), "min": stat(np.min, 1),
        "wall": stat(np.median, 0), "wall_min": stat(np.min, 0),
        "samples": samples, "agreement": agreement, "n_states": int(A0.shape[-1]),
    }


# ------------------------------------------------------------------------------- report
def report(info: dict, gen: list[dict], ev: list[dict], asm: dict, repeats: int) -> str:
    """The section text (between the markers) as Markdown."""
    out = []
    m = info["machine"]
    out.append(
        f"Machine: nproc {m['nproc']}, CPU {m['cpu']}, load average {m['load average (1, 5, 15 min)']}; "
        f"python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, sympy {m['sympy']}, "
        f"BLAS {m['blas']} limited to 1 thread. Median of {repeats} repeats."
    )
    out.append("")
    out.append("(c) Assembly and analysis of the wingtip model "
               f"({asm['n_states']} states), CPU time in milliseconds (median; wall-clock times "
               "and minima are in the `--json` output):")
    out.append("")
    out.append("| measurement | per-matrix | shared | merged | per-matrix / shared | per-matrix / merged | merged / shared |")
    out.append("|---|---:|---:|---:|---:|---:|---:|")
    for key, t in asm["times"].items():
        p, s, g = (1e3 * t[f] for f in FORMS)
        out.append(f"| `{key}` | {p:.3f} | {s:.3f} | {g:.3f} | {p / s:.2f} | {p / g:.2f} | {g / s:.2f} |")
    out.append("")
    agr = asm["agreement"]
    out.append(
        "Agreement with the per-matrix form: state matrices at 36 speeds "
        + "; ".join(
            f"{f} {'bit-identical' if agr[f]['state_matrix_identical'] else 'max rel. diff %.1e' % agr[f]['state_matrix_max_rel_diff']}"
            for f in ("shared", "merged")
        )
        + "; speeds of the instability events of `analyse` "
        + "; ".join(f"{f} max rel. diff {agr[f]['event_speeds_max_rel_diff']:.1e}" for f in ("shared", "merged"))
        + "."
    )
    out.append("")
    out.append("(b) One evaluation of each block group (random arguments of the given leading "
               "shape), CPU time in microseconds:")
    out.append("")
    out.append("| module | block group | shape | per-matrix | shared | merged | per-matrix / shared | per-matrix / merged | shared max rel. diff |")
    out.append("|---|---|---|---:|---:|---:|---:|---:|---:|")
    for r in ev:
        p, s, g = (1e6 * r[f"{f}_s"] for f in FORMS)
        out.append(f"| {r['module']} | `{r['group']}` | {r['shape']} | {p:.0f} | {s:.0f} | {g:.0f} | "
                   f"{p / s:.2f} | {p / g:.2f} | {r['shared_diff']:.0e} |")
    out.append("")
    out.append("(a) Generation (render step, cold SymPy cache; `derive()` is common to all forms) "
               "and module size. per-matrix: the module with one function per matrix (all "
               "outputs); shared, merged: a module with the block functions only; shipped: "
               "generated/ as `make generate` writes it (per-matrix functions and merged block "
               "functions). CSE: number of common-subexpression assignments over the matrices "
               "of the block groups (shipped: those of its block functions).")
    out.append("")
    out.append("| module | derive [s] | form | render [s] | size [kB] | lines | functions | CSE |")
    out.append("|---|---:|---|---:|---:|---:|---:|---:|")
    for r in gen:
        out.append(f"| {r['module']} | {r['derive_s']:.2f} | {r['form']} | {r['render_s']:.2f} | "
                   f"{r['bytes'] / 1e3:.1f} | {r['lines']} | {r['functions']} | {r['cse']} |")
    out.append("")
    out.append(f"Decision: {info['decision']}")
    return "\n".join(out)


def decide(asm: dict) -> str:
    """What the measurement says and what generated/ ships (the rule is in the docs)."""
    lines = []
    for key in ("state_matrix(V), 1 speed", "state_matrix(V), 36 speeds", "analyse(model)"):
        t = asm["times"][key]
        fastest = min(FORMS, key=t.get)
        lines.append(f"`{key}` fastest {fastest} (per-matrix/merged "
                     f"{t['per-matrix'] / t['merged']:.2f}, merged/shared {t['merged'] / t['shared']:.2f})")
    shipped = SHIPPED[0] if SHIPPED else "neither (generated/ is stale: run `make generate`)"
    return (
        "; ".join(lines) + " (differences of a few per cent are within the load noise). "
        f"generated/ ships the block functions in the {shipped} form, and the runtime calls them."
    )


def write_markdown(path: Path, body: str) -> None:
    """Replace the text between this benchmark's markers in ``path`` (append the section if
    absent): :func:`markdown_section.replace_section`."""
    replace_section(path, body, BEGIN, END, TITLE)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=9, help="samples per timing (median; >= 7)")
    parser.add_argument("--generation-repeats", type=int, default=7, help="renders per form and module")
    parser.add_argument("--markdown", type=Path, help="rewrite this file's generator_cse section")
    parser.add_argument("--json", type=Path, help="write all numbers to this JSON file")
    args = parser.parse_args(argv)
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1), tempfile.TemporaryDirectory() as tmp:
        info = {"machine": machine()}
        variants = variant_modules(Path(tmp))
        asm = assembly(variants, args.repeats)
        ev = evaluation(variants, args.repeats)
        gen = generation(args.generation_repeats)
    info["decision"] = decide(asm)
    body = report(info, gen, ev, asm, args.repeats)
    print(body)
    if args.json:
        args.json.write_text(json.dumps(
            {"info": info, "generation": gen, "evaluation": ev, "assembly": asm}, indent=2))
    if args.markdown:
        write_markdown(args.markdown, body)
        print(f"wrote the section of {args.markdown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
