"""Shared symbolic machinery: Lagrange's equations (thesis eq. 5.1), linearisation, Jacobians.

Every derivation module builds a :class:`Derivation` — the matrices of one model as SymPy
expressions of named parameters — from energies (T, U, D) and the virtual work of the loads:

    d/dt(dT/dq̇_i) - dT/dq_i + dU/dq_i + dD/dq̇_i = Q_i          (5.1)

linearised about q = q̇ = q̈ = 0, so that the left side is M q̈ + C q̇ + K q and the right side
(the loads, from δW = Σ Q_i δq_i) is M_a q̈ + C_a q̇ + K_a q.  The matrices are Jacobians of
these expressions with respect to q̈, q̇ and q.

The generator (`derivations/generate.py`) turns each entry of :attr:`Derivation.blocks` into
one vectorised NumPy function in `generated/` that returns several outputs computed with one
shared common-subexpression elimination, and each :class:`Output` into a function of its own
name: a view of its block function, or its own code if it is in no block.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import sympy as sp

t = sp.Symbol("t", real=True)


@dataclass(frozen=True)
class Param:
    """A model parameter: the SymPy symbol, its meaning and SI unit."""

    symbol: sp.Symbol
    doc: str
    unit: str


@dataclass
class Output:
    """One generated function: a matrix (or vector) of expressions in `args`.

    `rows`/`cols` label the matrix (degrees of freedom); `equations` names the thesis
    equations this matrix reproduces.
    """

    name: str
    matrix: sp.Matrix
    args: Sequence[sp.Symbol]
    doc: str
    equations: str
    rows: Sequence[str] = ()
    cols: Sequence[str] = ()


@dataclass
class Derivation:
    """Everything one derivation module produces for the generator."""

    module: str
    title: str
    source: str
    equations: str
    doc: str
    params: Sequence[Param]
    outputs: list[Output] = field(default_factory=list)
    #: shared-CSE block functions: function name -> names of the outputs it returns together
    #: (one ``sympy.cse`` over all of them; the runtime assembles from these); an output is
    #: in one block at most
    blocks: dict[str, Sequence[str]] = field(default_factory=dict)

    def param(self, name: str) -> Param:
        for p in self.params:
            if p.symbol.name == name:
                return p
        raise KeyError(name)


def coordinates(names: Sequence[str]) -> list[sp.Function]:
    """Generalised coordinates q_i(t) with the given (Python-identifier) names."""
    return [sp.Function(n, real=True)(t) for n in names]


def lagrange_lhs(T: sp.Expr, U: sp.Expr, D: sp.Expr, q: Sequence[sp.Expr]) -> list[sp.Expr]:
    """Left side of Lagrange's equations (5.1) for each coordinate in `q`."""
    lhs = []
    for qi in q:
        qd = sp.diff(qi, t)
        lhs.append(
            sp.diff(sp.diff(T, qd), t) - sp.diff(T, qi) + sp.diff(U, qi) + sp.diff(D, qd)
        )
    return lhs


def generalised_forces(dW: sp.Expr, dq: Sequence[sp.Symbol]) -> list[sp.Expr]:
    """Q_i from the virtual work δW = Σ Q_i δq_i (δW linear in the virtual displacements)."""
    forces = []
    for d in dq:
        Qi = sp.diff(dW, d)
        if sp.diff(Qi, d) != 0:
            raise ValueError("virtual work must be linear in the virtual displacements")
        forces.append(sp.expand(Qi))
    return forces


def second_order_matrices(exprs: Sequence[sp.Expr], q: Sequence[sp.Expr]):
    """(M, C, K) with exprs = M q̈ + C q̇ + K q, linearised about the zero state.

    Each matrix is the Jacobian of `exprs` with respect to q̈, q̇, q, evaluated at
    q = q̇ = q̈ = 0.  A non-linear remainder is not an error here (the energies are already
    second order), but any term that survives with all coordinates at zero is: a linear
    system about equilibrium has no constant term.
    """
    qd = [sp.diff(x, t) for x in q]
    qdd = [sp.diff(x, t, 2) for x in q]
    # Replace derivatives by plain symbols (highest order first) so Jacobians are ordinary.
    a = sp.symbols(f"_a0:{len(q)}")
    v = sp.symbols(f"_v0:{len(q)}")
    x = sp.symbols(f"_x0:{len(q)}")
    subs = list(zip(qdd, a)) + list(zip(qd, v)) + list(zip(q, x))
    plain = sp.Matrix([sp.expand(e.subs(subs)) for e in exprs])
    zero = {s: 0 for s in (*a, *v, *x)}
    if any(sp.simplify(e.subs(zero)) != 0 for e in plain):
        raise ValueError("equations have a constant term: not about an equilibrium")
    mats = []
    for syms in (a, v, x):
        J = plain.jacobian(syms).subs(zero)
        mats.append(J.applyfunc(sp.expand))
    return tuple(mats)


def hessian_matrix(energy: sp.Expr, variables: Sequence[sp.Symbol]) -> sp.Matrix:
    """Symmetric matrix of a quadratic form: energy = ½ vᵀ H v."""
    return sp.hessian(sp.expand(energy), variables).applyfunc(sp.expand)
