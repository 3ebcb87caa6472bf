"""Free response of ẋ = A x in time (§9.2, Figures 9.11–9.12), model-agnostic."""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp

from propwhirl.engine.eigensolve import _as_square_stack, single_thread_blas
from propwhirl.validate import InputError, finite, in_range, increasing


@dataclass(frozen=True)
class TimeResponse:
    """Time histories of the states: t (T,) [s], x (T, n), labels (n)."""

    t: np.ndarray
    x: np.ndarray
    labels: tuple[str, ...]

    def __getitem__(self, label: str) -> np.ndarray:
        try:
            return self.x[:, self.labels.index(label)]
        except ValueError:
            raise InputError(f"no state labelled {label!r}; states are {self.labels}") from None

    def to_dict(self) -> dict[str, Any]:
        return {"t": self.t.tolist(), "x": self.x.tolist(), "labels": list(self.labels)}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "TimeResponse":
        return cls(np.asarray(d["t"], dtype=float), np.asarray(d["x"], dtype=float),
                   tuple(d["labels"]))


def time_response(A, x0, t, state_labels: Sequence[str] | None = None, *,
                  method: str = "expm", rtol: float = 1e-9) -> TimeResponse:
    """Free response of ẋ = A x from x(t[0]) = x0 (§9.2, Figures 9.11–9.12).

    method "expm": exact transition matrices e^{AΔt} (scipy.linalg.expm), one per distinct
    step, applied step by step; "ivp": scipy's solve_ivp (RK45, like MATLAB's ode45) with
    ``rtol``.  ``t`` [s] strictly increasing.
    """
    A = _as_square_stack(A, "A")
    if A.ndim != 2:
        raise InputError(f"A must be one square matrix, got shape {A.shape}")
    n = A.shape[0]
    x0 = finite("x0", x0)
    if x0.shape != (n,):
        raise InputError(f"x0 must have {n} entries (one per state), got shape {x0.shape}")
    tt = increasing("t", t, "s")
    labels = tuple(f"x{i}" for i in range(n)) if state_labels is None else tuple(state_labels)
    if len(labels) != n:
        raise InputError(f"state_labels: got {len(labels)}, need {n}")
    if method == "expm":
        dts = np.diff(tt)
        key = np.round(dts / dts.max(), 12)
        uniq, inv = np.unique(key, return_inverse=True)
        with single_thread_blas():
            Phi = {i: sla.expm(A * dts[np.argmax(inv == i)]) for i in range(uniq.size)}
        x = np.empty((tt.size, n))
        x[0] = x0
        for j in range(tt.size - 1):          # sequential in time by nature
            x[j + 1] = Phi[int(inv[j])] @ x[j]
    elif method == "ivp":
        in_range("rtol", rtol, 0.0, 1e-2, low_open=True)
        atol = rtol * max(float(np.abs(x0).max()), 1e-300) * 1e-3
        sol = solve_ivp(lambda _t, y: A @ y, (tt[0], tt[-1]), x0, t_eval=tt, rtol=rtol,
                        atol=atol, method="RK45")
        if not sol.success:
            raise InputError(f"time integration failed: {sol.message}")
        x = sol.y.T
    else:
        raise InputError(f"method = {method!r} is invalid: must be 'expm' or 'ivp'")
    return TimeResponse(tt, x, labels)
