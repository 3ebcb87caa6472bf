"""Render every derivation into a plain NumPy module in `generated/` (run by `make generate`).

    python -m derivations.generate --out generated

Each module in `derivations/` that defines ``derive()`` becomes `generated/<module>.py`:
common subexpressions are eliminated (``sympy.cse``) and the expressions printed with SymPy's
NumPy printer, through the jinja2 template `templates/module.py.j2`.  The output is
deterministic (sorted discovery, fixed entry order, pinned SymPy), so running the generator
twice gives byte-identical files; tests/test_freshness.py holds `generated/` to that.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
import time
from pathlib import Path

import jinja2
import sympy as sp
from sympy.printing.numpy import NumPyPrinter

import derivations
from derivations.common import Derivation, Output

ROOT = Path(__file__).resolve().parent.parent
TEMPLATES = ROOT / "templates"
SKIP = {"common", "generate"}


def discover() -> list[str]:
    """Derivation module names, sorted (deterministic)."""
    names = [m.name for m in pkgutil.iter_modules(derivations.__path__) if m.name not in SKIP]
    return sorted(n for n in names if hasattr(importlib.import_module(f"derivations.{n}"), "derive"))


class _Printer(NumPyPrinter):
    """SymPy's NumPy printer (rationals print as Python float divisions, e.g. 13/420)."""


def _render_function(out: Output, d: Derivation, printer: _Printer) -> dict:
    matrix = sp.Matrix(out.matrix)
    args = list(out.args)
    free = set().union(*(e.free_symbols for e in matrix)) if matrix else set()
    missing = free - set(args)
    if missing:
        raise ValueError(f"{d.module}.{out.name}: symbols {sorted(map(str, missing))} not in args")
    entries = [(i, j, matrix[i, j]) for i in range(matrix.rows) for j in range(matrix.cols)]
    entries = [(i, j, e) for i, j, e in entries if e != 0]
    replacements, reduced = sp.cse(
        [e for _, _, e in entries], symbols=sp.numbered_symbols("_c"), order="canonical"
    )
    params = {p.symbol: p for p in d.params}
    return {
        "name": out.name,
        "doc": out.doc,
        "equations": out.equations,
        "signature": ", ".join(a.name for a in args),
        "argnames": repr(tuple(a.name for a in args)),
        "arginfo": [
            {"name": a.name, "doc": params[a].doc, "unit": params[a].unit} for a in args
        ],
        "rows": repr(tuple(out.rows)),
        "cols": repr(tuple(out.cols)),
        "rows_text": ", ".join(out.rows),
        "cols_text": ", ".join(out.cols),
        "nrows": matrix.rows,
        "ncols": matrix.cols,
        "cse": [(str(s), printer.doprint(e)) for s, e in replacements],
        "entries": [(i, j, printer.doprint(e)) for (i, j, _), e in zip(entries, reduced)],
    }


def render(d: Derivation, env: jinja2.Environment) -> str:
    printer = _Printer({"fully_qualified_modules": True})
    functions = [_render_function(o, d, printer) for o in d.outputs]
    doc = (d.doc or "").strip().replace('"""', "'''")
    text = env.get_template("module.py.j2").render(d=d, functions=functions, doc=doc)
    return text.rstrip() + "\n"


def generate(out_dir: Path, only: list[str] | None = None, verbose: bool = True) -> dict[str, str]:
    """Write all generated modules to `out_dir`; return {file name: text}."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(TEMPLATES)),
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )
    out_dir.mkdir(parents=True, exist_ok=True)
    written: dict[str, str] = {}
    derivs = []
    for name in discover():
        if only and name not in only:
            continue
        start = time.perf_counter()
        d = importlib.import_module(f"derivations.{name}").derive()
        text = render(d, env)
        (out_dir / f"{d.module}.py").write_text(text)
        written[f"{d.module}.py"] = text
        derivs.append(d)
        if verbose:
            print(f"generated/{d.module}.py  {len(text):>8} bytes  {time.perf_counter() - start:6.2f} s")
    if not only:
        init = env.get_template("package_init.py.j2").render(modules=derivs).rstrip() + "\n"
        (out_dir / "__init__.py").write_text(init)
        written["__init__.py"] = init
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "generated")
    parser.add_argument("--only", nargs="*", help="derivation modules to regenerate")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    generate(args.out, args.only)
    print(f"total {time.perf_counter() - start:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
