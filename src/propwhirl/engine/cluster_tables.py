"""The index tables of a cluster of k roots: everything about the permutations of its members
that the cluster continuations (:mod:`propwhirl.engine.clusters`) look up instead of computing
per step — which member is which after a step, how two steps' relabellings compose, the
companion matrix's subdiagonal, the derivatives of a monic polynomial in the powers of z.

One function, :func:`cluster_tables`, gives them: built once for the sizes that occur (2–4
roots), read-only, so the acceptance logic of the continuations reads as logic and the tables
are tested on their own (tests/engine/test_clusters_fastpaths.py).

>>> t = cluster_tables(3)
>>> t.perms.shape, t.perms[t.compose[1][1]].tolist()       # the swap of the last two, twice
((6, 3), [0, 1, 2])
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

__all__ = ["ClusterTables", "cluster_tables"]


def frozen(x: np.ndarray) -> np.ndarray:
    """``x``, made read-only (constant tables)."""
    x.flags.writeable = False
    return x


@dataclass(frozen=True)
class ClusterTables:
    """Index tables of a cluster of k roots, built once per k (read-only arrays).

    perms: (k!, k) the permutations of range(k) (in ``itertools.permutations`` order);
    index: the row of each permutation (as a tuple) in ``perms``; compose[i][j]: the row of
    perms[i][perms[j]]; others: (k, k − 1), row m the members other than m; sub: rows and
    columns of the companion matrix's subdiagonal; orders: 1 … k, the orders of the
    coefficients; w1, e1 / w2: factors and exponents of the first / second derivative of a
    monic polynomial of degree k in the powers of z (coefficient order: highest power first;
    the exponents of the second are e1[1:]); gather: (k!, k), the flat indices i·k + perm[i]
    of a k × k matrix picked by each permutation.
    """

    perms: np.ndarray
    index: dict[tuple[int, ...], int]
    compose: tuple[tuple[int, ...], ...]
    others: np.ndarray
    sub: tuple[np.ndarray, np.ndarray]
    orders: np.ndarray
    w1: np.ndarray
    e1: np.ndarray
    w2: np.ndarray
    gather: np.ndarray

    @classmethod
    def build(cls, k: int) -> ClusterTables:
        pw = np.arange(k, -1, -1)
        perms = list(itertools.permutations(range(k)))
        index = {p: i for i, p in enumerate(perms)}
        compose = tuple(tuple(index[tuple(p[j] for j in r)] for r in perms) for p in perms)
        arrays = dict(
            perms=np.array(perms), orders=np.arange(1, k + 1),
            others=np.array([[j for j in range(k) if j != m] for m in range(k)],
                            dtype=int).reshape(k, k - 1),
            w1=pw[:-1, None], e1=np.maximum(pw[:-1, None] - 1, 0),
            w2=(pw[:-2] * (pw[:-2] - 1))[:, None],
            gather=np.arange(k) * k + np.array(perms, dtype=int).reshape(-1, k))
        sub = (frozen(np.arange(1, k)), frozen(np.arange(k - 1)))
        return cls(sub=sub, index=index, compose=compose,
                   **{name: frozen(x) for name, x in arrays.items()})


#: the tables of the cluster sizes that occur (2–4 roots; 1 for completeness)
_TABLES = {k: ClusterTables.build(k) for k in range(1, 5)}


def cluster_tables(k: int) -> ClusterTables:
    """The index tables of a cluster of k roots (built anew only for k > 4)."""
    t = _TABLES.get(k)
    return t if t is not None else ClusterTables.build(k)
