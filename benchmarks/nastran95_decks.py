"""NASTRAN-95 flutter decks written from propwhirl's own models (issue 37, item 2): the same
structure, panels (or strips) and spline, so that NASTRAN-95's PK solution and propwhirl's
p-k can be compared number for number and timed side by side
(``benchmarks/nastran95_side_by_side.py``).

NASTRAN-95 (COSMIC NASTRAN, the ``nastran95`` package) runs its modal flutter analysis as
``APP AERO``, ``SOL 10`` (rigid format AERO 10, MSC's SOL 145), ``FLUTTER`` method ``PK``.
What the deck holds:

* **the structure as its modes** (modal coordinates): the lowest ``n_modes`` in-vacuo modes of
  propwhirl's own structural matrices (the wing's M and K on its free DOFs, the same the p-k
  uses), mass-normalised, each a scalar point (``SPOINT``) with the mass 1/s_i² (``CMASS2``)
  and the stiffness ω_i²/s_i² (``CELAS2``), s_i the mode's largest spline coefficient (so that
  the ``SPLINE3`` coefficients, small fields only, keep six digits).  NASTRAN's eigenvalue
  analysis (``EIGR``, Givens) of these finds the same frequencies and mode shapes: NASTRAN-95 has no beam element with a
  mass offset (no CBEAM; ``propwhirl export``'s SOL 103 deck uses one), and its DMIG
  matrices (K2PP, M2PP) enter AERO 10 only after its modes are found, so modal coordinates are
  the one way to give it propwhirl's structure exactly.
* **the spline as propwhirl's own**, one ``SPLINE3`` (a linear constraint) per aerodynamic DOF:
  a doublet-lattice box's point is its centre, a strip's its quarter chord at mid-span
  (NASTRAN-95's APD1/APD4), with components 3 (T3, up) and 5 (R2, the pitch about the span,
  nose up); their coefficients on each mode are propwhirl's beam-to-panel spline
  (:func:`propwhirl.model.aerodynamics.dlm_mesh.spline`, the beam's own shape functions with a
  rigid chord) times the mode: T3 = −z (propwhirl's z is positive down), R2 = α.
* **the aerodynamics as NASTRAN's own**: doublet-lattice panels (``CAERO1``/``PAERO1``, the
  planform of :func:`~propwhirl.model.aerodynamics.dlm_mesh.panel_mesh`: equal chordwise and
  spanwise divisions; ``AERO`` SYMXZ = +1, the root a plane of symmetry as in propwhirl) or
  strips (``CAERO4``/``PAERO4``: Theodorsen's function, C_lα = 2π), the AICs at the Mach
  numbers and reduced frequencies of ``MKAERO1`` (all combinations, computed by NASTRAN at the
  start of the run: its whole table), interpolated by its surface spline (``IMETH = S``).
* **the PK solution** at the density ratio 1 (RHOREF the model's density), one Mach, the
  velocities given, ``EPS`` on k.

Units: SI (m, kg, s) throughout.  Nothing of NASTRAN is written here but its input; the
package runs the deck (:func:`run_deck`) and :func:`flutter_summary` reads its printed
FLUTTER SUMMARY.
"""
from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from propwhirl.model.aerodynamics.dlm_mesh import panel_mesh, spline
from propwhirl.model.structure.assembly import free_dofs

#: first id of the aerodynamic boxes (or strips); the modes are scalar points 1 … n_modes
CAERO_ID = 1001
#: reduced frequency standing for k = 0 (MKAERO1 allows none: its Remark 4)
K_ZERO = 1e-4
#: PK convergence on k (NASTRAN's default 1e-3 is coarse against propwhirl's 1e-7 relative)
EPS = 1e-6


# ---------------------------------------------------------------------------------- cards
def _real(x: float) -> str:
    """A real in a large (16-character) field, ten significant digits (NASTRAN-95 keeps
    single precision of bulk data reals: seven)."""
    x = float(x)
    if not np.isfinite(x):
        raise ValueError(f"not a finite number: {x!r}")
    return f"{x:.9E}"


def _field(value) -> str:
    if value is None:
        return ""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return _real(value)
    return str(value)


def _real8(x: float) -> str:
    """A real in a small (8-character) field with the most significant digits that fit
    (fixed point, or NASTRAN's exponent without the ``E``: ``-1.2345-3``)."""
    x = float(x)
    if not np.isfinite(x):
        raise ValueError(f"not a finite number: {x!r}")
    if x == 0.0:
        return "0."
    for digits in range(7, 0, -1):
        m, e = f"{x:.{digits - 1}E}".split("E")
        e = int(e)
        cands = [f"{m}{e:+d}"]
        decimals = digits - 1 - e
        if decimals >= 0:
            fixed = f"{x:.{decimals}f}"
            fixed = fixed.replace("0.", ".", 1) if fixed.startswith(("0.", "-0.")) else fixed
            cands.insert(0, fixed if "." in fixed else fixed + ".")
        for t in cands:
            if len(t) <= 8:
                return t
    raise ValueError(f"{x!r} does not fit a small field")


class _Cards:
    """Bulk data cards, each continuation named (NASTRAN-95 pairs a card's field 10 with its
    continuation's field 1): large fields (16 characters) by default, small ones
    (``small=True``) for the cards NASTRAN-95 reads only in small fields."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self._n = 0

    def add(self, name: str, *fields, small: bool = False) -> None:
        if small:
            return self._add_small(name, *fields)
        texts = [_field(f) for f in fields]
        while texts and texts[-1] == "":
            texts.pop()
        chunks = [texts[i:i + 4] for i in range(0, max(len(texts), 1), 4)]
        head = f"{name}*"
        for j, chunk in enumerate(chunks):
            body = "".join(f"{t:>16s}" for t in chunk).ljust(64)
            if j < len(chunks) - 1:
                self._n += 1
                tag = f"{self._n:07d}"
                self.lines.append(f"{head:<8s}{body}+{tag}")
                head = f"*{tag}"
            else:
                self.lines.append(f"{head:<8s}{body}".rstrip())

    def _add_small(self, name: str, *fields) -> None:
        texts = [("" if f is None else _real8(f) if isinstance(f, (float, np.floating))
                  else str(int(f)) if isinstance(f, (int, np.integer)) else str(f))
                 for f in fields]
        while texts and texts[-1] == "":
            texts.pop()
        chunks = [texts[i:i + 8] for i in range(0, max(len(texts), 1), 8)]
        head = name
        for j, chunk in enumerate(chunks):
            body = "".join(f"{t:<8s}" for t in chunk).ljust(64)
            if j < len(chunks) - 1:
                self._n += 1
                tag = f"+{self._n:06d}"
                self.lines.append(f"{head:<8s}{body}{tag}")
                head = tag
            else:
                self.lines.append(f"{head:<8s}{body}".rstrip())

    def small(self, line: str) -> None:
        """A card as written (small field, e.g. SPOINT ... THRU ...)."""
        self.lines.append(line)


# ---------------------------------------------------------------------------------- model
@dataclass(frozen=True)
class Modes:
    """The lowest in-vacuo modes of a wing's structure: ω [rad/s] (n_modes,) and the
    mass-normalised shapes (n_free, n_modes) on the free DOFs of the p-k's structural
    matrices (its first ``n_bt`` rows the wing's bending–torsion DOFs, root removed)."""

    omega: np.ndarray
    shapes: np.ndarray
    n_bt: int


def structural_modes(model, n_modes: int) -> Modes:
    """:class:`Modes` of ``model``'s structure (its wing aerodynamics off, the matrices the
    p-k method uses: :func:`propwhirl.model.aerodynamics.dlm.pk_system_dlm`); a wing alone
    (no propellers), no damping (refused otherwise: the deck holds none)."""
    if model.propellers:
        raise ValueError("nastran95_decks: the wing alone (no propellers) only")
    dry = dataclasses.replace(model, wing_aero=False).second_order(np.array([1.0]))
    M, C, K = (np.asarray(X[0], float) for X in (dry.S1, dry.S2, dry.S3))
    if np.abs(C).max() > 0:
        raise ValueError("nastran95_decks: a structure with damping is not written")
    w2, X = eigh(K, M)
    keep = slice(0, n_modes)
    return Modes(np.sqrt(w2[keep]), X[:, keep], free_dofs(model.wing.n_nodes).size)


def _spline_rows(model, modes: Modes, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(T3, R2) coefficients (n_points, n_modes) of each aerodynamic point on each mode."""
    Z, S = spline(model.wing, points)
    keep = free_dofs(model.wing.n_nodes)
    phi = modes.shapes[:modes.n_bt]
    return -(Z[:, keep] @ phi), S[:, keep] @ phi


def k_nodes(model, speeds, modes: Modes, extra: int = 1) -> np.ndarray:
    """The reduced frequencies of the AIC table: propwhirl's own table nodes
    (:meth:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics.k_node`: 0 — here
    :data:`K_ZERO` —, then 8 a decade from 0.01) up to ``extra`` beyond the highest mode's k at
    the lowest speed (k on the root semichord)."""
    from propwhirl.model.aerodynamics.dlm import DlmAerodynamics
    b = float(model.wing.node_properties()["b"][0])
    k_max = 1.3 * modes.omega.max() * b / float(np.min(speeds))
    ks, i = [K_ZERO], 1
    while True:
        k = DlmAerodynamics.k_node(i)
        ks.append(k)
        if k >= k_max:
            extra -= 1
            if extra < 0:
                break
        i += 1
    return np.array(ks)


def deck(model, speeds, *, mach: float, n_modes: int = 6, panels: tuple[int, int] | None = None,
         strips: int | str | None = None, ks=None, title: str = "PROPWHIRL MODEL") -> str:
    """The NASTRAN-95 deck (AERO 10, PK) of ``model``'s wing alone: ``panels`` = (chordwise,
    spanwise) doublet-lattice boxes (default the wing's own counts), or ``strips`` equal strips
    of Theodorsen strip theory (``"nodes"``: one strip per beam node, edges half-way between
    the nodes, as propwhirl's strips); one ``mach``; velocities ``speeds`` [m/s]; the AICs at ``ks``
    (default :func:`k_nodes`); ``n_modes`` in-vacuo modes."""
    wing = model.wing
    modes = structural_modes(model, n_modes)
    speeds = np.asarray(speeds, float)
    if isinstance(strips, str) and strips == "nodes":
        # one strip per beam node, as propwhirl's strips (its loads lumped at the nodes): the
        # division points half-way between the nodes
        y = wing.node_y / wing.semi_span
        edges = np.concatenate([[0.0], 0.5 * (y[1:] + y[:-1]), [1.0]])
    elif strips is not None:
        edges = np.linspace(0.0, 1.0, int(strips) + 1)
    ks = k_nodes(model, speeds, modes) if ks is None else np.asarray(ks, float)
    node = wing.node_properties()
    b_root = float(node["b"][0])
    c = _Cards()
    n = modes.omega.size
    c.small(f"SPOINT  1       THRU    {n}")
    # the spline (below) first: each mode's scalar point scaled so that its largest spline
    # coefficient is 1 (six digits in a small field, where SPLINE3 must be)
    if strips is None:
        mesh = panel_mesh(wing, *(panels or (None, None)))
        points = mesh.points(0.5)                       # the box centres (NASTRAN's APD1)
    else:
        ys = 0.5 * (edges[1:] + edges[:-1]) * wing.semi_span
        bs = np.interp(ys, node["y"], node["b"])
        aa = np.interp(ys, node["y"], node["a"])        # quarter chords (NASTRAN's APD4)
        points = np.stack([-(1.0 + aa) * bs + 0.5 * bs, ys, np.zeros(ys.size)], axis=1)
    t3, r2 = _spline_rows(model, modes, points)
    scale = np.maximum(np.abs(t3).max(axis=0), np.abs(r2).max(axis=0))
    for i, (w, s) in enumerate(zip(modes.omega, scale), 1):
        c.add("CMASS2", 100 + i, 1.0 / s ** 2, i, 0)
        c.add("CELAS2", 200 + i, float(w) ** 2 / s ** 2, i, 0)
    # Givens, every root, mass normalisation
    c.add("EIGR", 10, "GIV", 0.0, float(modes.omega.max()) / np.pi, None, n, None, None,
          "MASS")
    c.add("EIGC", 20, "HESS", "MAX", None, None, None, None, None,
          None, None, None, None, None, None, n)
    c.add("AERO", 0, float(np.max(speeds)), 2.0 * b_root, float(model.flight.density), 1)
    y = np.array([0.0, wing.semi_span])
    b = np.interp(y, node["y"], node["b"])
    a = np.interp(y, node["y"], node["a"])
    le = -(1.0 + a) * b
    corners = (le[0], 0.0, 0.0, 2 * b[0], le[1], float(wing.semi_span), 0.0, 2 * b[1])
    if strips is None:
        c.add("CAERO1", CAERO_ID, 1, 0, mesh.n_span, mesh.n_chord, None, None, 1, *corners)
        c.add("PAERO1", 1)
    else:
        n_strips = edges.size - 1
        if isinstance(strips, str):
            c.add("CAERO4", CAERO_ID, 1, 0, None, 50, None, None, None, *corners)
            c.add("AEFACT", 50, *[float(e) for e in edges], small=True)
        else:
            c.add("CAERO4", CAERO_ID, 1, 0, n_strips, None, None, None, None, *corners)
        c.add("PAERO4", 1, 0, 0, 0, 0, *([0.0, 0.0, 0.0] * n_strips), small=True)
    eid = 100000
    for p in range(points.shape[0]):
        for comp, row in ((3, t3[p]), (5, r2[p])):
            eid += 1
            terms = []
            for j in range(n):
                terms += [j + 1, 1, float(row[j] / scale[j]), None]
            c.add("SPLINE3", eid, CAERO_ID, CAERO_ID + p, comp, *terms, small=True)
    for i in range(0, ks.size, 8):
        c.add("MKAERO1", max(float(mach), K_ZERO), *([None] * 7),
              *[float(k) for k in ks[i:i + 8]], small=True)
    c.add("FLFACT", 1, 1.0, small=True)
    c.add("FLFACT", 2, max(float(mach), K_ZERO), small=True)
    c.add("FLFACT", 3, *[float(v) for v in speeds], small=True)
    c.add("FLUTTER", 30, "PK", 1, 2, 3, "S", n, EPS, small=True)
    c.add("PARAM", "LMODES", n, small=True)
    head = ["ID    PROPWHIRL,N95", "APP   AERO", "SOL   10,0", "TIME  100", "CEND",
            f"TITLE = {title[:60].upper()}", "ECHO = NONE", "METHOD = 10", "CMETHOD = 20",
            "FMETHOD = 30", "BEGIN BULK"]
    return "\n".join(head + c.lines + ["ENDDATA", ""])


# ---------------------------------------------------------------------------------- output
@dataclass(frozen=True)
class Point:
    """One mode's PK results over the velocities: k, V [m/s], g, f [Hz]."""

    point: int
    k: np.ndarray
    V: np.ndarray
    g: np.ndarray
    f: np.ndarray


_ROW = re.compile(r"^\s+([-+0-9.E]+)\s+([-+0-9.E]+)\s+([-+0-9.E]+)\s+([-+0-9.E]+)\s+"
                  r"([-+0-9.E]+)\s+([-+0-9.E]+)\s+([-+0-9.E]+)\s*$")


def flutter_summary(output: str) -> list[Point]:
    """The FLUTTER SUMMARY tables of NASTRAN-95's printed output, one :class:`Point` per mode
    (POINT), rows in the order of the velocities."""
    rows: dict[int, list] = {}
    point = None
    for line in output.splitlines():
        m = re.search(r"POINT =\s+(\d+)\s+MACH NUMBER", line)
        if m:
            point = int(m.group(1))
            rows.setdefault(point, [])
            continue
        if "FLUTTER  SUMMARY" in line or line.startswith("1"):
            continue
        r = _ROW.match(line)
        if r and point is not None:
            k, _, V, g, f, _, _ = (float(x) for x in r.groups())
            rows[point].append((k, V, g, f))
    out = []
    for p, rr in sorted(rows.items()):
        a = np.array(rr, float)
        out.append(Point(p, a[:, 0], a[:, 1], a[:, 2], a[:, 3]))
    return out


def crossings(points: list[Point]) -> list[tuple[float, float, int, str]]:
    """Every sign change of g between neighbouring velocities, linear in V between them:
    (V [m/s], f [Hz], point, "onset" | "end"), by speed."""
    out = []
    for pt in points:
        for i in range(pt.V.size - 1):
            g0, g1 = pt.g[i], pt.g[i + 1]
            if g0 < 0 <= g1 or g0 >= 0 > g1:
                t = -g0 / (g1 - g0) if g1 != g0 else 0.0
                V = pt.V[i] + t * (pt.V[i + 1] - pt.V[i])
                f = pt.f[i] + t * (pt.f[i + 1] - pt.f[i])
                out.append((float(V), float(f), pt.point, "onset" if g0 < 0 else "end"))
    return sorted(out)


def run_deck(text: str, timeout: float | None = None):
    """Run ``text`` with the ``nastran95`` package (its ``nastrn`` executable, a subprocess):
    (the result, CPU seconds of the NASTRAN process: user + system of the children waited for
    meanwhile)."""
    import resource

    import nastran95
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    res = nastran95.NastranRunner().run(text, timeout=timeout)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return res, cpu
