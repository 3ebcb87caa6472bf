"""Size limits: memory estimates of an analysis, bounds on model sizes, safe terminal text.

Every limit here refuses *before* allocating, with a one-line
:class:`~propwhirl.validate.InputError` that gives the estimate and the limit.

Memory of an analysis (:func:`sweep_bytes`)
    A sweep of ``T`` speeds of a model with ``n`` first-order states (``n = 2 n_dof + n_lag``,
    :attr:`propwhirl.model.protocol.DofMap.n_states`) keeps, per speed, the complex eigenvectors
    of its node (``n² · 16`` bytes) and again in the assembled
    :class:`~propwhirl.engine.results.Sweep` (``n² · 16``): :data:`RETAINED_BYTES_PER_ENTRY`
    = 32 bytes per entry of ``A``.  The engine evaluates at most :data:`MAX_BATCH` speeds per
    call of the state matrix; a batch holds ``A(V)`` and ``A(V + h)`` (2 · 8 bytes), dA/dV (8),
    LAPACK's eigenvectors before they are stored (16) and workspace:
    :data:`BATCH_BYTES_PER_ENTRY` = 48 bytes per entry and speed of the batch.  Measured
    (tracemalloc) on the wingtip propeller-wing, 204 states, one batch of 50 and 200 speeds:
    61–64 bytes per entry and speed, = 32 + 32 of the two terms above.  Each node also holds
    a few vectors and a Python object: :data:`NODE_OVERHEAD_BYTES`; a batch also holds the
    model's own temporaries, :data:`BATCH_MODEL_BYTES` per speed (the Houbolt–Reed integrals:
    ≈ 25 kB per speed measured on the isolated propeller, where they dominate).

The memory limit (:func:`memory_limit`)
    ``PROPWHIRL_MEMORY_LIMIT`` (bytes, or a number with a unit: ``"512MiB"``, ``"4GiB"``,
    ``"2GB"``), else half of the machine's physical memory (``os.sysconf``), at most
    :data:`DEFAULT_LIMIT_CAP` (8 GiB: an analysis that needs more is refused unless asked for
    explicitly), at least 256 MiB; 2 GiB where the machine does not report its memory.

Memory of a doublet-lattice AIC (:func:`aic_bytes`, :func:`check_panels`)
    PanelAero computes the AIC of n panels of a half-wing on both halves, a (2n)² complex
    kernel, from some twenty (2n, 2n) temporaries: :data:`AIC_BYTES_PER_ENTRY` = 512 bytes per
    entry of (2n)².  Measured on 200–1200 mirrored panels at k > 0 (planar wing): 480 bytes
    per entry (tracemalloc peak), 485–502 (growth of the process's peak RSS); at k = 0, 280.
    2,000 panels (``dlm_mesh.MAX_PANELS``): ≈ 7.6 GiB.  Checked before any panel is built.
    Since issue 37 item 2 a planar mesh takes propwhirl's kernel on the half-wing's rows
    (``model.aerodynamics.dlm_kernel``): a new Mach column with the kernels kept, 331 bytes
    per entry of (2n)² (tests/model/test_dlm_memory.py); the estimate stays PanelAero's, the
    path a non-planar mesh takes.

Arrays read from a file (:func:`check_read`)
    The bytes the file's description says its arrays hold (e.g. an eigenvector ``.npz``: the
    speeds and states of its analysis file) against :func:`memory_limit`, before reading.

Sizes bounded outright (the memory they imply is no question of the machine)
    :data:`MAX_SPEEDS` speeds in a grid, :data:`MAX_ELEMENTS` wing elements,
    :data:`MAX_PROPELLERS` propellers, :data:`MAX_QUADRATURE_ORDER` Gauss–Legendre points,
    :data:`MAX_RPM` rev/min, :data:`MAX_NESTING` levels of nesting in a model file, and
    :data:`MAX_REFINED_NODES` speeds the tracker may add to a sweep.
"""
from __future__ import annotations

import math
import os
import re
import unicodedata

from propwhirl.validate import InputError

GiB = 2 ** 30
MiB = 2 ** 20

#: environment variable of the memory limit (bytes, or e.g. "4GiB", "512MB")
MEMORY_ENV = "PROPWHIRL_MEMORY_LIMIT"
#: the default limit is at most this [bytes] (half the physical memory below 16 GiB of RAM)
DEFAULT_LIMIT_CAP = 8 * GiB
#: fraction of the physical memory the default limit allows
DEFAULT_FRACTION = 0.5
#: default limit where the machine does not report its memory [bytes]
FALLBACK_LIMIT = 2 * GiB

#: bytes kept per entry of A(V) and per node: eigenvectors in the node and in the Sweep
RETAINED_BYTES_PER_ENTRY = 32
#: bytes per entry of A(V) and per speed of one batch while it is evaluated
BATCH_BYTES_PER_ENTRY = 48
#: per node: eigenvalues, dλ/dV, conjugate index, the Python objects [bytes] (n ≤ a few 1000)
NODE_OVERHEAD_BYTES = 4096
#: speeds per call of the state matrix in the engine (bounds a batch's temporaries; the
#: Houbolt–Reed integrals of a propeller take ≈ 25 kB per speed at the default order)
MAX_BATCH = 256
#: temporaries of one batch at most [bytes] (fewer speeds per batch for large models)
BATCH_MEMORY = 256 * MiB
#: the model's own temporaries per speed of a batch [bytes]: the Houbolt–Reed integrals of a
#: propeller at the default order, measured ≈ 25 kB per speed (isolated propeller, tracemalloc)
BATCH_MODEL_BYTES = 32 * 2 ** 10

#: bytes per entry of the (2n)² doublet-lattice kernel of n half-wing panels while PanelAero
#: computes one AIC (module docstring: measured 480–502)
AIC_BYTES_PER_ENTRY = 512

#: speeds in one grid: a sweep refined to the tracker's 0.01 m/s over 0–1000 m/s has 100,000
MAX_SPEEDS = 100_000
#: speeds the tracker may add to a sweep (refinement and hump checks) beyond its first
#: evaluation; besides ``20 · len(grid) + 200`` and the memory limit.  The thesis's analyses
#: add fewer than 100.
MAX_REFINED_NODES = 2_000
#: wing elements: the thesis's wing results converge within a few elements (§7.4, Figures 7.3
#: and 7.5) and its analyses use 25; 200 elements are ≈ 1,600–2,000 states, one
#: eigen-solution ≈ 5 s and ≈ 0.2 GB per speed
MAX_ELEMENTS = 200
#: propellers on one wing (X-57 has 14); each adds 2 DOFs and its Houbolt–Reed integrals
MAX_PROPELLERS = 64
#: Gauss–Legendre points per panel: 8× the default 32, which agrees with 64 points to 1e-8
#: (tests/model/test_propeller_aero.py); numpy's nodes cost O(order²) memory, O(order³) time
MAX_QUADRATURE_ORDER = 256
#: propeller rotational speed [rev/min] of a Campbell diagram (tip speed of a 1 m propeller
#: at 100,000 rev/min: 10.5 km/s)
MAX_RPM = 100_000.0
#: nesting of arrays and tables in a model file, the document itself counted (the case
#: library's model files have 3 to 5 levels)
MAX_NESTING = 32


# ----------------------------------------------------------------------------- memory
_UNITS = {"": 1, "b": 1, "k": 1000, "kb": 1000, "kib": 2 ** 10, "m": 1000 ** 2, "mb": 1000 ** 2,
          "mib": MiB, "g": 1000 ** 3, "gb": 1000 ** 3, "gib": GiB, "t": 1000 ** 4,
          "tb": 1000 ** 4, "tib": 2 ** 40}


def parse_bytes(text: str, name: str = MEMORY_ENV) -> int:
    """Bytes from ``"4GiB"``, ``"512 MB"``, ``"2e9"`` (units: B, kB, KiB, MB, MiB, GB, GiB, …)."""
    m = re.fullmatch(r"\s*([0-9]*\.?[0-9]+(?:[eE][+-]?[0-9]+)?)\s*([A-Za-z]*)\s*", str(text))
    unit = m.group(2).lower() if m else ""
    if m is None or unit not in _UNITS:
        raise InputError(f"{name} = {text!r} is invalid: give bytes or a number with a unit, "
                         "e.g. 4GiB or 512MB")
    value = float(m.group(1)) * _UNITS[unit]
    if not (math.isfinite(value) and value >= MiB):
        raise InputError(f"{name} = {text!r} is invalid: must be at least 1 MiB")
    return int(value)


def physical_memory() -> int | None:
    """The machine's physical memory [bytes] (``os.sysconf``), None where not reported."""
    try:
        pages, size = os.sysconf("SC_PHYS_PAGES"), os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None
    return pages * size if pages > 0 and size > 0 else None


def memory_limit() -> int:
    """The memory an analysis may use [bytes] (module docstring): ``PROPWHIRL_MEMORY_LIMIT``,
    else half the physical memory, within [256 MiB, 8 GiB]."""
    env = os.environ.get(MEMORY_ENV)
    if env is not None and env.strip():
        return parse_bytes(env)
    phys = physical_memory()
    if phys is None:
        return FALLBACK_LIMIT
    return int(min(max(DEFAULT_FRACTION * phys, 256 * MiB), DEFAULT_LIMIT_CAP))


def format_bytes(n: float) -> str:
    """'9.5 GiB', '310 MiB', '2.5 TiB'."""
    for unit, size in (("TiB", 2 ** 40), ("GiB", GiB), ("MiB", MiB), ("KiB", 2 ** 10)):
        if n >= size:
            x = n / size
            return f"{x:.1f} {unit}" if x < 100 else f"{x:,.0f} {unit}"
    return f"{n:.0f} B"


def batch_size(n_states: int) -> int:
    """Speeds per call of the state matrix in the engine: at most :data:`MAX_BATCH`, and
    temporaries of at most :data:`BATCH_MEMORY` (≥ 1 speed)."""
    per_speed = BATCH_BYTES_PER_ENTRY * float(n_states) ** 2
    return int(max(1, min(MAX_BATCH, BATCH_MEMORY // max(per_speed, 1.0))))


def sweep_bytes(n_speeds: int, n_states: int) -> int:
    """Estimated peak memory [bytes] of a sweep of ``n_speeds`` nodes of ``n_states`` states
    (module docstring): kept eigenvectors, one batch's temporaries, per-node overhead."""
    n2 = float(n_states) ** 2
    return int(n_speeds * (RETAINED_BYTES_PER_ENTRY * n2 + NODE_OVERHEAD_BYTES)
               + min(n_speeds, batch_size(n_states)) * (BATCH_BYTES_PER_ENTRY * n2
                                                        + BATCH_MODEL_BYTES))


def check_sweep(n_speeds: int, n_states: int, what: str = "the analysis",
                advice: str = "pass fewer speeds") -> None:
    """Refuse a sweep whose :func:`sweep_bytes` exceeds :func:`memory_limit`."""
    need, limit = sweep_bytes(n_speeds, n_states), memory_limit()
    if need > limit:
        raise InputError(
            f"{what} needs ≈ {format_bytes(need)} for {n_speeds:,} speeds × {n_states:,} states "
            f"(limit {format_bytes(limit)}, set {MEMORY_ENV} or {advice})")


def check_read(n_bytes: int, what: str) -> None:
    """Refuse reading arrays of ``n_bytes`` [bytes] from a file (their size as the file's
    own description gives it, checked before anything is allocated) when they exceed
    :func:`memory_limit`."""
    limit = memory_limit()
    if n_bytes > limit:
        raise InputError(f"{what} needs ≈ {format_bytes(n_bytes)} to read (limit "
                         f"{format_bytes(limit)}, set {MEMORY_ENV})")


def aic_bytes(n_panels: int) -> int:
    """Estimated peak memory [bytes] of one doublet-lattice AIC of ``n_panels`` panels of a
    half-wing (module docstring): :data:`AIC_BYTES_PER_ENTRY` per entry of (2 n_panels)²."""
    return int(AIC_BYTES_PER_ENTRY * (2.0 * n_panels) ** 2)


def check_panels(n_chord: int, n_span: int) -> None:
    """Refuse doublet-lattice panels whose AIC (:func:`aic_bytes`) exceeds
    :func:`memory_limit`, naming the panel counts that fit (the chordwise count kept, or the
    spanwise one)."""
    n = int(n_chord) * int(n_span)
    need, limit = aic_bytes(n), memory_limit()
    if need <= limit:
        return
    most = int(math.isqrt(limit // AIC_BYTES_PER_ENTRY) // 2)          # aic_bytes(most) <= limit
    fits = [f"{a} x {b}" for a, b in ((n_chord, most // n_chord), (most // n_span, n_span))
            if a >= 1 and b >= 1]
    raise InputError(
        f"dlm_chordwise_panels x dlm_spanwise_panels = {n_chord} x {n_span} = {n:,} panels is "
        f"invalid: each AIC needs ≈ {format_bytes(need)} (limit {format_bytes(limit)}, set "
        f"{MEMORY_ENV}); at most {most:,} panels fit"
        + (f", e.g. {' or '.join(fits)}" if fits else ""))


def node_budget(n_grid: int, n_first: int, n_states: int, requested: int | None = None) -> int:
    """Most nodes (speeds) a sweep may hold: ``requested`` (``TrackingOptions.max_nodes``), by
    default its first ``n_first`` evaluations plus at most :data:`MAX_REFINED_NODES`
    refinements and at most ``20 · n_grid + 200``; in any case no more than fit in
    :func:`memory_limit` (:func:`sweep_bytes`), and never fewer than ``n_first``."""
    per_node = RETAINED_BYTES_PER_ENTRY * float(n_states) ** 2 + NODE_OVERHEAD_BYTES
    # a refinement batch may be a full one: its temporaries are reserved whole
    batch = batch_size(n_states) * (BATCH_BYTES_PER_ENTRY * float(n_states) ** 2
                                    + BATCH_MODEL_BYTES)
    fit = int(max(memory_limit() - batch, 0) // per_node)
    want = (min(20 * n_grid + 200, n_first + MAX_REFINED_NODES) if requested is None
            else int(requested))
    return max(n_first, min(want, fit))


# ----------------------------------------------------------------------------- sizes
def grid_count(first: float, last: float, step: float) -> float:
    """Number of speeds of the grid first, first + step, …, last (last included); inf when
    the range or the step is not finite or the step is not positive."""
    try:
        n = (float(last) - float(first)) / float(step)
    except (TypeError, ValueError, ZeroDivisionError):
        return math.inf
    if not math.isfinite(n) or not float(step) > 0:
        return math.inf
    return math.ceil(n - 1e-9) + 1


def check_speed_count(name: str, count: float, form: str = "a larger step") -> None:
    """At most :data:`MAX_SPEEDS` speeds in a grid."""
    if not count <= MAX_SPEEDS:
        what = "infinitely many" if not math.isfinite(count) else f"{int(count):,}"
        raise InputError(f"{name} gives {what} speeds: must be at most {MAX_SPEEDS:,} "
                         f"({form})")


def _at_most(name: str, value, maximum, why: str) -> None:
    try:
        ok = value <= maximum
    except TypeError:
        return                      # the type is the field check's business
    if not ok:
        raise InputError(f"{name} = {value!r} is invalid: must be at most {maximum:,} ({why})")


def check_elements(n_elements) -> None:
    """At most :data:`MAX_ELEMENTS` wing elements."""
    _at_most("n_elements", n_elements, MAX_ELEMENTS,
             "the states grow as 8-10 per element, memory and time of an eigen-solution as "
             "their square and cube; the thesis's wing results converge within a few elements")


def check_propellers(count: int) -> None:
    """At most :data:`MAX_PROPELLERS` propellers on a wing."""
    _at_most("number of propellers", count, MAX_PROPELLERS, "each adds 2 DOFs and its "
             "Houbolt-Reed integrals at every speed")


def check_quadrature_order(order) -> None:
    """At most :data:`MAX_QUADRATURE_ORDER` Gauss–Legendre points per panel."""
    _at_most("quadrature_order", order, MAX_QUADRATURE_ORDER,
             "the default 32 is converged to 1e-8; the nodes cost order^2 memory")


# ----------------------------------------------------------------------------- nesting
def nesting_depth(data, limit: int = MAX_NESTING) -> int:
    """Depth of nested dicts and lists in ``data`` (a scalar: 0), iteratively; counting stops
    at ``limit + 1``."""
    deepest, stack = 0, [(data, 0)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, dict):
            children = item.values()
        elif isinstance(item, (list, tuple)):
            children = item
        else:
            continue
        depth += 1
        deepest = max(deepest, depth)
        if deepest > limit:
            return deepest
        stack.extend((c, depth) for c in children)
    return deepest


def nesting_error(source: str) -> InputError:
    """The one-line error of a document nested deeper than :data:`MAX_NESTING` levels."""
    return InputError(f"{source}: nesting deeper than {MAX_NESTING} levels (arrays or tables "
                      "inside each other; a model file needs at most 5)")


def check_nesting(data, source: str) -> None:
    """Refuse parsed data nested deeper than :data:`MAX_NESTING` levels."""
    if nesting_depth(data) > MAX_NESTING:
        raise nesting_error(source)


# ----------------------------------------------------------------------------- terminal text
_BIDI = {0x061C, 0x200E, 0x200F, *range(0x202A, 0x202F), *range(0x2066, 0x206A)}


def _escape(ch: str) -> str:
    o = ord(ch)
    return f"\\x{o:02x}" if o < 0x100 else (f"\\u{o:04x}" if o < 0x10000 else f"\\U{o:08x}")


def printable(text) -> str:
    """``text`` safe to print: control characters (C0, DEL, C1 — ESC among them), line and
    paragraph separators and bidirectional overrides become visible escapes (``\\x1b``,
    ``\\u202e``); everything else is kept.

    >>> printable("wing\\x1b[2J\\x9b1m")
    'wing\\\\x1b[2J\\\\x9b1m'
    """
    s = str(text)
    if s.isprintable() and not any(ord(c) in _BIDI for c in s):
        return s
    return "".join(_escape(c) if (unicodedata.category(c) in ("Cc", "Zl", "Zp")
                                  or ord(c) in _BIDI) else c for c in s)


# ----------------------------------------------------------------------------- studies
#: environment variable of the longest study started without asking (seconds, or a number
#: with a unit: "90min", "12h", "3d"; "none": no limit)
STUDY_TIME_ENV = "PROPWHIRL_STUDY_TIME_LIMIT"
#: default longest estimated study [s] (wall-clock on the given processes): 12 hours
DEFAULT_STUDY_SECONDS = 12 * 3600.0
#: a study estimated at least this long [s] prints its estimate before the work
STUDY_NOTICE_SECONDS = 60.0
#: speeds an analysis evaluates, typically (the thesis's models: 8–30 with ``analyse``'s
#: refinement; docs/performance.md) — the estimate's nodes per analysis
STUDY_NODES = 40
#: seconds per state³ of one eigen-solution (``eig`` with vectors, dλ/dV included):
#: ≈ 7 ms for the 204 states of the wingtip model on one thread (docs/performance.md)
EIG_SECONDS_PER_STATE3 = 8.5e-10
#: per node and state: the model's matrices, the linking, the crossings [s]
NODE_SECONDS_PER_STATE = 1e-5
#: per analysis: the naming, the events, the result [s]
ANALYSIS_SECONDS = 0.05
#: above this many states ``method="auto"`` tracks a reduced model
#: (:data:`propwhirl.analysis.reduced.REDUCED_ABOVE`)
ESTIMATE_REDUCED_ABOVE = 400
#: the reduced model's size is not known before the reduction: estimated as
#: REDUCED_STATES_BASE + REDUCED_STATES_PER_PROPELLER per flexibly mounted propeller (at most
#: the full size): measured 50, 176, 242, 242 and 448 reduced states for 1, 8, 12, 12 and 64
#: propellers (docs/performance.md, issue 20.9)
REDUCED_STATES_BASE = 40
REDUCED_STATES_PER_PROPELLER = 16
#: bytes per point of a study in the parent process: its model variant (≈ 4.8 kB measured
#: with tracemalloc for the wingtip model) and its result row (a dict of 15 columns)
STUDY_POINT_BYTES = 8192

_TIME_UNITS = {"": 1.0, "s": 1.0, "sec": 1.0, "min": 60.0, "m": 60.0, "h": 3600.0,
               "d": 86400.0}


def study_time_limit() -> float:
    """The longest study started without asking [s]: ``PROPWHIRL_STUDY_TIME_LIMIT`` (seconds,
    "90min", "12h", "3d"; "none" or "inf": no limit), else :data:`DEFAULT_STUDY_SECONDS`."""
    text = os.environ.get(STUDY_TIME_ENV, "").strip().lower()
    if not text:
        return DEFAULT_STUDY_SECONDS
    if text in ("none", "inf", "infinite", "unlimited"):
        return math.inf
    m = re.fullmatch(r"([0-9]*\.?[0-9]+(?:e[+-]?[0-9]+)?)\s*([a-z]*)", text)
    if m is None or m.group(2) not in _TIME_UNITS or not float(m.group(1)) > 0:
        raise InputError(f"{STUDY_TIME_ENV} = {text!r} is invalid: give seconds or a number "
                         "with a unit (s, min, h, d), e.g. 12h, or none")
    return float(m.group(1)) * _TIME_UNITS[m.group(2)]


def format_seconds(s: float) -> str:
    """'42 s', '17 min', '3.5 h', '2.9 days'."""
    if s < 90:
        return f"{s:.0f} s"
    if s < 5400:
        return f"{s / 60:.0f} min"
    if s < 2 * 86400:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:,.1f} days"


def effective_states(n_states: int, method: str = "auto", n_propellers: int = 0) -> int:
    """The states the engine tracks: ``n_states``, or for a model that ``method`` reduces
    (``"reduced"``, or ``"auto"`` above :data:`ESTIMATE_REDUCED_ABOVE` states) the estimated
    reduced size (:data:`REDUCED_STATES_BASE` + :data:`REDUCED_STATES_PER_PROPELLER` per
    propeller, at most ``n_states``).  ``"auto"`` here is a method not resolved for a model
    (an estimate from the size alone); :func:`study_estimate` is given the resolved one
    (``analysis.reduced.choose_method``: ``"reduced"`` for every strip-theory wing since issue
    26)."""
    n = int(n_states)
    if method == "reduced" or (method == "auto" and n > ESTIMATE_REDUCED_ABOVE):
        return min(n, REDUCED_STATES_BASE + REDUCED_STATES_PER_PROPELLER * int(n_propellers))
    return n


def analysis_seconds(n_states: int, method: str = "auto", n_propellers: int = 0) -> float:
    """Estimated CPU time [s] of one default analysis (``analyse(model)``) of a model of
    ``n_states`` first-order states on one BLAS thread: :data:`STUDY_NODES` eigen-solutions
    of O(n³) and their O(n) work per node, and :data:`ANALYSIS_SECONDS`; n the
    :func:`effective_states`.  Measured (one thread) against estimated: isolated propeller
    (4 states) 0.03 / 0.05 s; baseline wing of 12 elements (100) 0.14 / 0.12 s; the wingtip
    model (204) 0.38 / 0.42 s; 25 elements and 4 propellers (216) 0.75 / 0.48 s; reduced:
    100/1 (804 states) 0.08 / 0.08 s, 50/8 (432) 0.45 / 0.28 s, 100/12 (848) 1.2 / 0.57 s,
    25 elements and 64 propellers (768) 22 / 16 s.  An estimate within about 2×."""
    n = float(effective_states(n_states, method, n_propellers))
    return ANALYSIS_SECONDS + STUDY_NODES * (EIG_SECONDS_PER_STATE3 * n ** 3
                                             + NODE_SECONDS_PER_STATE * n)


class StudyEstimate:
    """Time and memory of a study of ``n_points`` analyses before it starts.

    seconds: wall-clock [s] on ``processes`` processes (CPU time / processes); cpu_seconds:
    all analyses [s]; per_analysis: one analysis [s] (:func:`analysis_seconds`); bytes: peak
    memory [bytes]: each process's sweep (:func:`sweep_bytes` of :data:`STUDY_NODES` speeds)
    and the points' variants and result rows (:data:`STUDY_POINT_BYTES`).
    """

    def __init__(self, n_points: int, n_states: int, processes: int = 1,
                 method: str = "auto", n_propellers: int = 0) -> None:
        self.n_points, self.n_states = int(n_points), int(n_states)
        self.processes = max(1, int(processes))
        self.per_analysis = analysis_seconds(n_states, method, n_propellers)
        self.cpu_seconds = self.n_points * self.per_analysis
        self.seconds = self.cpu_seconds / min(self.processes, max(self.n_points, 1))
        n = effective_states(n_states, method, n_propellers)
        self.bytes = (min(self.processes, max(self.n_points, 1)) * sweep_bytes(STUDY_NODES, n)
                      + self.n_points * STUDY_POINT_BYTES)

    def text(self) -> str:
        """'250,000 analyses of 204 states: ≈ 1.2 days on 1 process (≈ 0.41 s each), ≈ 80 MiB'"""
        p = self.processes
        return (f"{self.n_points:,} analyses of {self.n_states:,} states: "
                f"≈ {format_seconds(self.seconds)} on {p} process{'es' if p > 1 else ''} "
                f"(≈ {self.per_analysis:.2g} s each), ≈ {format_bytes(self.bytes)}")


def study_estimate(model, n_points: int, processes: int = 1,
                   method: str = "auto") -> StudyEstimate:
    """The :class:`StudyEstimate` of ``n_points`` analyses of variants of ``model`` (their
    size: the model's ``dof_map()``: its states and flexibly mounted propellers).  ``method``:
    the one the analyses run, resolved for the model (the studies and the CLI pass
    ``analysis.reduced.choose_method(model, method)``: a wing's ``"auto"`` is ``"reduced"``);
    an unresolved ``"auto"`` is estimated from the size (:func:`effective_states`)."""
    dm = model.dof_map()
    return StudyEstimate(n_points, dm.n_states, processes, method, len(dm.propellers))


#: an analysis estimated at least this long [s] is announced before it starts (the CLI)
ANALYSIS_NOTICE_SECONDS = 10.0


def analysis_notice(model, method: str = "auto") -> str | None:
    """One line announcing a long analysis of ``model`` before it starts (its states, the
    estimated time and memory: :func:`study_estimate` of one point), or None when it is
    estimated shorter than :data:`ANALYSIS_NOTICE_SECONDS`."""
    est = study_estimate(model, 1, 1, method)
    if est.seconds < ANALYSIS_NOTICE_SECONDS:
        return None
    return (f"an analysis of {est.n_states:,} states: ≈ {format_seconds(est.seconds)}, "
            f"≈ {format_bytes(est.bytes)} (estimated from the model's size)")


def check_study(model, n_points: int, processes: int = 1, *, method: str = "auto",
                cluster: bool = False, progress=None, stream=None) -> StudyEstimate:
    """Refuse a study estimated (:func:`study_estimate`) longer than :func:`study_time_limit`
    (not on a cluster, whose size is unknown here) or larger in memory than
    :func:`memory_limit`, with a one-line InputError giving the estimate; print the
    estimate on stderr (``stream``) before a long one (:data:`STUDY_NOTICE_SECONDS`) when a
    progress bar was asked for (``progress`` True).  Returns the estimate."""
    import sys

    p = processes if isinstance(processes, int) and processes >= 1 else 1   # checked later
    est = study_estimate(model, n_points, 1 if cluster else p, method)
    limit, mem = study_time_limit(), memory_limit()
    if est.bytes > mem:
        raise InputError(f"the study needs {est.text()} (memory limit {format_bytes(mem)}: "
                         f"set {MEMORY_ENV}, or fewer points or processes)")
    if not cluster and est.seconds > limit:
        raise InputError(f"the study of {est.text()} exceeds {format_seconds(limit)} "
                         f"(set {STUDY_TIME_ENV}, e.g. 3d or none, or give fewer points or "
                         "more processes)")
    if progress is True and est.seconds >= STUDY_NOTICE_SECONDS:
        print(f"propwhirl: estimate: {est.text()}", file=stream or sys.stderr)
    return est
