"""Render every derivation into a plain NumPy module in `generated/` (run by `make generate`).

    python -m derivations.generate --out generated

Each module in `derivations/` that defines ``derive()`` becomes `generated/<module>.py`:
common subexpressions are eliminated (``sympy.cse``) and the expressions printed with SymPy's
NumPy printer, through the jinja2 template `templates/module.py.j2`.  Two forms of code:

- one function per matrix (``Derivation.outputs``), each with its own ``sympy.cse`` — the
  documented API, checked by the oracle tests against the thesis's printed matrices;
- one *block function* per entry of ``Derivation.blocks``, returning the matrices the assembly
  uses together (a dict) after broadcasting the arguments once.  Its subexpressions are
  ``--block-cse merged`` (default): each matrix's own ``sympy.cse``, identical subexpressions
  computed once, so the results are bit-identical to the per-matrix functions; or ``shared``:
  one ``sympy.cse`` over all the matrices (PyDy's way; last-bit differences).  The
  measurement behind the choice: benchmarks/generator_cse.py, docs/performance.md.

- one *derivative function* ``<name>_d`` per block function (and per matrix in no block):
  ``{matrix name: {parameter: ∂matrix/∂parameter}}`` for every argument, identically-zero
  derivatives left out, one ``sympy.cse`` over all of them.  The derivatives are SymPy's
  ``diff`` of the very matrices the other forms print; the runtime builds ∂A/∂p from them by
  the same assembly as A (`src/propwhirl/model/derivatives.py`).

The output is
deterministic (sorted discovery, fixed entry order, pinned SymPy), so running the generator
twice gives byte-identical files; tests/generated/test_freshness.py holds `generated/` to that.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import re
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


def _render_function(out: Output, d: Derivation, printer: _Printer) -> dict:
    """One function per matrix, with its own ``sympy.cse``."""
    matrix = sp.Matrix(out.matrix)
    args = list(out.args)
    _check_args(out.name, list(matrix), args, d)
    entries = _nonzero_entries(matrix)
    replacements, reduced = _cse([e for _, _, e in entries])
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
        "cse": [(str(s), printer.doprint(e)) for s, e in replacements],
        "entries": [(i, j, printer.doprint(e)) for (i, j, _), e in zip(entries, reduced)],
    }


def _render_blocks(
    name: str, members: Sequence[str], d: Derivation, printer: _Printer, cse: str = "shared"
) -> dict:
    """One function returning several outputs, broadcasting its arguments once.

    Its arguments are the union of the members' arguments, in the derivation's parameter
    order; every returned array has the full broadcast shape.  `cse` chooses the common
    subexpressions:

    - ``"shared"``: one ``sympy.cse`` over all entries of all members (as PyDy's codegen);
    - ``"merged"``: each member's own ``sympy.cse`` (exactly the per-matrix function's code),
      the subexpressions renamed apart and identical ones computed once.  Every entry is then
      evaluated by the same floating-point operations as in the per-matrix function, so the
      results are bit-identical to it.
    """
    if cse not in BLOCK_CSE:
        raise ValueError(f"cse = {cse!r} is invalid: must be one of {BLOCK_CSE}")
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
    if cse == "shared":
        replacements, reduced = _cse([e for _, _, entries in tables for _, _, e in entries])
        lines = [(str(sym), printer.doprint(e)) for sym, e in replacements]
        texts = iter(printer.doprint(e) for e in reduced)
        entry_texts = [[next(texts) for _ in entries] for _, _, entries in tables]
    else:
        lines, entry_texts = _merge_cse(tables, printer)
    rendered = [
        {
            "name": o.name,
            "var": f"_o{k}",
            "nrows": matrix.rows,
            "ncols": matrix.cols,
            "entries": [(i, j, text) for (i, j, _), text in zip(entries, entry_texts[k])],
        }
        for k, (o, matrix, entries) in enumerate(tables)
    ]
    return {
        "name": name,
        "signature": ", ".join(a.name for a in args),
        "argnames": repr(tuple(a.name for a in args)),
        "members": repr(tuple(members)),
        "arginfo": _arginfo(args, d),
        "cse": lines,
        "outputs": rendered,
    }


_CSE_NAME = re.compile(r"\b_c(\d+)\b")


def _merge_cse(tables, printer: _Printer) -> tuple[list[tuple[str, str]], list[list[str]]]:
    """Each member's own ``sympy.cse``, printed as in its per-matrix function, with the
    subexpression names renumbered apart; a subexpression whose text (after renaming) is
    already defined reuses that definition."""
    lines: list[tuple[str, str]] = []
    defined: dict[str, str] = {}  # text -> merged name
    entry_texts = []
    for _, _, entries in tables:
        replacements, reduced = _cse([e for _, _, e in entries])
        local: dict[str, str] = {}  # this member's name -> merged name

        def rename(text: str) -> str:
            return _CSE_NAME.sub(lambda m: local[f"_c{m.group(1)}"], text)

        for sym, e in replacements:
            text = rename(printer.doprint(e))
            if text not in defined:
                defined[text] = f"_c{len(lines)}"
                lines.append((defined[text], text))
            local[str(sym)] = defined[text]
        entry_texts.append([rename(printer.doprint(e)) for e in reduced])
    return lines, entry_texts


#: how a block function eliminates common subexpressions (see `_render_blocks`)
BLOCK_CSE = ("shared", "merged")
CSE_NOTES = {
    "shared": "Their code is one common-subexpression\nelimination over all the matrices: "
              "the results equal the per-matrix functions' to rounding.",
    "merged": "Their code is each matrix's own common\nsubexpressions, identical ones computed "
              "once: the results are bit-identical to the per-matrix\nfunctions.",
}


#: the forms of generated code: one function per matrix, shared-CSE block functions, and the
#: parameter derivatives of the block functions (and of the matrices in no block)
FORMS = ("matrices", "blocks", "derivatives")

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
    ``sympy.cse`` over all nonzero entries of all its derivatives (the "shared" form of the
    block functions; no other function computes these, so there is nothing to be
    bit-identical to)."""
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


def render(
    d: Derivation,
    env: jinja2.Environment,
    forms: Sequence[str] = FORMS,
    block_cse: str = "merged",
) -> str:
    """The text of `generated/<d.module>.py` with the requested forms of generated code."""
    if not set(forms) <= set(FORMS):
        raise ValueError(f"forms = {forms!r} is invalid: must be a subset of {FORMS}")
    printer = _Printer({"fully_qualified_modules": True})
    functions = [_render_function(o, d, printer) for o in d.outputs] if "matrices" in forms else []
    blocks = (
        [_render_blocks(n, m, d, printer, block_cse) for n, m in d.blocks.items()] if "blocks" in forms else []
    )
    doc = (d.doc or "").strip().replace('"""', "'''")
    derivatives = (
        [_render_derivatives(n, m, a, d, printer) for n, m, a in derivative_groups(d)]
        if "derivatives" in forms else []
    )
    text = env.get_template("module.py.j2").render(
        d=d, functions=functions, blocks=blocks, derivatives=derivatives, doc=doc,
        cse_note=CSE_NOTES[block_cse]
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


def generate(
    out_dir: Path,
    only: list[str] | None = None,
    verbose: bool = True,
    forms: Sequence[str] = FORMS,
    block_cse: str = "merged",
) -> dict[str, str]:
    """Write all generated modules to `out_dir`; return {file name: text}.

    `forms` selects the generated code (default both; the benchmark
    `benchmarks/generator_cse.py` renders each form alone to compare them).
    """
    env = environment()
    out_dir.mkdir(parents=True, exist_ok=True)
    written: dict[str, str] = {}
    derivs = []
    for name in discover():
        if only and name not in only:
            continue
        start = time.perf_counter()
        d = importlib.import_module(f"derivations.{name}").derive()
        text = render(d, env, forms, block_cse)
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
    parser.add_argument(
        "--block-cse", choices=BLOCK_CSE, default="merged",
        help="common subexpressions of the block functions (default merged: bit-identical to "
        "the per-matrix functions; see docs/performance.md)",
    )
    args = parser.parse_args(argv)
    start = time.perf_counter()
    generate(args.out, args.only, block_cse=args.block_cse)
    print(f"total {time.perf_counter() - start:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
