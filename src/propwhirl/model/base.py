"""What every model shares: A(V) from its second-order matrices by the one builder, errors
that name the model parameter behind a bad entry, state labels from the DOF map; and the
evaluator a model gives an analysis (:meth:`StateSpaceModel.assembly`)."""
from __future__ import annotations

import numpy as np

from propwhirl import validate as v
from propwhirl.model.structure.assembly import blame_entry
from propwhirl.model.statespace import SecondOrder, StateMatrixError, check_system, state_matrix


class EvaluatorBase:
    """What every evaluator of a model shares (the model itself, or the assembly a model builds,
    :meth:`StateSpaceModel.assembly`): A(V) from ``second_order`` by the one builder, and a
    bad entry explained by the model parameter behind it.

    Subclasses define ``second_order(V, ...)`` and ``dof_map()``.
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
        (:meth:`_contributions` and :func:`propwhirl.model.structure.assembly.blame_entry`)."""
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

    def state_labels(self) -> tuple[str, ...]:
        """Labels of the first-order state [q, q̇, w] (:attr:`DofMap.state_labels`)."""
        return self.dof_map().state_labels


class StateSpaceModel(EvaluatorBase):
    """What every model shares (the :class:`~propwhirl.model.protocol.Model` contract).

    Subclasses define ``second_order(V, ...)``, ``dof_map()`` and ``without_aerodynamics()``;
    a model whose matrices need speed-independent parts built ahead (a wing's structure)
    overrides :meth:`assembly`.
    """

    def assembly(self) -> EvaluatorBase:
        """The evaluator of this model that an analysis builds once and evaluates at every
        speed (``second_order``, ``state_matrix``, ``dof_map``).  By default the model itself:
        nothing of its matrices is worth building ahead."""
        return self
