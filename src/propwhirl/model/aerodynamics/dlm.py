"""Generalised aerodynamic forces of the doublet-lattice method on a wing's DOFs (issue 23).

For harmonic motion q(t) = q̂ e^{iωt} at airspeed V and Mach number M, the wing's aerodynamic
generalised forces are Q_aero = ½ ρ V² Q(k, M) q̂, with k = ω b_ref / V the reduced frequency
on the reference semichord (the root semichord, NASTRAN's k = ω c_ref / 2V, as every p-k result
of propwhirl reports it).  Q is built from the panels and spline of
:mod:`propwhirl.model.aerodynamics.dlm_mesh` and PanelAero's AIC matrix (the ``dlm`` extra,
``panelaero.DLM.calc_Qjj``: the steady vortex-lattice part plus the oscillatory doublet-lattice
increment, Rodden's parabolic kernel approximation, the root a plane of symmetry) — on a
planar mesh its equations evaluated on the half-wing's rows only, the parts every k shares
once per Mach column (:class:`Kernel`, :mod:`propwhirl.model.aerodynamics.dlm_kernel`:
PanelAero's AIC to round-off, ~15x faster):

    w_j = S_j q̂ + i k̄ Z_j q̂            normalised normal wash at the collocation points (3/4)
    c_p = Q_jj(k̄, M) w                    pressure coefficients (lift positive up)
    Q(k, M) = −Z_lᵀ diag(A) Q_jj (S_j + i k̄ Z_j)

where Z, S are the spline's displacement (positive down) and chordwise slope
(:func:`~propwhirl.model.aerodynamics.dlm_mesh.spline`) at the collocation points (j) and the force points
on the doublet lines (l, 1/4 panel chord), A the panel areas and **k̄ = ω / V = k / b_ref
[1/m] PanelAero's reduced frequency** (its "classical" ω/U, not NASTRAN's ωc/2U: converted
here, nowhere else).  The minus sign: the generalised load of a force is its work on the
displacement, positive down (Q_h = −L, as the strips' 7.27).  In-plane DOFs and propeller
DOFs get nothing from the panels; the propellers' Houbolt–Reed loads stay as they are (the DLM
replaces only the wing's strip aerodynamics).

Q is tabulated lazily on a grid of k (0, then :data:`K_PER_DECADE` points per decade from
:data:`K_FIRST`) and of Mach (steps of :data:`MACH_STEP` up to :data:`MACH_MAX`), every entry
computed once per geometry and kept in the analysis's :class:`DlmTables` (the last
:data:`CACHE_SIZE` geometries; nothing at module level; with ``PROPWHIRL_DLM_CACHE`` set,
every AIC also on disk, :mod:`propwhirl.model.aerodynamics.dlm_cache`), and interpolated: cubic (Lagrange through the four
nearest k) in k, linear in Mach.  The Mach number is the wing's ``dlm_mach``
(:func:`wing_mach`): by default "speed", V / a of each analysed speed (a matched analysis,
the Mach interpolated between the table's Mach nodes, the speeds beyond Mach
:data:`MACH_MAX` refused), or one fixed number in [0, :data:`MACH_MAX`] for every speed (the
non-matched analysis of most published DLM flutter results; its own column of the tables,
cubic in k only: the AICs of one Mach number).
"""
from __future__ import annotations

import copy
from collections import OrderedDict
from collections.abc import Callable, Iterable
from dataclasses import replace

import numpy as np

from propwhirl import validate as v
from propwhirl.model.aerodynamics import dlm_cache, dlm_kernel
# the Mach limits the Wing checks its dlm_mach against (they live with the field)
from propwhirl.model.structure.wing import DLM_MACH_MAX as MACH_MAX, DLM_MATCHED as MATCHED
from propwhirl.model.aerodynamics.dlm_mesh import PanelMesh
from propwhirl.model.aerodynamics.dlm_surface import DlmSurface, surface_of

#: first non-zero reduced frequency of the tables (on the reference semichord)
K_FIRST = 0.01
#: table points per decade of k (ratio 10^(1/8) ≈ 1.33 between neighbours: Q within ~0.2 %
#: of the computed one, tests/model/test_dlm.py)
K_PER_DECADE = 8
#: Mach step of the tables (linear interpolation between them)
MACH_STEP = 0.05
#: Mach step of the fine columns a matched crossing is converged on (:meth:`DlmAerodynamics.gaf`
#: with ``fine``): linear between them Q is within 2e-7 of max |Q| of the AICs at that very
#: Mach at Mach 0.6 (k 0-1.5), 1.6e-5 at worst (Mach 0.89, k = 1.5; the error falls as the
#: step squared: 6.5e-5 at 0.002; 5e-4 at 0.6 and 2.5e-2 at 0.89 with the tables' 0.05), and
#: crossings within 0.001 of Mach of each other share their columns
MACH_FINE = 0.001
#: geometries whose tables a :class:`DlmTables` keeps (by default)
CACHE_SIZE = 4
#: Mach columns whose :class:`Kernel` (the parts every k shares) a geometry keeps
KERNELS = 2


def _panelaero():
    """PanelAero's DLM module, or an InputError saying how to install it.  Importing it calls
    ``np.seterr(all='ignore')`` (panelaero/DLM.py): the caller's floating-point error state is
    restored, whatever the import does (its calls run inside ``np.errstate``, :meth:`aic`)."""
    saved = np.geterr()
    try:
        from panelaero import DLM
    except ImportError as exc:
        raise v.InputError("aero = 'dlm' needs PanelAero: pip install 'propwhirl[dlm]' "
                           "(or pip install panelaero)") from exc
    finally:
        np.seterr(**saved)
    return DLM


def steady_aic(grid: dict, mach: float) -> np.ndarray:
    """PanelAero's steady vortex-lattice part of the AIC of ``grid`` at ``mach`` (the same
    at every k of one Mach: :meth:`DlmAerodynamics.aic` keeps it for its Mach column)."""
    DLM = _panelaero()
    with np.errstate(all="ignore"):
        return DLM.VLM.calc_Ajj(aerogrid=copy.deepcopy(grid), Ma=float(mach))[0]


def fold(A: np.ndarray, n: int) -> np.ndarray:
    """The right half-wing's rows of a normalwash matrix of the mirrored wing (the right
    half-wing last, ``n`` panels each), folded onto the half-wing: A_RR + A_RL (n, n).  With
    A = [[D, E], [E, D]] (the left panel p the mirror image of the right one),
    Q_RR + Q_RL = −(A_RR + A_RL)⁻¹: the symmetric AIC from half the kernel and an n × n
    inverse.  ``A`` may hold only those rows (n, 2n)."""
    R = A[-n:]
    return R[:, n:] + R[:, :n]


class Kernel:
    """What the symmetric AICs of one Mach column share, computed once: the folded steady
    vortex-lattice part (PanelAero's, the right half-wing's rows:
    :func:`~propwhirl.model.aerodynamics.dlm_kernel.steady_rows`) and, on a planar mesh, the
    k-independent parts of the doublet-lattice kernel on the right half-wing's rows
    (:class:`~propwhirl.model.aerodynamics.dlm_kernel.PlanarKernel`); on a non-planar mesh
    PanelAero's ``calc_Ajj`` of the whole mirrored wing at each k.  :meth:`aic` is the symmetric
    AIC Q_RR + Q_RL (n, n) complex at k̄ = ω/U [1/m]."""

    def __init__(self, grid: dict, n: int, mach: float, planar: bool):
        self.grid, self.n, self.mach = grid, n, float(mach)
        with np.errstate(all="ignore"):        # PanelAero's VLM, the right half-wing's rows
            self.steady = fold(dlm_kernel.steady_rows(grid, self.mach, slice(n, None)), n)
        with np.errstate(all="ignore"):
            self.planar = (dlm_kernel.PlanarKernel(grid, self.mach, slice(n, None)) if planar
                           else None)

    def aic(self, kbar: float) -> np.ndarray:
        kbar = float(kbar)
        with np.errstate(all="ignore"):
            if kbar == 0.0:
                A = self.steady
            elif self.planar is not None:
                A = self.steady + fold(self.planar.increment(kbar), self.n)
            else:
                D = _panelaero().calc_Ajj(aerogrid=copy.deepcopy(self.grid), Ma=self.mach,
                                          k=kbar, method="parabolic")
                A = self.steady + fold(D, self.n)
            return -np.linalg.inv(A)


def symmetric_aics(grid: dict, n: int, mach: float, kbars, planar: bool) -> list[np.ndarray]:
    """The symmetric AICs Q_RR + Q_RL (n, n) complex of the mirrored ``grid`` (both
    half-wings, the right one last, ``n`` panels each) at ``mach`` and each k̄ = ω/U of
    ``kbars`` [1/m] (:class:`Kernel`: one Mach column's shared parts once): a function of its
    arguments alone, so that worker processes compute it (:meth:`DlmAerodynamics.fill`), with
    one BLAS thread each (two workers on two cores: no oversubscription)."""
    from threadpoolctl import threadpool_limits   # lazy: only in a worker process
    with threadpool_limits(limits=1, user_api="blas"):
        kernel = Kernel(grid, n, mach, planar)
        return [kernel.aic(kb) for kb in kbars]


def symmetric_aic(grid: dict, n: int, mach: float, kbar: float,
                  steady: np.ndarray | None = None) -> np.ndarray:
    """PanelAero's AIC of the mirrored ``grid`` (both half-wings, the right one last, ``n``
    panels each) at ``mach`` and k̄ = ω/U ``kbar`` [1/m], folded to the symmetric one of the
    half-wing, Q_RR + Q_RL (n, n) complex, the way PanelAero's ``calc_Qjj`` computes it: the
    whole (2n)² kernel and its inverse (the reference :class:`Kernel` is checked against,
    tests/model/test_dlm_kernel.py), its steady part ``steady`` (:func:`steady_aic` of this
    Mach) when already computed."""
    DLM = _panelaero()
    kbar = float(kbar)
    with np.errstate(all="ignore"):
        A_vlm = steady_aic(grid, mach) if steady is None else steady
        if kbar == 0.0:
            A_dlm = np.zeros((grid["n"], grid["n"]))
        else:
            A_dlm = DLM.calc_Ajj(aerogrid=copy.deepcopy(grid), Ma=float(mach), k=kbar,
                                 method="parabolic")
        Q = -np.linalg.inv(A_vlm + A_dlm)
    return Q[n:, n:] + Q[n:, :n]


#: a fill of at least this many AICs of at least :data:`PARALLEL_PANELS` panels (half-wing)
#: runs on worker processes (:meth:`DlmAerodynamics.fill`): below, starting them costs more
#: than it saves
PARALLEL_AICS = 16
PARALLEL_PANELS = 150


def require_panelaero() -> None:
    """InputError now, before any analysis, when PanelAero is not installed."""
    _panelaero()


def fixed_mach(wing) -> float | None:
    """The wing's fixed doublet-lattice Mach number (its ``dlm_mach`` number), None when it is
    matched (``dlm_mach = "speed"``: V / a of each speed)."""
    m = getattr(wing, "dlm_mach", MATCHED)
    return None if isinstance(m, str) else float(m)


def wing_mach(model, V: float) -> float:
    """The Mach number of ``model``'s doublet-lattice loads at airspeed V [m/s]: its wing's
    (or modal model's) fixed ``dlm_mach``, or V / a (``dlm_mach = "speed"``)."""
    m = fixed_mach(getattr(model, "wing", model))
    return float(V) / model.flight.speed_of_sound if m is None else m


def check_speed_mach(model, V) -> None:
    """InputError, before any analysis, when the doublet-lattice Mach of ``model`` at one of
    the airspeeds V [m/s] is beyond the tables (only possible with ``dlm_mach = "speed"``)."""
    for Vi in np.atleast_1d(np.asarray(V, float)):
        check_mach(wing_mach(model, Vi), float(Vi))


def snap_mach(mach: float) -> float:
    """``mach``, or the Mach of the table node it is within 1e-9 steps of (so that a fixed
    Mach 0.3 uses the node im = 6's own AICs, 6 · 0.05, not another column)."""
    x = float(mach) / MACH_STEP
    return round(x) * MACH_STEP if abs(x - round(x)) < 1e-9 else float(mach)


def check_mach(mach: float, V: float | None = None) -> None:
    """InputError unless 0 <= mach <= :data:`MACH_MAX` (V [m/s] named when given)."""
    if not (np.isfinite(mach) and 0.0 <= mach <= MACH_MAX + 1e-12):
        at = "" if V is None else f" (V = {V:.4g} m/s)"
        raise v.InputError(f"Mach = {mach:.4g}{at} is invalid for aero = 'dlm': the "
                           f"doublet-lattice tables cover Mach 0 to {MACH_MAX:g} (subsonic); "
                           "analyse lower speeds")


class DlmAerodynamics:
    """The doublet-lattice GAFs of one lifting surface and spline: panels, spline, lazily
    filled tables.

    wing: a beam :class:`~propwhirl.model.structure.wing.Wing` (its panels ``n_chord`` x
    ``n_span``, default its own counts) or any model's
    :class:`~propwhirl.model.aerodynamics.dlm_surface.DlmSurface` (a modal model's: its
    planform splined to its modes); b_ref [m]: the semichord of k (default the root
    semichord).  :meth:`gaf` is the interpolated Q(k, M) (n_dof, n_dof) on the spline's DOFs
    (a beam's 3 n_nodes bending–torsion DOFs, root included; the loaded ones ``keep``),
    :meth:`exact` the one computed at (k, M).  ``evaluations`` counts the AIC matrices
    computed (each an (2n)² complex kernel).
    """

    def __init__(self, wing, b_ref: float | None = None, n_chord: int | None = None,
                 n_span: int | None = None):
        surface = (DlmSurface.from_wing(wing, n_chord, n_span)
                   if not isinstance(wing, DlmSurface) else wing)
        self.surface = surface
        self.mesh: PanelMesh = surface.planform.mesh()
        self.b_ref = float(surface.b_ref if b_ref is None else b_ref)
        self.grid = self.mesh.mirrored().aerogrid()         # both half-wings
        self.n_dof = surface.n_dof
        #: the DOFs the panels load (the beam's free ones: root removed; every mode)
        self.keep = surface.keep
        Zj, Sj = surface.spline(self.mesh.points(0.75))
        Zl, _ = surface.spline(self.mesh.points(0.25))
        self._Zj, self._Sj = Zj, Sj
        self._left = -(Zl.T * self.mesh.area[None, :])
        self._table: dict[tuple[int, int], np.ndarray] = {}
        self.evaluations = 0
        #: the disk cache (``PROPWHIRL_DLM_CACHE``, :mod:`propwhirl.model.aerodynamics.dlm_cache`) or None
        self.cache = dlm_cache.cache_dir()
        self._geometry = dlm_cache.geometry_key(self.mesh.mirrored().corners)
        self.cache_hits = 0
        self._fits: dict = {}
        #: whether the mesh is planar (:func:`~propwhirl.model.aerodynamics.dlm_kernel.is_planar`)
        self.planar = dlm_kernel.is_planar(self.grid, slice(self.mesh.n, None))
        #: the :class:`Kernel` of the last :data:`KERNELS` Mach columns computed
        self._kernels: "OrderedDict[float, Kernel]" = OrderedDict()

    # ------------------------------------------------------------------ exact
    def aic(self, mach: float, k: float) -> np.ndarray:
        """The symmetric AIC Q_jj (n, n) complex of the half-wing at Mach and k (on b_ref):
        c_p = Q_jj w for a wash w mirrored on the other half-wing.  PanelAero's ``calc_Qjj``
        (VLM + DLM increment, parabolic kernel) of both halves, k̄ = k / b_ref its ω/U, then
        Q_sym = Q_RR + Q_RL.  (PanelAero's own ``xz_symmetry`` mirrors the panels upside down;
        its DLM then departs from Theodorsen's limit: docs/validation.md.)  With
        ``PROPWHIRL_DLM_CACHE`` an entry with a valid checksum is read instead; the first one
        read is computed again all the same and compared (:func:`dlm_cache.spot_check`)."""
        n = self.mesh.n
        cached = None
        if self.cache is not None:
            cached = dlm_cache.load(self.cache, self._geometry, mach, float(k) / self.b_ref, n)
            if cached is not None and self.cache_hits:   # the first one read: spot-checked
                self.cache_hits += 1
                return cached
        Q = self.kernel(mach).aic(float(k) / self.b_ref)
        self.evaluations += 1
        return self._computed(mach, k, Q, cached)

    def kernel(self, mach: float) -> "Kernel":
        """The :class:`Kernel` of the Mach column ``mach`` (its parts shared by every k),
        built on first use; the last :data:`KERNELS` kept (a matched p-k reads two columns in
        turn)."""
        mach = float(mach)
        if mach in self._kernels:
            self._kernels.move_to_end(mach)
        else:
            self._kernels[mach] = Kernel(self.grid, self.mesh.n, mach, self.planar)
            while len(self._kernels) > KERNELS:
                self._kernels.popitem(last=False)
        return self._kernels[mach]

    def _computed(self, mach: float, k: float, Q: np.ndarray, cached) -> np.ndarray:
        """Q computed at (mach, k): compared with the cache's entry read (the spot check) or
        written to the cache."""
        if cached is not None:                 # InputError when they differ (dlm_cache)
            dlm_cache.spot_check(self.cache, self._geometry, mach, float(k) / self.b_ref,
                                 cached, Q)
            self.cache_hits += 1
        elif self.cache is not None:
            dlm_cache.store(self.cache, self._geometry, mach, float(k) / self.b_ref, Q)
        return Q

    def exact(self, mach: float, k: float, Qjj: np.ndarray | None = None) -> np.ndarray:
        """Q(k, M) (n_dof, n_dof) complex computed at k [-] and Mach (no table), from
        the AIC ``Qjj`` when given (computed elsewhere: :meth:`fill`)."""
        kbar = float(k) / self.b_ref
        Qjj = self.aic(mach, k) if Qjj is None else Qjj
        return self._left @ (Qjj @ (self._Sj + 1j * kbar * self._Zj))

    def fitted(self, key: tuple, make: Callable[[], object]):
        """The rational-function fit of these tables named ``key``
        (:func:`propwhirl.model.aerodynamics.dlm_rfa.column_fit`), ``make()`` on first use and
        kept with the tables (data of this geometry's Q, as its table nodes are)."""
        if key not in self._fits:
            self._fits[key] = make()
        return self._fits[key]

    # ------------------------------------------------------------------ tables
    @staticmethod
    def k_node(i: int) -> float:
        """k of table node i: 0 for i = 0, else K_FIRST · 10^((i − 1)/K_PER_DECADE)."""
        return 0.0 if i == 0 else K_FIRST * 10.0 ** ((i - 1) / K_PER_DECADE)

    def node(self, im: int, ik: int) -> np.ndarray:
        """Q (n_dof, n_dof) of table node (Mach im · MACH_STEP, k :meth:`k_node` (ik)),
        computed once (no interpolation)."""
        return self.column_node(im * MACH_STEP, ik)

    def column_node(self, mach: float, ik: int) -> np.ndarray:
        """Q at k :meth:`k_node` (ik) in the table column of Mach ``mach`` (a fixed Mach's own
        column, or a Mach node's), computed once."""
        key = (float(mach), ik)
        if key not in self._table:
            self._table[key] = self.exact(float(mach), self.k_node(ik))
        return self._table[key]

    def fill(self, nodes: Iterable[tuple[float, int]],
             report: Callable[[int, int], None] | None = None, processes: int = 1) -> int:
        """Compute the table nodes ``nodes`` ((Mach, ik) pairs of :meth:`column_node`) not yet
        computed, in their order, calling ``report(done, total)`` (total: those missing)
        before the first and after each; returns how many were computed.  What an analysis
        calls to report its AICs' progress: the values are :meth:`column_node`'s whatever the
        order.  ``processes`` > 1: the AICs not in the disk cache computed on that many worker
        processes (:func:`symmetric_aic`, the same numbers) when there are at least
        :data:`PARALLEL_AICS` of them on at least :data:`PARALLEL_PANELS` panels."""
        todo = [key for key in dict.fromkeys((float(m), int(ik)) for m, ik in nodes)
                if key not in self._table]
        if report is not None:
            report(0, len(todo))
        done = 0
        if processes > 1 and self.mesh.n >= PARALLEL_PANELS:
            done = self._fill_on_processes(todo, report, processes)
        for mach, ik in todo[done:]:
            self.column_node(mach, ik)
            done += 1
            if report is not None:
                report(done, len(todo))
        return len(todo)

    def _fill_on_processes(self, todo: list[tuple[float, int]], report, processes: int) -> int:
        """The nodes of ``todo`` whose AIC the disk cache does not hold, their AICs on worker
        processes (in ``todo``'s order, as they finish), put in the table; the others are left
        to :meth:`column_node`.  Returns how many of ``todo`` (a prefix once reordered: the
        computed ones first) are done."""
        from concurrent.futures import ProcessPoolExecutor   # lazy: only for big tables
        import multiprocessing

        n = self.mesh.n
        mine = [(m, ik) for m, ik in todo
                if self.cache is None or dlm_cache.load(
                    self.cache, self._geometry, m, self.k_node(ik) / self.b_ref, n) is None]
        if len(mine) < PARALLEL_AICS:
            return 0
        rest = [key for key in todo if key not in set(mine)]
        ctx = multiprocessing.get_context("fork" if "fork" in
                                          multiprocessing.get_all_start_methods() else None)
        columns: dict[float, list[int]] = {}
        for m, ik in mine:                        # one task per Mach column: its kernel once
            columns.setdefault(m, []).append(ik)
        mine[:] = [(m, ik) for m, iks in columns.items() for ik in iks]
        todo[:] = mine + rest
        done = 0
        with ProcessPoolExecutor(max_workers=processes, mp_context=ctx) as pool:
            futures = [(m, iks, pool.submit(symmetric_aics, self.grid, n, m,
                                            [self.k_node(ik) / self.b_ref for ik in iks],
                                            self.planar))
                       for m, iks in columns.items()]
            for i, (mach, iks, fut) in enumerate(futures):
                futures[i] = None             # its AICs released once in the table (n² each)
                for ik, Qjj in zip(iks, fut.result()):
                    Q = self._computed(mach, self.k_node(ik), Qjj, None)
                    self.evaluations += 1
                    self._table[(mach, ik)] = self.exact(mach, self.k_node(ik), Q)
                    done += 1
                    if report is not None:
                        report(done, len(todo))
        return len(mine)

    @property
    def table_nodes(self) -> tuple[tuple[float, int], ...]:
        """The (Mach, k index) of every Q computed so far (:meth:`column_node`), in the order
        computed."""
        return tuple(self._table)

    @property
    def columns(self) -> tuple[float, ...]:
        """The Mach numbers of the table columns computed so far, ascending."""
        return tuple(sorted({m for m, _ in self._table}))

    def _in_k(self, im: int | float, k: float, *, mach: float | None = None) -> np.ndarray:
        """Cubic Lagrange interpolation in k through the four table nodes around k, in the
        column of Mach node ``im`` (or of Mach ``mach`` when given)."""
        return _in_k(self.column_node, self.n_dof, im, k, mach)

    def gaf(self, mach: float, k: float, *, exact_mach: bool = False,
            fine: bool = False) -> np.ndarray:
        """Q(k, M) interpolated from the tables (cubic in k, linear in Mach) [-]; with
        ``exact_mach`` (a wing's fixed ``dlm_mach``) from the column of that very Mach
        (:func:`snap_mach`), cubic in k only: one Mach's AICs, none of its neighbours'; with
        ``fine`` linear in Mach between the columns :data:`MACH_FINE` apart around it (a
        matched crossing's own Mach, its error there)."""
        return _gaf(self.column_node, self.n_dof, mach, k, exact_mach, fine)

    def projected(self, Psi: np.ndarray) -> "ProjectedGaf":
        """The tables projected on the real basis ``Psi`` (n_dof, r): :class:`ProjectedGaf`."""
        return ProjectedGaf(self, Psi)


class ProjectedGaf:
    """Ψᵀ Q(k, M) Ψ (r, r) of a :class:`DlmAerodynamics` ``aero`` on a real basis ``Psi``
    (n_dof, r): every table node read is projected once (kept here, for the one analysis that
    made it), and :meth:`gaf` interpolates the projected nodes exactly as
    :meth:`DlmAerodynamics.gaf` does the full ones — the interpolation is linear in the nodes'
    values, so it commutes with the projection (the p-k sweep on a Galerkin basis,
    :mod:`propwhirl.analysis.pk_basis`)."""

    def __init__(self, aero: DlmAerodynamics, Psi: np.ndarray):
        self.aero, self.Psi = aero, np.asarray(Psi, dtype=float)
        self._nodes: dict[tuple[float, int], np.ndarray] = {}

    def column_node(self, mach: float, ik: int) -> np.ndarray:
        """Ψᵀ Q Ψ of :meth:`DlmAerodynamics.column_node` (mach, ik)."""
        key = (float(mach), ik)
        if key not in self._nodes:
            self._nodes[key] = self.Psi.T @ self.aero.column_node(mach, ik) @ self.Psi
        return self._nodes[key]

    def gaf(self, mach: float, k, *, exact_mach: bool = False,
            fine: bool = False) -> np.ndarray:
        """Ψᵀ Q(k, M) Ψ [-] (:meth:`DlmAerodynamics.gaf`'s interpolation); ``k`` a scalar or
        an array (m,) (then (m, r, r))."""
        return _gaf(self.column_node, self.Psi.shape[1], mach, k, exact_mach, fine)


def _in_k(node: Callable[[float, int], np.ndarray], n: int, im: int | float, k,
          mach: float | None = None) -> np.ndarray:
    """Cubic Lagrange interpolation in k of the (n, n) table nodes ``node(mach, ik)`` through
    the four around k, in the column of Mach node ``im`` (or of Mach ``mach`` when given);
    ``k`` a scalar, or an array (m,) of reduced frequencies interpolated together (m, n, n):
    the p-k iteration of several modes at once."""
    mach = im * MACH_STEP if mach is None else mach
    kk = np.atleast_1d(np.asarray(k, dtype=float))
    above = np.maximum(kk, K_FIRST) / K_FIRST
    i = np.where(kk < K_FIRST, 0,
                 1 + np.floor(np.log10(above) * K_PER_DECADE + 1e-12).astype(int))
    idx = np.maximum(0, i - 1)[:, None] + np.arange(4)      # (m, 4): the nodes around each k
    uniq, pos = np.unique(idx, return_inverse=True)
    pos = pos.reshape(idx.shape)
    ks = np.array([DlmAerodynamics.k_node(int(j)) for j in uniq])[pos]
    nodes = np.stack([node(mach, int(j)) for j in uniq])
    out = np.zeros((kk.size, n, n), complex)
    for a in range(4):
        w = None
        for b in range(4):
            if b != a:
                f = (kk - ks[:, b]) / (ks[:, a] - ks[:, b])
                w = f if w is None else w * f
        out += w[:, None, None] * nodes[pos[:, a]]
    return out if np.ndim(k) else out[0]


def _gaf(node: Callable[[float, int], np.ndarray], n: int, mach: float, k,
         exact_mach: bool, fine: bool) -> np.ndarray:
    """Q(k, M) from the table nodes ``node(mach, ik)`` (:meth:`DlmAerodynamics.gaf`); ``k``
    a scalar or an array (m,) (then (m, n, n))."""
    check_mach(mach)
    k = max(float(k), 0.0) if np.ndim(k) == 0 else np.maximum(np.asarray(k, float), 0.0)
    if exact_mach:
        return _in_k(node, n, 0, k, snap_mach(mach))
    if fine:
        x = float(mach) / MACH_FINE
        i = int(np.floor(x + 1e-9))
        t = x - i
        Q = _in_k(node, n, 0, k, snap_mach(i * MACH_FINE))
        if t > 1e-9:
            Q = (1 - t) * Q + t * _in_k(node, n, 0, k, snap_mach((i + 1) * MACH_FINE))
        return Q
    x = mach / MACH_STEP
    im = min(int(np.floor(x + 1e-12)), int(round(MACH_MAX / MACH_STEP)))
    t = x - im
    Q = _in_k(node, n, im, k)
    if t > 1e-9:
        Q = (1 - t) * Q + t * _in_k(node, n, im + 1, k)
    return Q


def geometry_key(wing) -> tuple:
    """What a wing's (or any model's surface's) doublet-lattice tables depend on
    (:attr:`DlmSurface.key`: a beam's nodes' y, b, a and panel counts; a modal model's
    planform and spline): two with the same key share their tables in a :class:`DlmTables`."""
    return surface_of(wing).key


class DlmTables:
    """The doublet-lattice tables an analysis owns (issue 33 item 8): per wing geometry
    (:func:`geometry_key`) its :class:`DlmAerodynamics` — the AICs' Q(k, M) table nodes and the
    rational-function fits of them — for the last ``size`` geometries used.

    ``analyse(model)`` creates one (or uses the one it is given, ``dlm_tables=``) and passes it
    wherever its doublet-lattice loads are evaluated (the model's assembly, the p-k method);
    a study passes one to all its analyses, so the variants of one planform compute their AICs
    once.  Nothing is kept at module level: two analyses with different tables share no entry.
    Pickled (a study's tables sent to a worker process) it travels empty: each process fills
    its own; ``PROPWHIRL_DLM_CACHE`` shares the AICs across processes
    (:mod:`propwhirl.model.aerodynamics.dlm_cache`).  ``processes``: worker processes an
    analysis may compute a big first batch of AICs on (:meth:`DlmAerodynamics.fill`); None
    (default): two where the machine has two cores and this is not itself a worker process
    (a study's pool), else one.

    Examples
    --------
    >>> tables = DlmTables()
    >>> len(tables)
    0
    """

    def __init__(self, size: int = CACHE_SIZE, processes: int | None = None):
        self.size = v.integer_at_least("size", size, 1)
        self._processes = None if processes is None else v.integer_at_least(
            "processes", processes, 1)
        self._aero: "OrderedDict[tuple, DlmAerodynamics]" = OrderedDict()

    @property
    def processes(self) -> int:
        """Worker processes for a big fill (class docstring)."""
        if self._processes is not None:
            return self._processes
        import multiprocessing   # lazy: only asked before a fill
        import os
        main = multiprocessing.parent_process() is None
        return min(2, os.cpu_count() or 1) if main else 1

    def __len__(self) -> int:
        """Geometries held."""
        return len(self._aero)

    def __contains__(self, wing) -> bool:
        """Whether the tables of ``wing``'s geometry are held."""
        return geometry_key(wing) in self._aero

    def __reduce__(self):
        return (DlmTables, (self.size, self._processes))     # to another process: empty

    def __repr__(self) -> str:
        return f"DlmTables({len(self)} of at most {self.size} geometries)"

    def aero(self, wing) -> DlmAerodynamics:
        """The :class:`DlmAerodynamics` of ``wing``'s geometry (a beam wing, a model or a
        :class:`~propwhirl.model.aerodynamics.dlm_surface.DlmSurface`: its panel counts, root
        semichord, spline), created on first use; the least recently used geometry is dropped
        beyond :attr:`size`."""
        surface = surface_of(wing)
        key = surface.key
        if key in self._aero:
            self._aero.move_to_end(key)
            return self._aero[key]
        aero = DlmAerodynamics(surface)
        self._aero[key] = aero
        while len(self._aero) > self.size:
            self._aero.popitem(last=False)
        return aero


def check_tables(tables) -> DlmTables:
    """``tables`` when it is a :class:`DlmTables`, a new one when None, else an InputError."""
    if tables is None:
        return DlmTables()
    if not isinstance(tables, DlmTables):
        raise v.InputError(f"dlm_tables = {tables!r:.60} is invalid: must be None or a "
                           "propwhirl.model.aerodynamics.dlm.DlmTables")
    return tables


def dlm_aerodynamics(wing, tables: DlmTables | None = None) -> DlmAerodynamics:
    """The :class:`DlmAerodynamics` of ``wing`` (a beam wing, a model or a
    :class:`~propwhirl.model.aerodynamics.dlm_surface.DlmSurface`) in ``tables`` (shared by
    every one of the same geometry there); without tables a new one, filled by its caller
    alone."""
    surface = surface_of(wing)
    return DlmAerodynamics(surface) if tables is None else tables.aero(surface)


def pk_system_dlm(model, V: float, k_min: float, tables: DlmTables | None = None,
                  own_mach: bool = False, basis: tuple | None = None, dry=None):
    """ω ↦ (M, C, K) of the p-k equation of a PropellerWing with doublet-lattice wing
    aerodynamics at airspeed V [m/s]: its structure and propellers (the model's own second-order
    system with the wing aerodynamics off), minus the DLM loads in the p-k form
    K_a = ½ρV² Re Q(k, M), C_a = ½ρV² Im Q(k, M) / ω (exact at p = iω), k = ω b_ref / V
    (raised to ``k_min``), M the wing's Mach at this speed (:func:`wing_mach`: V / a, or its
    fixed ``dlm_mach``), Q read from ``tables`` (the analysis's; None: new ones).  Q is
    interpolated in Mach between the table's Mach nodes (linear), or with ``own_mach`` between
    the fine columns :data:`MACH_FINE` apart around this Mach (what a matched crossing is
    converged with, :func:`propwhirl.analysis.pk_crossings.matched_crossing`); at a fixed ``dlm_mach``
    always from the AICs of that very Mach, cubic in k only.  ``basis``: (Φ, G), a Galerkin
    basis Φ (n, r) over the model's DOFs and G the tables projected on it
    (:meth:`DlmAerodynamics.projected` of Φ's wing rows on the spline's DOFs): the system
    projected, Φᵀ (M, C, K) Φ (r, r), Q read from G, for one ω or an array (m,) of them
    (then (m, r, r)).  ``dry``: the model's assembly with
    its wing aerodynamics off, built once by the analysis (None: built here;
    :func:`propwhirl.model.frequency_domain.dry_assembly`)."""
    mach = wing_mach(model, V)
    surface = surface_of(model)
    exact = fixed_mach(surface) is not None
    check_mach(mach, V)
    dry = (replace(model, wing_aero=False) if dry is None else dry).second_order(np.array([V]))
    aero = dlm_aerodynamics(surface, tables)
    keep = aero.keep
    q = 0.5 * model.flight.density * V ** 2
    structure = (dry.S1[0], dry.S2[0], dry.S3[0])
    b = aero.b_ref
    if basis is not None:
        Phi, projected = basis
        structure = tuple(Phi.T @ X @ Phi for X in structure)

        def reduced(omega):
            k = np.maximum(np.asarray(omega, float) * b / V, k_min)   # one or several ω
            Q = q * projected.gaf(mach, k, exact_mach=exact, fine=own_mach)
            M, C, K = structure
            w = (k * V / b)[..., None, None]
            return (M if Q.ndim == 2 else np.broadcast_to(M, Q.shape), C - Q.imag / w,
                    K - Q.real)

        return reduced

    def matrices(omega: float):
        k = max(float(omega) * b / V, k_min)
        Q = q * aero.gaf(mach, k, exact_mach=exact, fine=own_mach)[np.ix_(keep, keep)]
        M, C, K = (np.array(X, dtype=float) for X in structure)
        n = keep.size
        C[:n, :n] -= Q.imag / (k * V / b)
        K[:n, :n] -= Q.real
        return M, C, K

    return matrices


def strip_twin(model):
    """The model with strip aerodynamics on its wing (``aero = "strip"``: a beam wing's, a
    modal model's strips), the model itself when it has them: the finite-state model a
    doublet-lattice p-k analysis tracks and names its modes with, starts its p-k roots from
    and reports beside its events."""
    wing = getattr(model, "wing", None)
    if wing is None:
        return model.with_(aero="strip") if getattr(model, "aero", "strip") == "dlm" else model
    if wing.aero != "dlm":
        return model
    return model.with_(wing=replace(wing, aero="strip"))
