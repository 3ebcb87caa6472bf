"""Tuning of the mode tracker (:class:`TrackingOptions`) and the check of a speed grid."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from propwhirl import limits
from propwhirl.validate import InputError, in_range, increasing, integer_at_least, positive

#: the valid form of a speed grid, for error messages
SPEEDS_FORM = ("an increasing 1-D array of at least 2 airspeeds > 0 m/s, "
               "e.g. numpy.arange(1.0, 351.0, 10.0)")


@dataclass(frozen=True)
class TrackingOptions:
    """Tuning of the mode tracker (dimensionless unless stated).

    Parameters
    ----------
    mac_min : float
        A match whose MAC is below this is ambiguous (step refined); in [0, 1].
    cost_ratio : float
        A match whose cost exceeds this fraction of the runner-up's cost is ambiguous.
        Cost = (1 − MAC) + |λ_b − λ_pred| / s, s = max(|λ_a|, floor); the correct
        continuation's cost → 0 as the step shrinks, a wrong one's does not, so a relative test
        resolves even near-identical shapes.  Between two real roots the cost is the distance
        term alone.
    dist_max : float
        A match farther than this (relative to s) from its prediction is ambiguous.
    approach_ratio : float
        Two complex eigenvalues whose predicted paths come closer inside a step than this
        fraction of their end separations mark the step ambiguous.
    min_step : float
        Smallest speed step of the refinement [m/s].
    fd_rel : float
        Relative finite-difference step for dA/dV (h = fd_rel·max(V, 1 m/s)).
    degenerate_tol : float
        Eigenvalues closer than this (relative) are treated as repeated.
    zero_tol : float
        |Re λ| ≤ zero_tol·max(|λ|, floor) counts as neutral (no sign).
    max_nodes : int, optional
        Budget of speeds (grid + refinement); None → the first evaluation plus at most
        ``limits.MAX_REFINED_NODES`` (2,000), at most 20·len(grid) + 200, and no more than fit
        in the memory limit (:func:`propwhirl.limits.node_budget`).
    hump_check : bool
        Insert samples where the cubic Hermite model of Re λ between two samples of equal sign
        crosses zero, or comes closer to zero than `margin` times its uncertainty (below).
    decisive_ratio : float
        A match whose prediction mismatch is below this fraction of every other candidate's
        (below 0.1·dist_max, every other candidate farther than dist_max) is unambiguous
        whatever its MAC: the eigenvalue continuation is unique while the shape may change a
        lot along V (e.g. whirl modes at low speed).  0: the MAC is always required.
    margin : float
        Uncertainty of the Hermite model of a step = the mismatch of the trapezoidal
        prediction at the step's end, |λ_b − λ_a − ½(λ'_a + λ'_b) ΔV| (a third-order error
        estimate; the cubic's own error is of fourth order), spread over the step as
        16 s²(1 − s)² (zero at the samples, where λ and λ' are exact).  A branch whose |Re λ|
        model falls below margin × that envelope inside the step is sampled there.  0 keeps
        only the sign test.

    Examples
    --------
    A coarser refinement (0.1 m/s steps at the finest) for :func:`~propwhirl.engine.sweep`,
    :func:`~propwhirl.engine.analyse` or ``propwhirl.analyse(model, options=...)``:

    >>> from propwhirl.engine import TrackingOptions
    >>> opts = TrackingOptions(min_step=0.1)
    >>> opts.min_step, opts.mac_min
    (0.1, 0.8)
    """

    mac_min: float = 0.8
    cost_ratio: float = 0.5
    dist_max: float = 0.1
    approach_ratio: float = 0.5
    min_step: float = 0.01
    fd_rel: float = 1e-6
    degenerate_tol: float = 1e-7
    zero_tol: float = 1e-9
    max_nodes: int | None = None
    hump_check: bool = True
    decisive_ratio: float = 0.05
    margin: float = 1.0

    def __post_init__(self) -> None:
        in_range("mac_min", self.mac_min, 0.0, 1.0)
        in_range("cost_ratio", self.cost_ratio, 0.0, 1.0, low_open=True)
        positive("dist_max", self.dist_max)
        in_range("approach_ratio", self.approach_ratio, 0.0, 1.0)
        positive("min_step", self.min_step, "m/s")
        in_range("fd_rel", self.fd_rel, 0.0, 1e-2, low_open=True)
        in_range("degenerate_tol", self.degenerate_tol, 0.0, 1e-2)
        in_range("zero_tol", self.zero_tol, 0.0, 1e-3)
        in_range("decisive_ratio", self.decisive_ratio, 0.0, 1.0)
        in_range("margin", self.margin, 0.0, 100.0)
        if self.max_nodes is not None:
            integer_at_least("max_nodes", self.max_nodes, 2)


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def check_speeds(speeds, name: str = "speeds") -> np.ndarray:
    """A speed grid [m/s] as a float array: 1-D, at least 2 and at most
    :data:`propwhirl.limits.MAX_SPEEDS` finite values, strictly increasing, all > 0; else a
    one-line InputError naming ``name`` and the valid form (:data:`SPEEDS_FORM`)."""
    bad = InputError(f"{name} = {_short(speeds)} is invalid: must be {SPEEDS_FORM}")
    if speeds is None or isinstance(speeds, (str, bytes, dict, set, frozenset)):
        raise bad
    try:
        raw = np.asarray(speeds)
    except (TypeError, ValueError, OverflowError) as exc:   # ragged nested sequences
        raise bad from exc
    if raw.dtype.kind not in "iuf" and not (raw.dtype.kind == "O" and raw.size and all(
            isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool)
            for x in raw.flat)):
        raise bad                   # bool, complex, strings, None, nested objects
    if raw.ndim != 1 or raw.size < 2:
        raise InputError(f"{name} must be a 1-D array of at least 2 values, got shape "
                         f"{raw.shape}: give {SPEEDS_FORM}")
    limits.check_speed_count(name, raw.size, "fewer speeds")
    try:
        V = increasing(name, raw.astype(float), "m/s")
    except InputError as exc:       # non-finite or not increasing: say what is valid
        raise InputError(f"{exc} ({name}: {SPEEDS_FORM})") from None
    if V[0] <= 0:
        raise InputError(
            f"{name}[0] = {float(V[0])!r} m/s is invalid: must be > 0 (the aerodynamic matrices "
            f"carry 1/V; start the sweep at a small positive speed, e.g. 0.1 m/s)")
    return V


