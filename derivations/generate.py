"""Render every derivation into a plain NumPy module in `generated/` (run by `make generate`).

    python -m derivations.generate --out generated

Each module in `derivations/` that defines ``derive()`` becomes `generated/<module>.py`:
common subexpressions are eliminated (``sympy.cse``) and the expressions printed with SymPy's
NumPy printer, through the jinja2 template `templates/module.py.j2`.  Every matrix is computed
by exactly one piece of generated code:

- one *block function* per entry of ``Derivation.blocks``, returning the matrices the assembly
  uses together (a dict) after broadcasting the arguments once, with one ``sympy.cse`` over
  all of them (PyDy's way): what the runtime calls;
- one function per matrix (``Derivation.outputs``), the documented API that the oracle tests
  check against the thesis's printed matrices: for a matrix in a block, a *view* — the
  block function called with the matrix's arguments (the block's other arguments NaN: they
  feed only the other matrices), its matrix returned; for a matrix in no block, the matrix's
  own code with its own ``sympy.cse``;
- one *derivative function* ``<name>_d`` per block function (and per matrix in no block):
  ``{matrix name: {parameter: ∂matrix/∂parameter}}`` for every argument, identically-zero
  derivatives left out, one ``sympy.cse`` over all of them.  The derivatives are SymPy's
  ``diff`` of the very matrices the other forms print; the runtime builds ∂A/∂p from them by
  the same assembly as A (`src/propwhirl/model/derivatives.py`).

Until issue 21 the per-matrix functions carried their own code too, and the block functions
reused each matrix's own ``sympy.cse`` so as to stay bit-identical to them; the measurement
of the one form against that: benchmarks/generated_form.py, docs/performance.md.

The output is deterministic (sorted discovery, fixed entry order, pinned SymPy), so running
the generator twice gives byte-identical files; tests/generated/test_freshness.py holds
`generated/` to that.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
import time
from pathlib import Path
from typing import Sequence

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


def _check_args(label: str, exprs, args, d: Derivation) -> None:
    free = set().union(*(e.free_symbols for e in exprs)) if exprs else set()
    missing = free - set(args)
    if missing:
        raise ValueError(f"{d.module}.{label}: symbols {sorted(map(str, missing))} not in args")


def _nonzero_entries(matrix: sp.Matrix) -> list[tuple[int, int, sp.Expr]]:
    entries = [(i, j, matrix[i, j]) for i in range(matrix.rows) for j in range(matrix.cols)]
    return [(i, j, e) for i, j, e in entries if e != 0]


def _cse(exprs: list[sp.Expr]):
    return sp.cse(exprs, symbols=sp.numbered_symbols("_c"), order="canonical")


def _arginfo(args, d: Derivation) -> list[dict]:
    params = {p.symbol: p for p in d.params}
    return [{"name": a.name, "doc": params[a].doc, "unit": params[a].unit} for a in args]


def _render_function(
    out: Output, d: Derivation, printer: _Printer, block: str | None = None
) -> dict:
    """The function of one matrix: with `block`, a view (the matrix as the block function
    `block` computes it: no code of its own); without, the matrix's code, its own
    ``sympy.cse`` (a matrix in no block)."""
    matrix = sp.Matrix(out.matrix)
    args = list(out.args)
    _check_args(out.name, list(matrix), args, d)
    if block is None:
        entries = _nonzero_entries(matrix)
        replacements, reduced = _cse([e for _, _, e in entries])
        cse = [(str(s), printer.doprint(e)) for s, e in replacements]
        texts = [(i, j, printer.doprint(e)) for (i, j, _), e in zip(entries, reduced)]
    else:
        cse, texts = [], []
    return {
        "name": out.name,
        "doc": out.doc,
        "equations": out.equations,
        "signature": ", ".join(a.name for a in args),
        "argnames": repr(tuple(a.name for a in args)),
        "arginfo": _arginfo(args, d),
        "rows": repr(tuple(out.rows)),
        "cols": repr(tuple(out.cols)),
        "rows_text": ", ".join(out.rows),
        "cols_text": ", ".join(out.cols),
        "nrows": matrix.rows,
        "ncols": matrix.cols,
        "block": block,
        "cse": cse,
        "entries": texts,
    }


def _render_blocks(name: str, members: Sequence[str], d: Derivation, printer: _Printer) -> dict:
    """One function returning several outputs, broadcasting its arguments once.

    Its arguments are the union of the members' arguments, in the derivation's parameter
    order; every returned array has the full broadcast shape.  One ``sympy.cse`` over all
    nonzero entries of all members (as PyDy's code generator does): a subexpression that
    several matrices share is computed once.
    """
    by_name = {o.name: o for o in d.outputs}
    unknown = [m for m in members if m not in by_name]
    if unknown or not members:
        raise ValueError(f"{d.module}.{name}: unknown or no outputs {unknown}")
    outs = [by_name[m] for m in members]
    used = set().union(*(set(o.args) for o in outs))
    args = [p.symbol for p in d.params if p.symbol in used]
    if len(args) != len(used):
        raise ValueError(f"{d.module}.{name}: arguments not declared as parameters")
    tables = []
    for o in outs:
        matrix = sp.Matrix(o.matrix)
        _check_args(o.name, list(matrix), o.args, d)
        tables.append((o, matrix, _nonzero_entries(matrix)))
    replacements, reduced = _cse([e for _, _, entries in tables for _, _, e in entries])
    texts = iter(printer.doprint(e) for e in reduced)
    rendered = [
        {
            "name": o.name,
            "var": f"_o{k}",
            "nrows": matrix.rows,
            "ncols": matrix.cols,
            "entries": [(i, j, next(texts)) for i, j, _ in entries],
        }
        for k, (o, matrix, entries) in enumerate(tables)
    ]
    return {
        "name": name,
        "signature": ", ".join(a.name for a in args),
        "argnames": repr(tuple(a.name for a in args)),
        "members": repr(tuple(members)),
        "arginfo": _arginfo(args, d),
        "cse": [(str(sym), printer.doprint(e)) for sym, e in replacements],
        "outputs": rendered,
    }


def block_of(d: Derivation) -> dict[str, str]:
    """{output name: the block function that computes it} of the outputs in a block; an
    output in two blocks is an error (its view would be ambiguous)."""
    owner: dict[str, str] = {}
    for name, members in d.blocks.items():
        for m in members:
            if m in owner:
                raise ValueError(f"{d.module}: output {m!r} is in blocks {owner[m]!r} and {name!r}")
            owner[m] = name
    return owner


#: suffix of a derivative function's name: ``ln_blocks`` -> ``ln_blocks_d``
DERIVATIVE_SUFFIX = "_d"


def derivative_groups(d: Derivation) -> list[tuple[str, tuple[str, ...], list[sp.Symbol]]]:
    """(function name, matrices, arguments) of each derivative function of `d`: one per block
    function (its members; its arguments, in parameter order), then one per output in no
    block (its own arguments, in its own order), in the derivation's order."""
    by_name = {o.name: o for o in d.outputs}
    groups = []
    for name, members in d.blocks.items():
        used = set().union(*(set(by_name[m].args) for m in members))
        groups.append((name + DERIVATIVE_SUFFIX, tuple(members),
                       [p.symbol for p in d.params if p.symbol in used]))
    in_block = {m for members in d.blocks.values() for m in members}
    for o in d.outputs:
        if o.name not in in_block:
            groups.append((o.name + DERIVATIVE_SUFFIX, (o.name,), list(o.args)))
    return groups


def derivative_matrices(d: Derivation, members: Sequence[str], args: Sequence[sp.Symbol]):
    """[(matrix name, [(parameter, ∂matrix/∂parameter), ...]), ...]: SymPy's ``diff`` of each
    member with respect to each argument, identically-zero derivatives left out."""
    by_name = {o.name: o for o in d.outputs}
    out = []
    for m in members:
        matrix = sp.Matrix(by_name[m].matrix)
        free = matrix.free_symbols
        parts = []
        for a in args:
            if a in free:
                dm = matrix.diff(a)
                if any(e != 0 for e in dm):
                    parts.append((a, dm))
        out.append((m, parts))
    return out


def _render_derivatives(name: str, members: Sequence[str], args: Sequence[sp.Symbol],
                        d: Derivation, printer: _Printer) -> dict:
    """One derivative function, ``{matrix: {parameter: ∂matrix/∂parameter}}``: one
    ``sympy.cse`` over all nonzero entries of all its derivatives (as in the block
    functions)."""
    by_name = {o.name: o for o in d.outputs}
    tables = []
    for m, parts in derivative_matrices(d, members, args):
        for a, dm in parts:
            _check_args(f"{m}_d/{a.name}", list(dm), args, d)
            tables.append((m, a, dm.shape, _nonzero_entries(dm)))
    replacements, reduced = _cse([e for *_, entries in tables for _, _, e in entries])
    texts = iter(printer.doprint(e) for e in reduced)
    partials = [
        {"matrix": m, "param": a.name, "var": f"_d{k}", "nrows": nr, "ncols": nc,
         "entries": [(i, j, next(texts)) for i, j, _ in entries]}
        for k, (m, a, (nr, nc), entries) in enumerate(tables)
    ]
    returned = []
    for m in members:
        nr, nc = sp.Matrix(by_name[m].matrix).shape
        returned.append({"name": m, "nrows": nr, "ncols": nc,
                         "partials": [p for p in partials if p["matrix"] == m]})
    nonzero = {r["name"]: tuple(p["param"] for p in r["partials"]) for r in returned}
    return {
        "name": name,
        "of": name[: -len(DERIVATIVE_SUFFIX)],
        "is_block": name[: -len(DERIVATIVE_SUFFIX)] in d.blocks,
        "signature": ", ".join(a.name for a in args),
        "argnames": repr(tuple(a.name for a in args)),
        "nonzero": repr(nonzero),
        "arginfo": _arginfo(args, d),
        "cse": [(str(s), printer.doprint(e)) for s, e in replacements],
        "partials": partials,
        "returned": returned,
    }


def render(d: Derivation, env: jinja2.Environment) -> str:
    """The text of `generated/<d.module>.py`: the block functions, one function per matrix
    (a view of its block function, or the matrix's own code if it is in no block), the
    derivative functions."""
    printer = _Printer({"fully_qualified_modules": True})
    owner = block_of(d)
    blocks = [_render_blocks(n, m, d, printer) for n, m in d.blocks.items()]
    functions = [_render_function(o, d, printer, owner.get(o.name)) for o in d.outputs]
    derivatives = [_render_derivatives(n, m, a, d, printer) for n, m, a in derivative_groups(d)]
    doc = (d.doc or "").strip().replace('"""', "'''")
    text = env.get_template("module.py.j2").render(
        d=d, functions=functions, blocks=blocks, derivatives=derivatives, doc=doc,
        views=[f for f in functions if f["block"]],
    )
    return text.rstrip() + "\n"


def environment() -> jinja2.Environment:
    """The jinja2 environment of `templates/` (strict: an undefined name is an error)."""
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(TEMPLATES)),
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )


def generate(out_dir: Path, only: list[str] | None = None, verbose: bool = True) -> dict[str, str]:
    """Write all generated modules to `out_dir`; return {file name: text}."""
    env = environment()
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
