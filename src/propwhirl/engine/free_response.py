"""Free response of ẋ = A x in time (§9.2, Figures 9.11–9.12), model-agnostic."""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp

from propwhirl.engine.eigensolve import as_square_stack, single_thread_blas
from propwhirl.results import Result, SavedDict
from propwhirl.validate import InputError, finite, in_range, increasing


@dataclass(frozen=True)
class TimeResponse(Result):
    """Time histories of the states: t (T,) [s], x (T, n), labels (n).

    A :class:`~propwhirl.results.Result` of kind "time-response" (format
    ``propwhirl.time-response/1``; a dict without a format, as written before it, is
    version 1): :meth:`save` / :meth:`load`.  ``response["label"]`` is one state's history.

    Attributes
    ----------
    t : ndarray
        (T,) times [s], increasing.
    x : ndarray
        (T, n) the states, each in its own unit (displacements [m] or [rad], rates [m/s] or
        [rad/s], lag states).
    labels : tuple of str
        The n state labels.

    Examples
    --------
    An undamped oscillator ẍ + 4 x = 0 from x = 1 at rest (:func:`time_response`):

    >>> import numpy as np
    >>> from propwhirl.engine import time_response
    >>> r = time_response(np.array([[0.0, 1.0], [-4.0, 0.0]]), [1.0, 0.0],
    ...                   np.linspace(0.0, 3.0, 31), ["x", "v"])
    >>> r.x.shape, r.labels
    ((31, 2), ('x', 'v'))
    >>> round(float(r["x"][-1]), 4), round(float(np.cos(6.0)), 4)       # x(3 s) = cos 6
    (0.9602, 0.9602)
    """

    t: np.ndarray
    x: np.ndarray
    labels: tuple[str, ...]

    KIND: ClassVar[str] = "time-response"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    UNTAGGED: ClassVar[int | None] = 1
    WHAT: ClassVar[str] = "time-response file"

    def __getitem__(self, label: str) -> np.ndarray:
        try:
            return self.x[:, self.labels.index(label)]
        except ValueError:
            raise InputError(f"no state labelled {label!r}; states are {self.labels}") from None

    def encode(self) -> dict[str, Any]:
        return {"t": self.t.tolist(), "x": self.x.tolist(), "labels": list(self.labels)}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "TimeResponse":
        """t finite and increasing, x of shape (T, n) finite, n labels (InputError naming the
        key)."""
        r = SavedDict(d, where, ("t", "x", "labels"))
        t = r.array("t")
        if t.size == 0:
            raise InputError(f"{r.name('t')}: no times")
        if not (np.diff(t) > 0).all():
            raise InputError(f"{r.name('t')}: times must increase")
        labels = r.strings("labels")
        return cls(t, r.array("x", ndim=2, shape=(t.size, len(labels))), labels)


def time_response(A, x0, t, state_labels: Sequence[str] | None = None, *,
                  method: str = "expm", rtol: float = 1e-9) -> TimeResponse:
    """Free response of ẋ = A x from x(t[0]) = x0 (§9.2, Figures 9.11–9.12).

    Parameters
    ----------
    A : array_like, shape (n, n)
        The real state matrix (eq. 5.4) at one speed.
    x0 : array_like, shape (n,)
        The initial state.
    t : array_like
        Times [s], strictly increasing; ``t[0]`` is the start.
    state_labels : sequence of str, optional
        The ``n`` state labels; default ``"x0"``, ``"x1"``, ….
    method : {"expm", "ivp"}
        "expm": exact transition matrices e^{AΔt} (scipy.linalg.expm), one per distinct
        step, applied step by step; "ivp": scipy's solve_ivp (RK45, like MATLAB's ode45) with
        ``rtol``.
    rtol : float
        Relative tolerance of "ivp".

    Returns
    -------
    TimeResponse
        ``t`` and the states ``x`` (T, n), indexable by label.

    Examples
    --------
    An undamped oscillator ẍ + 4 x = 0 from x = 1 at rest: x(t) = cos 2t.

    >>> import numpy as np
    >>> from propwhirl.engine import time_response
    >>> A = np.array([[0.0, 1.0], [-4.0, 0.0]])
    >>> r = time_response(A, [1.0, 0.0], np.linspace(0.0, 3.0, 31), ["x", "v"])
    >>> np.allclose(r["x"], np.cos(2 * r.t))
    True
    """
    A = as_square_stack(A, "A")
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
