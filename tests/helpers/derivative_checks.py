"""Central-difference checks of the exact parameter derivatives of a wing model's
second-order system (:mod:`propwhirl.model.derivatives`), and of the critical speeds they give."""
import numpy as np

from propwhirl.analysis import analyse
from propwhirl.model import derivatives as D
from propwhirl.studies import paths as P

NAMES = ("S1", "S2", "S3", "S4", "Ww", "Wv", "Wq")


def assert_matches_central_differences(model, par, exact, V, rel_step=1e-5, rtol=1e-6):
    """∂S/∂p (`exact`, a SecondOrder) against (S(p + h) − S(p − h))/2h of ``second_order(V)``
    of the model with the field changed (:func:`~propwhirl.model.derivatives.with_value`),
    h = max(rel_step |p|, 1e-6).  Tolerance: `rtol` of the derivative's largest entry (the
    truncation, (h/p)² ~ 1e-10 relative for these smooth matrices) plus 1e-9 max|S|/|p|
    (rounding, ~1e-16 max|S| / h)."""
    p = par.value
    h = max(rel_step * abs(p), 1e-6)
    up = D.with_value(model, par.path, p + h).second_order(V)
    down = D.with_value(model, par.path, p - h).second_order(V)
    base = model.second_order(V)
    for name in NAMES:
        fd = (getattr(up, name) - getattr(down, name)) / (2 * h)
        got = getattr(exact, name)
        assert got.shape == getattr(base, name).shape, (par.path, name)
        size = max(float(np.max(np.abs(getattr(base, name)), initial=0.0)), 1e-300)
        tol = rtol * float(np.max(np.abs(got), initial=0.0)) + 1e-9 * size / max(abs(p), h)
        err = np.max(np.abs(got - fd), initial=0.0)
        assert err <= tol, (par.path, name, err, tol)


def fd_critical_speed(model, path, value, event, rel=1e-3):
    """Central difference of the engine's speed of the same event (kind, mode) [m/s per unit]."""
    h = rel * abs(value)
    # whole-distribution factors ("wing.GJ*", value 1) and the density are set as the studies
    # set them; every other path as the derivatives name it
    set_value = P.set_value if path.endswith("*") or path == "flight.density" else D.with_value
    V = []
    for s in (1.0, -1.0):
        a = analyse(set_value(model, path, value + s * h))
        e = min((x for x in a.events if (x.kind, x.event, x.label) ==
                 (event.kind, event.event, event.label)), key=lambda x: abs(x.V - event.V))
        V.append(e.V)
    return (V[0] - V[1]) / (2 * h)
