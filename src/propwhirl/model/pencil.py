"""The full-order sparse pencil of one model at any speed, its sparsity pattern built once.

:meth:`propwhirl.model.blocks.BlockSystem.pencil` assembles E ẋ = F x (eq. 5.4, 7.59) from
(row, column, value) triplets: the constant part (:meth:`~BlockSystem.pencil_constant`: the
identities, M, C, K) and the speed-dependent blocks and lag states.  Its conversion to CSC sorts
the triplets and adds the duplicates every time, although their positions do not depend on the
speed.  :class:`SparsePencil` does that once per model (:meth:`SparsePencil.of`): it keeps the
union of the positions as a CSC pattern, where each triplet lands, and the constant values;
:meth:`SparsePencil.at` then only gathers a speed's values and adds the duplicates.

The matrices are those of :meth:`BlockSystem.pencil` to the last bit (same indices, same data):
SciPy's COO → CSC conversion places each column's entries in the order given (a stable
counting sort), sorts each column's rows — an insertion sort, which keeps equal rows in the
order given, for columns of at most :data:`STABLE_COLUMN` entries (libstdc++'s ``std::sort``)
— and adds each position's entries in that order, leaving out zero values before; here the
entries of each position are added in the order given (a zero added changes no sum) and a
position whose entries are all zero is left out.  A model with a longer column (more than
:data:`STABLE_COLUMN` entries: not one of the examples') is assembled by
:meth:`BlockSystem.pencil` itself.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from propwhirl.model.blocks import BlockSystem

#: the longest column whose entries SciPy's index sort keeps in their given order (an insertion
#: sort: libstdc++'s std::sort on ranges of at most 16 elements)
STABLE_COLUMN = 16


@dataclass(frozen=True, eq=False)
class _Pattern:
    """One matrix of the pencil: the CSC pattern (indptr, indices; ``column`` of each stored
    position) of every position an entry can take, ``order`` the triplets (in their given
    order, removed states left out) sorted by position, ``slot`` the stored position of each
    sorted triplet, ``first`` the sorted triplet starting each position, and ``more`` the
    (positions, sorted triplets) of each position's second, third, ... triplet."""

    indptr: np.ndarray
    indices: np.ndarray
    column: np.ndarray
    order: np.ndarray
    slot: np.ndarray
    first: np.ndarray
    more: tuple[tuple[np.ndarray, np.ndarray], ...]
    longest_column: int

    @classmethod
    def of(cls, rows: list[np.ndarray], cols: list[np.ndarray], size: int) -> "_Pattern":
        r, c = (np.concatenate([np.ravel(x) for x in xs]) for xs in (rows, cols))
        given = np.flatnonzero((r >= 0) & (c >= 0))
        order = given[np.lexsort((r[given], c[given]))]          # stable: the given order kept
        rs, cs = r[order], c[order]
        start = np.ones(order.size, dtype=bool)
        start[1:] = (rs[1:] != rs[:-1]) | (cs[1:] != cs[:-1])
        slot = np.cumsum(start) - 1
        first = np.flatnonzero(start)
        rank = np.arange(order.size) - first[slot]
        more = tuple((slot[rank == k], np.flatnonzero(rank == k))
                     for k in range(1, int(rank.max(initial=0)) + 1))
        column = cs[first]
        indptr = np.zeros(size + 1, dtype=np.int32)
        indptr[1:] = np.cumsum(np.bincount(column, minlength=size))
        per_column = np.bincount(cs, minlength=size)
        return cls(indptr, rs[first].astype(np.int32), column, order, slot, first, more,
                   int(per_column.max(initial=0)))

    def matrix(self, values: np.ndarray, size: int) -> sp.csc_matrix:
        """The CSC matrix of the triplets' ``values`` (in their given order)."""
        v = values[self.order]
        data = v[self.first]
        for slots, at in self.more:
            data[slots] += v[at]
        held = np.zeros(data.size, dtype=bool)
        held[self.slot[v != 0]] = True
        if held.all():
            return sp.csc_matrix((data, self.indices, self.indptr), shape=(size, size))
        indptr = np.zeros(size + 1, dtype=np.int32)
        indptr[1:] = np.cumsum(np.bincount(self.column[held], minlength=size))
        return sp.csc_matrix((data[held], self.indices[held], indptr), shape=(size, size))


@dataclass(frozen=True, eq=False)
class SparsePencil:
    """The speed-independent part of the full-order pencil (F, E) of one model (module
    docstring): its size, the pattern of each matrix and the constant values.  Built once
    (:meth:`of`, from the model's blocks at any speed) and evaluated at a speed of any
    :class:`~propwhirl.model.blocks.BlockSystem` of the same model (:meth:`at`).

    ``stable``: whether every column is short enough for the pattern to give
    :meth:`BlockSystem.pencil`'s matrices (else :meth:`at` calls it, with the constant part).
    """

    size: int
    F: _Pattern
    E: _Pattern
    F_constant: np.ndarray
    E_constant: np.ndarray
    constant: tuple
    stable: bool

    @classmethod
    def of(cls, blocks: BlockSystem) -> "SparsePencil":
        """The pencil pattern of the model of ``blocks`` (its positions do not depend on the
        speed; the constant part, :meth:`BlockSystem.pencil_constant`, is that of every
        speed)."""
        size = 2 * blocks.keep_q.size + blocks.keep_w.size
        constant = blocks.pencil_constant()
        patterns, values = [], []
        for const, where in zip(constant, blocks.pencil_indices()):
            patterns.append(_Pattern.of(const.r + [r for r, _ in where],
                                        const.c + [c for _, c in where], size))
            values.append(np.concatenate([np.ravel(x) for x in const.v]))
        F, E = patterns
        return cls(size, F, E, values[0], values[1], constant,
                   max(F.longest_column, E.longest_column) <= STABLE_COLUMN)

    def at(self, blocks: BlockSystem, t: int = 0) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        """(F, E) at the speed index ``t`` of ``blocks`` (a BlockSystem of this model):
        :meth:`BlockSystem.pencil`'s matrices."""
        if not self.stable:
            return blocks.pencil(t, self.constant)
        F, E = blocks.pencil_values(t)
        return (self.F.matrix(np.concatenate([self.F_constant] + [np.ravel(x) for x in F]),
                              self.size),
                self.E.matrix(np.concatenate([self.E_constant] + [np.ravel(x) for x in E]),
                              self.size))
