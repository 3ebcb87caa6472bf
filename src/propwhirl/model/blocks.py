"""The second-order system as a sum of local blocks: dense, sparse and projected forms.

A wing model's matrices (eq. 7.59, D.18–D.29) are a constant structural part plus local,
speed-dependent blocks: the strip aerodynamics of each node on its [h, α] (7.24–7.80), each
propeller's 4×4 (or 2×2) block on [θ, ψ, h_P, α_P] (8.1–8.42), and each node's lag states.
:class:`BlockSystem` keeps them as blocks, so that

* :meth:`BlockSystem.dense` is the dense :class:`~propwhirl.model.statespace.SecondOrder`
  (the one assembly of :class:`~propwhirl.model.systems.PropellerWing`; blocks added in a fixed
  order, so the dense matrices do not depend on which form was asked for first);
* :meth:`BlockSystem.pencil` is the sparse first-order pencil E ẋ = F x of one speed
  (E = diag(I, S1, I), F = [[0, I, 0], [−S3, −S2, S4], [Wq, Wv, Ww]]: the full-order model
  for sparse shift-invert solves, memory and time linear in the number of elements);
* :meth:`BlockSystem.project` is the Galerkin projection Φᵀ S Φ (and the lag states on a
  basis Q) evaluated block by block — linear in the number of elements, never forming a dense
  full-size matrix (:mod:`propwhirl.model.reduction`).

All indices are *full* (clamped root included); ``keep_q`` and ``keep_w`` say which degrees of
freedom and lag states remain (root removed, 7.59).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from propwhirl import validate as v
from propwhirl.model.statespace import SecondOrder


@dataclass(frozen=True)
class LocalBlocks:
    """Blocks added to S1, S2, S3 at global DOFs ``dofs`` (nb, k); values (nV, nb, k, k).

    The DOFs of different blocks of one group do not overlap (one block per node or per
    propeller), so a group is added with one fancy-indexed ``+=``."""

    name: str
    dofs: np.ndarray
    S1: np.ndarray
    S2: np.ndarray
    S3: np.ndarray


@dataclass(frozen=True)
class LagBlocks:
    """The lag states of each node: S4 (nV, nb, kq, kw) at (qrows, wrows), Ww (nV, nb, kw, kw),
    Wv and Wq (nV, nb, kw, kq); qrows (nb, kq) and wrows (nb, kw) are full indices."""

    qrows: np.ndarray
    wrows: np.ndarray
    S4: np.ndarray
    Ww: np.ndarray
    Wv: np.ndarray
    Wq: np.ndarray


@dataclass(frozen=True)
class BlockSystem:
    """S1 q̈ + S2 q̇ + S3 q = S4 w, ẇ = Ww w + Wv q̇ + Wq q as constant matrices plus blocks.

    M, C, K: constant (n_q, n_q) structural parts (dense, V-independent); blocks: groups of
    :class:`LocalBlocks` added in order (aerodynamic blocks carry their sign, S1 = M − M_a + …);
    lag: the :class:`LagBlocks` or None; n_w: number of lag states (full); labels and
    keep_q/keep_w: full labels and the kept indices.
    """

    V: np.ndarray
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    blocks: tuple[LocalBlocks, ...]
    lag: LagBlocks | None
    n_w: int
    q_labels: tuple[str, ...]
    w_labels: tuple[str, ...]
    keep_q: np.ndarray
    keep_w: np.ndarray

    def __post_init__(self) -> None:
        if len(self.q_labels) != self.M.shape[0]:
            # an assembly that does not know the model's DOF layout must not give matrices on
            # the wrong DOFs
            raise v.InputError(
                f"q_labels has {len(self.q_labels)} labels but the matrices have "
                f"{self.M.shape[0]} DOFs: this assembly does not cover the model's degrees of "
                "freedom")

    @property
    def n_q(self) -> int:
        return self.M.shape[0]

    # ------------------------------------------------------------------ dense
    def dense(self) -> SecondOrder:
        """The dense second-order system over the kept DOFs and lag states (all speeds)."""
        nV, n, m = self.V.shape[0], self.n_q, self.n_w
        S = [np.empty((nV, n, n)) for _ in range(3)]
        for Si, X in zip(S, (self.M, self.C, self.K)):
            Si[:] = X
        for b in self.blocks:
            r, c = b.dofs[:, :, None], b.dofs[:, None, :]
            for Si, Bi in zip(S, (b.S1, b.S2, b.S3)):
                Si[:, r, c] += Bi
        S4 = np.zeros((nV, n, m))
        Ww, Wv, Wq = np.zeros((nV, m, m)), np.zeros((nV, m, n)), np.zeros((nV, m, n))
        lg = self.lag
        if lg is not None:
            qr, wr = lg.qrows, lg.wrows
            S4[:, qr[:, :, None], wr[:, None, :]] = lg.S4
            Ww[:, wr[:, :, None], wr[:, None, :]] = lg.Ww
            Wv[:, wr[:, :, None], qr[:, None, :]] = lg.Wv
            Wq[:, wr[:, :, None], qr[:, None, :]] = lg.Wq
        full = SecondOrder(S[0], S[1], S[2], S4, Ww, Wv, Wq, self.q_labels, self.w_labels)
        return full.reduced(self.keep_q, self.keep_w)

    def matrix(self, name: str = "S1") -> np.ndarray:
        """One of S1, S2, S3 alone over the kept DOFs (nV, n, n): :meth:`dense`'s, without the
        other six (for a large wing each is n² · 8 bytes per speed)."""
        k = ("S1", "S2", "S3").index(name)
        S = np.empty((self.V.shape[0], self.n_q, self.n_q))
        S[:] = (self.M, self.C, self.K)[k]
        for b in self.blocks:
            S[:, b.dofs[:, :, None], b.dofs[:, None, :]] += (b.S1, b.S2, b.S3)[k]
        kq = self.keep_q
        return S[:, kq[:, None], kq[None, :]]

    def take(self, t: np.ndarray) -> "BlockSystem":
        """The system at the speed indices ``t`` (an integer array into :attr:`V`)."""
        t = np.asarray(t, dtype=int)
        blocks = tuple(replace(b, S1=b.S1[t], S2=b.S2[t], S3=b.S3[t]) for b in self.blocks)
        lg = self.lag
        lag = None if lg is None else replace(lg, S4=lg.S4[t], Ww=lg.Ww[t], Wv=lg.Wv[t],
                                               Wq=lg.Wq[t])
        return replace(self, V=self.V[t], blocks=blocks, lag=lag)

    def speed_arrays(self) -> list[np.ndarray]:
        """Every array of the system with a leading speed axis."""
        out = [self.V] + [x for b in self.blocks for x in (b.S1, b.S2, b.S3)]
        lg = self.lag
        return out if lg is None else out + [lg.S4, lg.Ww, lg.Wv, lg.Wq]

    # ------------------------------------------------------------------ sparse pencil
    def _positions(self) -> tuple[int, int, np.ndarray, np.ndarray]:
        """n, m and the pencil position of every full DOF and lag state (removed: negative)."""
        n, m = self.keep_q.size, self.keep_w.size
        gone = -(1 << 40)                    # removed states stay negative after any offset
        qpos = np.full(self.n_q, gone)
        qpos[self.keep_q] = np.arange(n)
        wpos = np.full(self.n_w, gone)
        wpos[self.keep_w] = 2 * n + np.arange(m)
        return n, m, qpos, wpos

    def pencil_constant(self) -> tuple["_Triplets", "_Triplets"]:
        """The speed-independent part of :meth:`pencil` (the identities and the constant
        M, C, K) as (F, E) triplet lists: computed once, reused for every speed of a model with
        the same constant parts (``pencil(t, constant=...)``)."""
        n, m, qpos, _ = self._positions()
        F, E = _Triplets(), _Triplets()
        k = np.arange(n)
        E.add(k, k, np.ones(n))
        E.add(2 * n + np.arange(m), 2 * n + np.arange(m), np.ones(m))
        F.add(k, n + k, np.ones(n))
        for X, dst, sign, off in ((self.M, E, 1.0, n), (self.C, F, -1.0, n),
                                  (self.K, F, -1.0, 0)):
            r, c = np.nonzero(X)
            dst.add(n + qpos[r], off + qpos[c], sign * X[r, c])
        return F, E

    def pencil_indices(self) -> tuple[list[tuple[np.ndarray, np.ndarray]],
                                      list[tuple[np.ndarray, np.ndarray]]]:
        """(F, E): the (row, column) pencil positions of the speed-dependent entries of
        :meth:`pencil` (the blocks and the lag states; a removed state's negative), one pair
        per array of :meth:`pencil_values`, in the same order.  Speed-independent."""
        n, m, qpos, wpos = self._positions()
        F, E = [], []
        for b in self.blocks:
            rr = n + qpos[np.broadcast_to(b.dofs[:, :, None], b.S1.shape[1:])]
            cc = qpos[np.broadcast_to(b.dofs[:, None, :], b.S1.shape[1:])]
            E.append((rr, n + cc))
            F += [(rr, n + cc), (rr, cc)]
        lg = self.lag
        if lg is not None:
            qr, wr = lg.qrows, lg.wrows
            F.append((n + qpos[np.broadcast_to(qr[:, :, None], lg.S4.shape[1:])],
                      wpos[np.broadcast_to(wr[:, None, :], lg.S4.shape[1:])]))
            F.append((wpos[np.broadcast_to(wr[:, :, None], lg.Ww.shape[1:])],
                      wpos[np.broadcast_to(wr[:, None, :], lg.Ww.shape[1:])]))
            for W, off in ((lg.Wv, n), (lg.Wq, 0)):
                F.append((wpos[np.broadcast_to(wr[:, :, None], W.shape[1:])],
                          off + qpos[np.broadcast_to(qr[:, None, :], W.shape[1:])]))
        return F, E

    def pencil_values(self, t: int = 0) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """(F, E): the values of the speed-dependent entries of :meth:`pencil` at speed index
        ``t``, at the positions of :meth:`pencil_indices` (F: −S2, −S3 of each block, then
        the lag S4, Ww, Wv, Wq; E: S1 of each block)."""
        F = [x for b in self.blocks for x in (-b.S2[t], -b.S3[t])]
        E = [b.S1[t] for b in self.blocks]
        lg = self.lag
        if lg is not None:
            F += [lg.S4[t], lg.Ww[t], lg.Wv[t], lg.Wq[t]]
        return F, E

    def pencil(self, t: int = 0, constant: tuple["_Triplets", "_Triplets"] | None = None
               ) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        """(F, E) of the first-order form E ẋ = F x, x = [q, q̇, w], at speed index ``t``.

        E = diag(I, S1, I), F = [[0, I, 0], [−S3, −S2, S4], [Wq, Wv, Ww]] over the kept states:
        the eigenvalues of the pencil are those of A = E⁻¹F (eq. 5.4, 7.59), without forming the
        dense S1⁻¹.  Sparse (CSC), assembled from one list of (row, column, value) triplets per
        matrix (:meth:`pencil_constant`, then :meth:`pencil_indices` with
        :meth:`pencil_values`): memory and assembly linear in the number of elements.
        ``constant``: the :meth:`pencil_constant` of a system with the same constant parts, if
        already known (:class:`~propwhirl.model.pencil.SparsePencil` also keeps the sparsity
        pattern)."""
        F, E = (x.copy() for x in (constant or self.pencil_constant()))
        for X, where, values in zip((F, E), self.pencil_indices(), self.pencil_values(t)):
            for (r, c), x in zip(where, values):
                X.add(r, c, x)
        size = 2 * self.keep_q.size + self.keep_w.size
        return F.matrix(size), E.matrix(size)

    # ------------------------------------------------------------------ projection
    def project(self, Phi: np.ndarray, Q: np.ndarray | None,
                const: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
                ) -> tuple[np.ndarray, ...]:
        """Galerkin projection on q = Φ η, w = Q z, block by block (all speeds).

        Phi: (n_q, r) over the full DOFs (zero rows at removed ones); Q: (n_w, L) over the full
        lag states (zero rows at removed ones), orthonormal columns, or None without lag states.
        const: Φᵀ M Φ, Φᵀ C Φ, Φᵀ K Φ if already known (they do not depend on V).
        Returns (S1, S2, S3, S4, Ww, Wv, Wq) of the reduced system, leading speed axis.
        """
        nV, r = self.V.shape[0], Phi.shape[1]
        if const is None:
            const = tuple(Phi.T @ X @ Phi for X in (self.M, self.C, self.K))
        S = [np.broadcast_to(c, (nV, r, r)).copy() for c in const]
        for b in self.blocks:
            P = Phi[b.dofs]                                   # (nb, k, r)
            for Si, Bi in zip(S, (b.S1, b.S2, b.S3)):
                Si += _sandwich(P, Bi, P)
        lg = self.lag
        if lg is None or Q is None:
            L = 0 if Q is None else Q.shape[1]
            z = np.zeros((nV, L, r))
            return (*S, np.zeros((nV, r, L)), np.zeros((nV, L, L)), z, z.copy())
        P, G = Phi[lg.qrows], Q[lg.wrows]                      # (nb, kq, r), (nb, kw, L)
        S4 = _sandwich(P, lg.S4, G)
        Ww = _sandwich(G, lg.Ww, G)
        Wv = _sandwich(G, lg.Wv, P)
        Wq = _sandwich(G, lg.Wq, P)
        return (*S, S4, Ww, Wv, Wq)


class RecentBlocks:
    """The last few :class:`BlockSystem` evaluations of one evaluator (an assembly of one
    model: everything but the airspeeds fixed), for speeds asked for again.

    An explicit store, owned by a per-analysis object and passed where it is needed (the
    :class:`~propwhirl.model.reduction.ReducedModel` of one analysis holds one), never a
    model's: a reduced analysis evaluates some speeds twice (the full-order correction of a
    crossing at the speed its reduced refinement evaluated, the shape of a branch point at a
    speed of its bracket).  Keyed on the speeds only, so its owner must use it for one
    evaluator's own rotational speeds (no Ω override).  A request whose speeds all lie in one
    kept evaluation is answered from it (:meth:`BlockSystem.take`: the same values — the
    blocks are elementwise in V); others are evaluated and kept.  At most ``max_batches``
    evaluations of at most ``max_speeds`` speeds in all are kept (the oldest dropped first),
    their arrays read-only.
    """

    def __init__(self, max_batches: int = 8, max_speeds: int = 64) -> None:
        self.max_batches, self.max_speeds = max_batches, max_speeds
        self._kept: list[tuple[dict[float, int], BlockSystem]] = []

    def get(self, V: np.ndarray) -> BlockSystem | None:
        """The blocks at the speeds V [m/s] from one kept evaluation, or None."""
        speeds = V.tolist()
        for index, b in self._kept:
            t = [index.get(x) for x in speeds]
            if None not in t:
                return b if t == list(range(b.V.size)) else b.take(np.array(t))
        return None

    def add(self, b: BlockSystem) -> BlockSystem:
        """Keep ``b`` (if small enough) and return it."""
        if b.V.size > self.max_speeds:
            return b
        for x in b.speed_arrays():
            x.flags.writeable = False
        self._kept.insert(0, ({x: i for i, x in enumerate(b.V.tolist())}, b))
        total = 0
        for k, (_, kept) in enumerate(self._kept):
            total += kept.V.size
            if k >= self.max_batches or total > self.max_speeds:
                del self._kept[k:]
                break
        return b


def _sandwich(P: np.ndarray, B: np.ndarray, R: np.ndarray) -> np.ndarray:
    """Σ_b P_bᵀ B[v, b] R_b for blocks P (nb, k, r), B (nV, nb, k, l), R (nb, l, s):
    (nV, r, s), by two batched matrix products (BLAS; linear in nb)."""
    T = B @ R                                                  # (nV, nb, k, s)
    nV, nb, k, s = T.shape
    return P.reshape(nb * k, -1).T @ T.reshape(nV, nb * k, s)


class _Triplets:
    """(row, column, value) lists of a sparse matrix; entries with a negative index (a removed
    state) are left out; duplicates add up (COO → CSC)."""

    def __init__(self) -> None:
        self.r: list[np.ndarray] = []
        self.c: list[np.ndarray] = []
        self.v: list[np.ndarray] = []

    def add(self, r, c, v) -> None:
        r, c, v = (np.asarray(x).ravel() for x in (r, c, v))
        self.r.append(r)
        self.c.append(c)
        self.v.append(v)

    def copy(self) -> "_Triplets":
        """A new list holding the same entries (the arrays themselves are shared, not
        modified by either)."""
        out = _Triplets()
        out.r, out.c, out.v = list(self.r), list(self.c), list(self.v)
        return out

    def matrix(self, size: int) -> sp.csc_matrix:
        r, c, v = (np.concatenate(x) for x in (self.r, self.c, self.v))
        ok = (r >= 0) & (c >= 0) & (v != 0)
        return sp.csc_matrix((v[ok], (r[ok], c[ok])), shape=(size, size))
