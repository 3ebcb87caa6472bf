"""What every model shares: A(V) from its second-order matrices by the one builder, errors
that name the model parameter behind a bad entry, state labels from the DOF map."""
from __future__ import annotations

import numpy as np

from propwhirl import validate as v
from propwhirl.model.assembly import blame_entry
from propwhirl.model.statespace import SecondOrder, StateMatrixError, check_system, state_matrix


class StateSpaceModel:
    """What every model shares (the :class:`~propwhirl.model.protocol.Model` contract): A(V)
    from its second-order matrices by the one builder, and its state labels from its DOF map.

    Subclasses define ``second_order(V, ...)``, ``dof_map()`` and ``without_aerodynamics()``.
    """

    def state_matrix(self, V, **options) -> np.ndarray:
        """A(V), shape (nV, n_state, n_state), of the state [q, q̇, w] (eq. 5.3, 6.18, 7.59,
        D.27), by :func:`propwhirl.model.statespace.state_matrix`.  V [m/s], array; `options`
        go to ``second_order`` (e.g. ``omega`` of a PropellerWing)."""
        V = np.atleast_1d(np.asarray(V, dtype=float))
        sys = self.second_order(V, **options)          # finiteness checked there (_checked)
        try:
            return state_matrix(sys, V, finite_checked=True)
        except StateMatrixError as err:
            raise self._explained(err, V, options) from None

    def _checked(self, sys: SecondOrder, V: np.ndarray, options: dict) -> SecondOrder:
        """`sys` after :func:`~propwhirl.model.statespace.check_system` (every entry finite),
        a failure explained by :meth:`_explained`."""
        try:
            check_system(sys, V)
        except StateMatrixError as err:
            raise self._explained(err, V, options) from None
        return sys

    def _explained(self, err: StateMatrixError, V: np.ndarray, options: dict) -> v.InputError:
        """The error prefixed with the model parameter behind the offending entry, if found
        (:meth:`_contributions` and :func:`propwhirl.model.assembly.blame_entry`)."""
        t = min(err.index, V.size - 1)
        omega = options.get("omega")
        om = None if omega is None else np.broadcast_to(np.asarray(omega, float), V.shape)[t:t + 1]
        with np.errstate(all="ignore"):
            cause = blame_entry(self._contributions(V[t:t + 1], om), err)
        return v.InputError(cause or str(err))

    def _contributions(self, V: np.ndarray, omega):
        """(label, global DOF labels, evaluate(values) -> (M, C, K), values, units) of each
        block of the model (none by default: the error keeps naming the entry's states)."""
        return []

    def release_caches(self) -> None:
        """Free what the model memoised while it was analysed (its speed-independent matrices:
        the wing structure of a PropellerWing, ≈ 150 kB for the wingtip model; its last few
        evaluations of the blocks).  A study that
        analyses thousands of variants in one process calls it after each, so that its memory
        does not grow with the number of points; the next analysis recomputes them."""
        memo = getattr(self, "_memo", None)
        if memo is not None:
            memo.clear()

    def state_labels(self) -> tuple[str, ...]:
        """Labels of the first-order state [q, q̇, w] (:attr:`DofMap.state_labels`)."""
        return self.dof_map().state_labels
