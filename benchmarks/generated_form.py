"""Generated code: one form against the two forms before it (issue 21, item 5).

    python benchmarks/generated_form.py                                  # print the tables
    python benchmarks/generated_form.py --markdown docs/performance.md   # and rewrite its section
    python benchmarks/generated_form.py --reproduce BEFORE.json AFTER.json --markdown ...

*Before*: `generated/` at the git revision ``--before`` (default :data:`BEFORE`, the last one
with two forms: a function per matrix with its own code, and block functions whose
common subexpressions were each matrix's own, so as to be bit-identical to them), read with
``git show`` and loaded from a temporary folder.  *After*: `generated/` of the working tree
(`propwhirl.generated`): the block functions with one ``sympy.cse`` over all their matrices,
and per matrix a view of its block function (or, for a matrix in no block, its own code).

Measured in one run, with BLAS limited to one thread (threadpoolctl):

(a) the generated code's size: lines of each kind of function, and of the files;
(b) the time of one evaluation of each block function the runtime calls when it assembles the
    wingtip model (`propwhirl.cases.ch10_other_wings.wingtip_propeller_wing`) at a speed
    vector (36 speeds from 1 to 350 m/s, and one speed), on the very arguments the assembly
    passes (captured from `second_order(V)` of a fresh model), before and after alternating
    within each repeat; the median of ``--repeats`` samples of process CPU time, each the mean
    of ``--inner`` calls; and the largest difference of the matrices (relative to each matrix's
    largest entry);
(c) with ``--reproduce BEFORE.json AFTER.json`` (two outputs of ``propwhirl reproduce --json``,
    run separately: before at the revision, after at the working tree), the change of every
    computed value: the largest relative change, how many moved, and whether each stays within
    its last printed digit (the report prints 5 significant digits: ``format_table``'s
    ``%12.5g``) and within its tolerance as before.
"""
from __future__ import annotations

import argparse
import ast
import importlib
import importlib.util
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
#: the last revision whose generated/ has the per-matrix functions with code of their own and
#: the merged-CSE block functions (main before issue 21, item 5)
BEFORE = "6d1ccf3"
BEGIN = "<!-- generated_form:begin -->"
END = "<!-- generated_form:end -->"
TITLE = "## Generated code: one form (issue 21, item 5)"
KINDS = ("block functions", "per-matrix code (matrices in a block)", "views",
         "matrices in no block", "derivative functions", "helpers")


# ----------------------------------------------------------------------------- modules
def before_modules(rev: str, tmp: Path) -> dict[str, object]:
    """generated/*.py at git revision `rev`, loaded from `tmp`: {module name: module}."""
    names = subprocess.run(["git", "ls-tree", "--name-only", f"{rev}:generated"], cwd=ROOT,
                           check=True, capture_output=True, text=True).stdout.split()
    out = {}
    for fname in sorted(names):
        if not fname.endswith(".py") or fname == "__init__.py":
            continue
        text = subprocess.run(["git", "show", f"{rev}:generated/{fname}"], cwd=ROOT, check=True,
                              capture_output=True, text=True).stdout
        path = tmp / fname
        path.write_text(text)
        spec = importlib.util.spec_from_file_location(f"_before_{fname[:-3]}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        out[fname[:-3]] = module
    return out


def after_modules() -> dict[str, object]:
    """The working tree's generated modules: {module name: module}."""
    from propwhirl.generated import MODULES

    return {n: importlib.import_module(f"propwhirl.generated.{n}") for n in MODULES}


# --------------------------------------------------------------------------------- (a) size
def kind_lines(text: str) -> dict[str, int]:
    """Lines of each kind of top-level function of a generated module, and of the file."""
    tree = ast.parse(text)
    tables = {}
    for node in tree.body:
        if (isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)
                and node.targets[0].id in ("OUTPUTS", "BLOCKS", "PARTIALS", "VIEWS")):
            tables[node.targets[0].id] = ast.literal_eval(node.value)
    in_block = {m for _, members in tables.get("BLOCKS", {}).values() for m in members}
    lines = dict.fromkeys(KINDS, 0)
    for node in tree.body:
        if not isinstance(node, ast.FunctionDef):
            continue
        n = node.name
        if n in tables.get("BLOCKS", {}):
            kind = "block functions"
        elif n in tables.get("PARTIALS", {}):
            kind = "derivative functions"
        elif n in tables.get("VIEWS", {}):
            kind = "views"
        elif n in tables.get("OUTPUTS", {}):
            kind = "per-matrix code (matrices in a block)" if n in in_block else "matrices in no block"
        else:
            kind = "helpers"
        lines[kind] += node.end_lineno - node.lineno + 1
    lines["file"] = text.count("\n")
    return lines


def sizes(before: dict[str, object]) -> dict[str, dict[str, int]]:
    """{"before"/"after": {kind: lines summed over the modules}}."""
    out = {}
    for form, texts in (("before", [Path(m.__file__).read_text() for m in before.values()]),
                        ("after", [Path(m.__file__).read_text() for m in after_modules().values()])):
        total: dict[str, int] = {}
        for text in texts:
            for k, v in kind_lines(text).items():
                total[k] = total.get(k, 0) + v
        out[form] = total
    return out


# --------------------------------------------------------------------------- (b) evaluation
def captured_calls(speeds: np.ndarray) -> list[tuple[str, str, dict]]:
    """(module, block function, keyword arguments) of every block call of the wingtip
    model's `second_order(speeds)` (a fresh model: nothing cached)."""
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    modules = after_modules()
    calls: list[tuple[str, str, dict]] = []
    saved = []
    try:
        for name, module in modules.items():
            for group in module.BLOCKS:
                fn = getattr(module, group)

                def spy(_fn=fn, _name=name, _group=group, **kwargs):
                    # copies: the model freezes some of its arrays (read-only) after the call
                    calls.append((_name, _group, {k: np.array(v) for k, v in kwargs.items()}))
                    return _fn(**kwargs)

                saved.append((module, group, fn))
                setattr(module, group, spy)
        wingtip_propeller_wing().second_order(speeds)
    finally:
        for module, group, fn in saved:
            setattr(module, group, fn)
    return calls


def sample_cpu(fn: Callable[[], object], inner: int) -> float:
    """CPU time [s] of one call of `fn`, the mean over `inner` calls."""
    start = time.process_time()
    for _ in range(inner):
        fn()
    return (time.process_time() - start) / inner


def evaluation(before: dict[str, object], repeats: int, inner: int) -> list[dict]:
    """Per speed vector and block call: median CPU time before and after [s] and the largest
    relative difference of the matrices; a row "all" with the sums."""
    after = after_modules()
    rows = []
    for label, speeds in (("36 speeds", np.linspace(1.0, 350.0, 36)), ("1 speed", np.array([150.0]))):
        calls = captured_calls(speeds)
        fns = [(getattr(before[n], g), getattr(after[n], g), kw) for n, g, kw in calls]
        samples = {(k, f): [] for k in range(len(fns)) for f in ("before", "after")}
        for r in range(repeats):
            for k, (fb, fa, kw) in enumerate(fns):
                order = (("before", fb), ("after", fa)) if r % 2 == 0 else (("after", fa), ("before", fb))
                for form, fn in order:
                    samples[k, form].append(sample_cpu(lambda fn=fn, kw=kw: fn(**kw), inner))
        for k, ((n, g, _), (fb, fa, kw)) in enumerate(zip(calls, fns)):
            b, a = fb(**kw), fa(**kw)
            diff = max(float(np.max(np.abs(a[m] - b[m]))) / max(float(np.max(np.abs(b[m]))), 1e-300)
                       for m in b)
            rows.append({"speeds": label, "call": f"{n}.{g}",
                         "before_s": float(np.median(samples[k, "before"])),
                         "after_s": float(np.median(samples[k, "after"])), "max_rel_diff": diff})
        total = {f: float(np.median([sum(samples[k, f][r] for k in range(len(fns)))
                                     for r in range(repeats)])) for f in ("before", "after")}
        rows.append({"speeds": label, "call": "all of one second_order(V)",
                     "before_s": total["before"], "after_s": total["after"],
                     "max_rel_diff": max(r["max_rel_diff"] for r in rows if r["speeds"] == label)})
    return rows


# ---------------------------------------------------------------------------- (c) reproduce
def last_digit(x: float) -> float:
    """One unit of the last digit of `x` as the reproduction report prints it (``%.5g``)."""
    if x == 0:
        return 0.0
    return 10.0 ** (np.floor(np.log10(abs(float(f"{x:.5g}")))) - 4)


def reproduce_change(before_json: Path, after_json: Path) -> dict:
    """The change of every computed value between two ``propwhirl reproduce --json`` outputs."""
    before = {r["id"]: r for r in json.loads(before_json.read_text())["records"]}
    after = {r["id"]: r for r in json.loads(after_json.read_text())["records"]}
    if set(before) != set(after):
        raise ValueError(f"the two outputs have different ids: {sorted(set(before) ^ set(after))}")
    rows = []
    for i, b in before.items():
        a = after[i]
        if b["computed"] is None or a["computed"] is None:
            rows.append({"id": i, "computed_both": b["computed"] is None and a["computed"] is None})
            continue
        change = a["computed"] - b["computed"]
        rows.append({
            "id": i, "before": b["computed"], "after": a["computed"],
            "rel_change": abs(change) / abs(b["computed"]) if b["computed"] else abs(change),
            "printed_same": f"{a['computed']:.5g}" == f"{b['computed']:.5g}",
            "within_last_digit": bool(abs(change) < last_digit(b["computed"])),
            "within_tol_same": a["within_tol"] == b["within_tol"],
        })
    values = [r for r in rows if "before" in r]
    worst = max(values, key=lambda r: r["rel_change"])
    return {
        "n": len(rows), "computed": len(values),
        "none_in_one_only": [r["id"] for r in rows if "before" not in r and not r["computed_both"]],
        "moved": sum(r["rel_change"] > 0 for r in values),
        "max_rel_change": worst["rel_change"], "max_id": worst["id"],
        "max_before": worst["before"], "max_after": worst["after"],
        "printed_changed": [r["id"] for r in values if not r["printed_same"]],
        "beyond_last_digit": [r["id"] for r in values if not r["within_last_digit"]],
        "within_tol_changed": [r["id"] for r in values if not r["within_tol_same"]],
        "rows": rows,
    }


# ------------------------------------------------------------------------------- report
def machine() -> str:
    import scipy
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
    return (f"Machine: nproc {os.cpu_count()}, CPU {cpu}, load average {load}; python "
            f"{platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
            f"BLAS {blas} limited to 1 thread.")


def report(rev: str, size: dict, ev: list[dict], repro: dict | None, repeats: int, inner: int) -> str:
    out = [machine() + f" Before: generated/ at {rev}; after: the working tree.", ""]
    out.append("(a) Lines of the generated modules (all seven; `__init__.py` aside), by kind of "
               "function:")
    out.append("")
    out.append("| kind | before | after |")
    out.append("|---|---:|---:|")
    for k in KINDS + ("file",):
        out.append(f"| {'whole files' if k == 'file' else k} | {size['before'].get(k, 0)} | "
                   f"{size['after'].get(k, 0)} |")
    out.append("")
    out.append("(b) One evaluation of each block function the assembly of the wingtip model "
               f"calls in `second_order(V)`, on its arguments; CPU time in microseconds, median of "
               f"{repeats} samples of {inner} calls each, before and after alternating:")
    out.append("")
    out.append("| speeds | block function | before | after | before / after | max rel. diff |")
    out.append("|---|---|---:|---:|---:|---:|")
    for r in ev:
        out.append(f"| {r['speeds']} | `{r['call']}` | {1e6 * r['before_s']:.0f} | "
                   f"{1e6 * r['after_s']:.0f} | {r['before_s'] / r['after_s']:.2f} | "
                   f"{r['max_rel_diff']:.0e} |")
    if repro is not None:
        out.append("")
        moved = repro["moved"]
        out.append(
            f"(c) `propwhirl reproduce --json`, before against after: {repro['computed']} of "
            f"{repro['n']} values computed by both; {moved} moved, the largest by "
            f"{repro['max_rel_change']:.1e} relative (`{repro['max_id']}`: "
            f"{repro['max_before']:.10g} → {repro['max_after']:.10g}); "
            + ("every value prints the same (5 significant digits)" if not repro["printed_changed"]
               else f"{len(repro['printed_changed'])} print differently: "
               + ", ".join(f"`{i}`" for i in repro["printed_changed"]))
            + "; "
            + ("every change is below one unit of the last printed digit" if not repro["beyond_last_digit"]
               else "beyond one unit of the last printed digit: "
               + ", ".join(f"`{i}`" for i in repro["beyond_last_digit"]))
            + "; "
            + ("no value changed whether it is within its tolerance." if not repro["within_tol_changed"]
               else "within tolerance changed for: "
               + ", ".join(f"`{i}`" for i in repro["within_tol_changed"]) + ".")
        )
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default=BEFORE, help=f"git revision of the former generated/ (default {BEFORE})")
    parser.add_argument("--repeats", type=int, default=15, help="samples per timing (median)")
    parser.add_argument("--inner", type=int, default=50, help="calls per sample")
    parser.add_argument("--reproduce", type=Path, nargs=2, metavar=("BEFORE_JSON", "AFTER_JSON"),
                        help="two outputs of `propwhirl reproduce --json` to compare")
    parser.add_argument("--markdown", type=Path, help="rewrite this file's generated_form section")
    parser.add_argument("--json", type=Path, help="write all numbers to this JSON file")
    args = parser.parse_args(argv)
    from threadpoolctl import threadpool_limits

    repro = reproduce_change(*args.reproduce) if args.reproduce else None
    with threadpool_limits(limits=1), tempfile.TemporaryDirectory() as tmp:
        before = before_modules(args.before, Path(tmp))
        size = sizes(before)
        ev = evaluation(before, args.repeats, args.inner)
    body = report(args.before, size, ev, repro, args.repeats, args.inner)
    print(body)
    if args.json:
        args.json.write_text(json.dumps({"size": size, "evaluation": ev, "reproduce": repro}, indent=2))
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END, TITLE)
        print(f"wrote the section of {args.markdown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
