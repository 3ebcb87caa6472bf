"""Reduced-order models of large wings: in-vacuo modes, static correction, lag-state basis.

A distributed-propeller wing of 100–200 elements has 800–1650 states; a dense
eigendecomposition at each speed costs O(n³).  The analysis needs only the roots that can reach
the imaginary axis, and those live in a low-frequency band.  :func:`modal_basis` builds a
Galerkin basis for that band and :class:`ReducedModel` projects the model on it, block by block
(:meth:`propwhirl.model.blocks.BlockSystem.project`: cost linear in the number of elements):

1. **In-vacuo modes** of the non-rotating structure (K φ = ω² M φ, M-orthonormal).  The
   *reference frequency* f_ref is the highest of: every propeller-dominated mode (pitch/yaw
   kinetic energy > ½), the second bending-dominated and the first torsion-dominated wing mode —
   the modes of classical bending–torsion flutter and of whirl flutter — and, on a wing that
   bends in its plane, the first chordwise-dominated mode (the "chord" mode of the whirl-flutter
   literature).  Every mode with
   f ≤ f_c = ``factor`` · f_ref (default :data:`CUTOFF_FACTOR` = 3) is kept.
2. **Static correction** (modal acceleration): the static responses K⁻¹ ΔK(V) Φ to the
   aerodynamic stiffness ΔK = S3(V) − K of the kept modes at the middle and the top of the speed
   range are added, and the whole set is made M-orthonormal (Rayleigh–Ritz, dependent vectors
   dropped).  It restores the quasi-static deformation the truncated modes would carry (what
   divergence needs).
3. **Lag states**: the aerodynamic lag states of all nodes (eq. 7.54–7.56) are projected on a
   spanwise basis: per lag state of a node, the span of the lag inputs (Wv Φ, Wq Φ), the lag
   loads (S4ᵀ Φ) and one Krylov step (Ww applied to them) at the ends of the speed range,
   compressed by an SVD (singular values below :data:`LAG_SVD_TOL` = 1e-6 of the largest dropped; on the 200-element, 12-propeller wing 1e-8, 1e-6, 1e-5 and 1e-4 give lag bases of 188, 146, 118 and 102 states and the same crossings to 0.0005 m/s).  For a
   wing of constant chord the span of the inputs is invariant under Ww and the projection is
   exact; for a tapered wing it is a Galerkin approximation.

The reduced model's roots are approximations: :mod:`propwhirl.engine.correction` converges every
crossing it finds on the full-order sparse pencil, and the shift it makes is reported as the
truncation error (``docs/validation.md`` shows the cut-off's convergence and the comparison
with the dense full-order analysis).
"""
from __future__ import annotations

from dataclasses import InitVar, dataclass, field

import numpy as np
import scipy.linalg as sla

from propwhirl import validate as v
from propwhirl.model.blocks import BlockSystem, RecentBlocks
from propwhirl.model.pencil import SparsePencil
from propwhirl.model.statespace import SecondOrder, rate_label, state_matrix

#: f_c = CUTOFF_FACTOR × the reference frequency (module docstring, step 1)
CUTOFF_FACTOR = 3.0
#: relative singular-value threshold of the lag-state basis (step 3)
LAG_SVD_TOL = 1e-6
#: relative eigenvalue threshold of the M-Gram matrix below which a basis vector is dependent
GRAM_TOL = 1e-12


@dataclass(frozen=True)
class ModalBasis:
    """The Galerkin basis of a reduced model (module docstring).

    Phi:          (n_q, r) M-orthonormal Ritz vectors over the model's full DOFs (zero rows at
                  the clamped root), sorted by frequency.
    frequencies_hz: (r,) their Ritz frequencies [Hz].
    Q:            (n_w, L) orthonormal lag-state basis over the full lag states, or None.
    cutoff_hz:    f_c [Hz]; reference_hz: f_ref [Hz]; n_modes: in-vacuo modes kept (the rest
                  of the r vectors come from the static correction).
    in_vacuo_hz:  the frequencies of every in-vacuo mode [Hz] (what the cut-off was chosen from).
    """

    Phi: np.ndarray
    frequencies_hz: np.ndarray
    Q: np.ndarray | None
    cutoff_hz: float
    reference_hz: float
    n_modes: int
    in_vacuo_hz: np.ndarray = field(repr=False)

    @property
    def r(self) -> int:
        return self.Phi.shape[1]

    @property
    def L(self) -> int:
        return 0 if self.Q is None else self.Q.shape[1]


def _full_rows(n_full: int, keep: np.ndarray, X: np.ndarray) -> np.ndarray:
    out = np.zeros((n_full,) + X.shape[1:])
    out[keep] = X
    return out


def cutoff(assembly, f: np.ndarray, shapes: np.ndarray, M: np.ndarray,
           factor: float = CUTOFF_FACTOR, cutoff_hz: float | None = None) -> tuple[float, float]:
    """(f_ref, f_c) [Hz]: the reference frequency (module docstring, step 1) of the in-vacuo
    modes of ``assembly``'s model (frequencies ``f`` [Hz], ``shapes`` over its DOFs, mass
    ``M``) and the cut-off f_c = ``factor`` · f_ref, or ``cutoff_hz`` when given.  The one
    choice of the modes a reduced model keeps (strips: :func:`modal_basis`; doublet lattice:
    :func:`propwhirl.model.dlm_modal.modal_roger`)."""
    v.positive("factor", factor)
    ref = _reference_frequency(assembly, f, shapes, M)
    return ref, (factor * ref if cutoff_hz is None
                 else float(v.positive("cutoff_hz", cutoff_hz, "Hz")))


def _reference_frequency(assembly, f: np.ndarray, shapes: np.ndarray, M: np.ndarray) -> float:
    """f_ref [Hz] (module docstring, step 1) from the in-vacuo modes (shapes over kept DOFs)."""
    groups = assembly.dof_map().groups()
    e = np.real(shapes * (M @ shapes))
    e = e / np.sum(e, axis=0)
    share = {g: e[np.asarray(ix, dtype=int)].sum(axis=0) for g, ix in groups.items()}
    zero = np.zeros(f.size)
    prop = share.get("pitch", zero) + share.get("yaw", zero)
    bend, tors = share.get("bending", zero), share.get("torsion", zero)
    chord = share.get("chordwise", zero)        # in-plane bending (wing.EI_chordwise)
    cands = list(f[prop > 0.5])
    wing = prop <= 0.5
    b = f[wing & (bend >= tors) & (bend >= chord)]
    t = f[wing & (tors > bend) & (tors >= chord)]
    c = f[wing & (chord > bend) & (chord > tors)]
    cands += list(b[:2]) + list(t[:1]) + list(c[:1])
    return float(max(cands)) if cands else float(f[min(5, f.size - 1)])


def modal_basis(model, speeds, *, cutoff_hz: float | None = None,
                factor: float = CUTOFF_FACTOR) -> ModalBasis:
    """The reduced basis of ``model`` (a PropellerWing) for the airspeeds ``speeds`` [m/s].

    ``cutoff_hz`` overrides f_c; ``factor`` scales the reference frequency (module docstring).
    """
    return _modal_basis(model.assembly(), speeds, cutoff_hz, factor)[0]


def dof_basis(model, speeds) -> np.ndarray:
    """Φ of :func:`modal_basis` (the default's cut-off) over the model's kept DOFs (n_dof, r),
    M-orthonormal: the Galerkin basis the p-k sweep of a beam wing iterates on
    (:mod:`propwhirl.analysis.pk_basis`)."""
    basis, blocks = _modal_basis(model.assembly(), speeds, None, CUTOFF_FACTOR)
    return basis.Phi[blocks.keep_q]


def _modal_basis(assembly, speeds, cutoff_hz: float | None, factor: float,
                 structure: tuple[np.ndarray, np.ndarray] | None = None
                 ) -> tuple[ModalBasis, BlockSystem]:
    """:func:`modal_basis` of the model of ``assembly`` (its
    :class:`~propwhirl.model.systems.PropellerWingAssembly`) and its blocks at three speeds of
    the range (their constant parts are those of every speed).  ``structure``: the structural
    mass and stiffness (M, K) over the kept DOFs (aerodynamics off: they depend on neither the
    airspeed nor the rotational speed), if already evaluated."""
    V = np.asarray(speeds, dtype=float)
    if structure is None:
        quiet = assembly.with_switches(rotating=False, wing_aero=False, propeller_aero=False)
        S = quiet.second_order_blocks(V[:1]).dense()
        structure = S.S1[0], S.S3[0]
    M, K = structure
    w2, shapes = sla.eigh(K, M)
    f_all = np.sqrt(np.abs(w2)) / (2 * np.pi)
    ref, fc = cutoff(assembly, f_all, shapes, M, factor, cutoff_hz)
    n_keep = max(int(np.sum(f_all <= fc)), min(6, f_all.size))
    Phi_c = shapes[:, :n_keep]
    # static correction at the middle and the top of the range; the lag basis from the first
    # and the last speed: one evaluation of the blocks at the three speeds
    Vs = np.array([V[0], 0.5 * (V[0] + V[-1]), V[-1]])
    blocks = assembly.second_order_blocks(Vs)
    S3 = blocks.matrix("S3")
    cho = sla.cho_factor(K)
    X = [sla.cho_solve(cho, (S3[t] - K) @ Phi_c) for t in ([1, 2] if V[-1] > V[0] else [2])]
    B = np.hstack([Phi_c] + X)
    # a zero static correction (a mode without aerodynamic stiffness, e.g. the propeller's
    # with propeller_aero off) adds nothing: dropped before the normalisation
    norm2 = np.einsum("ij,ij->j", B, M @ B)
    B = B[:, norm2 > GRAM_TOL * norm2.max()]
    for _ in range(2):                    # M-orthonormal, dependent vectors dropped; twice,
        B = B / np.sqrt(np.einsum("ij,ij->j", B, M @ B))     # for the rounding of the first
        g, U = sla.eigh(B.T @ M @ B)
        ok = g > GRAM_TOL * g.max()
        B = B @ (U[:, ok] / np.sqrt(g[ok]))
    k2, U2 = sla.eigh(B.T @ K @ B)
    Phi = B @ U2
    freq = np.sqrt(np.abs(k2)) / (2 * np.pi)
    Phi_full = _full_rows(blocks.n_q, blocks.keep_q, Phi)
    Q = _lag_basis(blocks, Phi_full, [0, 2])
    return ModalBasis(Phi_full, freq, Q, float(fc), ref, n_keep, f_all), blocks


def _lag_basis(b: BlockSystem, Phi: np.ndarray, at: list[int]) -> np.ndarray | None:
    """Orthonormal spanwise basis of the lag states (module docstring, step 3) from the
    blocks at the speeds ``at`` (indices into ``b.V``)."""
    lg = b.lag
    if lg is None or b.keep_w.size == 0:
        return None
    P = Phi[lg.qrows]                                            # (nb, kq, r)
    U_in = [np.einsum("vbkl,blr->vbkr", W[at], P) for W in (lg.Wv, lg.Wq)]
    U_out = [np.einsum("vbkl,bkr->vblr", lg.S4[at], P)]
    U = np.concatenate(U_in + U_out, axis=-1)                    # (nV, nb, kw, c)
    U = np.concatenate([U, np.einsum("vbkl,vblc->vbkc", lg.Ww[at], U)], axis=-1)
    keep_node = np.isin(lg.wrows[:, 0], b.keep_w)
    U = U[:, keep_node]                                          # (nV, nb', kw, c)
    cols = np.moveaxis(U, 1, 0).reshape(U.shape[1], -1)         # nodes × (speeds, kw, c)
    norm = np.linalg.norm(cols, axis=0)
    cols = cols[:, norm > 0] / norm[norm > 0]
    u, s, _ = np.linalg.svd(cols, full_matrices=False)
    Psi = u[:, s > LAG_SVD_TOL * s[0]]                            # (nb', d)
    kw, d = lg.wrows.shape[1], Psi.shape[1]
    Q = np.zeros((b.n_w, kw * d))
    rows = lg.wrows[keep_node]
    for j in range(kw):
        Q[rows[:, j], j * d:(j + 1) * d] = Psi
    return Q


@dataclass(frozen=True)
class ReducedModel:
    """A PropellerWing projected on a :class:`ModalBasis`: state z = [η, η̇, ζ] (r, r, L).

    ``assembly`` is the model's :class:`~propwhirl.model.systems.PropellerWingAssembly`
    (built once by :func:`reduce`; every evaluation of the reduced model evaluates it);
    ``recent`` the last few of its evaluations at the model's own rotational speeds
    (:class:`~propwhirl.model.blocks.RecentBlocks`), for the speeds one analysis asks for
    again — a reduced model is made for one analysis.

    ``state_matrix(V)`` is the reduced A(V) (the one builder,
    :func:`propwhirl.model.statespace.state_matrix`); :attr:`lift` maps reduced state vectors to
    the full state [q, q̇, w] of ``model`` (q = Φη, q̇ = Φη̇, w = Qζ); :meth:`pencil` is the
    full-order sparse pencil of one speed, for the correction of crossings.
    """

    assembly: object
    basis: ModalBasis
    #: the model's blocks at any speed, for the constant parts (default: evaluated at 1 m/s)
    blocks: InitVar[BlockSystem | None] = None
    recent: RecentBlocks = field(default_factory=RecentBlocks, repr=False, compare=False)
    #: Φᵀ(M, C, K)Φ of the speed-independent parts, and the kept DOFs and lag states
    _const: tuple = field(init=False, repr=False, compare=False)
    _keep: tuple = field(init=False, repr=False, compare=False)
    #: the full-order pencil's sparsity pattern and constant part (:meth:`pencil`)
    _pencil: SparsePencil = field(init=False, repr=False, compare=False)

    def __post_init__(self, blocks: BlockSystem | None) -> None:
        b = self.assembly.second_order_blocks(np.array([1.0])) if blocks is None else blocks
        P = self.basis.Phi
        object.__setattr__(self, "_const", tuple(P.T @ X @ P for X in (b.M, b.C, b.K)))
        object.__setattr__(self, "_keep", (b.keep_q, b.keep_w))
        object.__setattr__(self, "_pencil", SparsePencil.of(b))

    @property
    def model(self):
        """The model that was reduced."""
        return self.assembly.model

    @property
    def name(self) -> str:
        return self.assembly.model.name

    @property
    def n_states(self) -> int:
        return 2 * self.basis.r + self.basis.L

    def labels(self) -> tuple[str, ...]:
        q = tuple(f"Ritz vector {i + 1}" for i in range(self.basis.r))
        return q + tuple(rate_label(s) for s in q) + tuple(
            f"lag basis {i + 1}" for i in range(self.basis.L))

    @property
    def displacement(self) -> np.ndarray:
        mask = np.zeros(self.n_states, dtype=bool)
        mask[: self.basis.r] = True
        return mask

    def second_order(self, V, omega=None) -> SecondOrder:
        """The projected second-order system at airspeeds V [m/s] (array)."""
        b = self._blocks(V, omega)
        S1, S2, S3, S4, Ww, Wv, Wq = b.project(self.basis.Phi, self.basis.Q, self._const)
        q = self.labels()[: self.basis.r]
        return SecondOrder(S1, S2, S3, S4, Ww, Wv, Wq, q, self.labels()[2 * self.basis.r:])

    def state_matrix(self, V, **options) -> np.ndarray:
        """The reduced A(V), shape (nV, 2r + L, 2r + L)."""
        V = np.atleast_1d(np.asarray(V, dtype=float))
        return state_matrix(self.second_order(V, **options), V)

    @property
    def dof_basis(self) -> np.ndarray:
        """Φ over the model's kept DOFs (n, r): q = Φ η."""
        return self.basis.Phi[self._keep[0]]

    @property
    def lift(self) -> np.ndarray:
        """(n_full_states, 2r + L): full state [q, q̇, w] of a reduced state [η, η̇, ζ]."""
        kq, kw = self._keep
        P = self.basis.Phi[kq]
        Q = None if self.basis.Q is None else self.basis.Q[kw]
        n, r, L = kq.size, self.basis.r, self.basis.L
        out = np.zeros((2 * n + kw.size, 2 * r + L))
        out[:n, :r] = P
        out[n:2 * n, r:2 * r] = P
        if Q is not None:
            out[2 * n:, 2 * r:] = Q
        return out

    def pencil(self, V: float):
        """The full-order sparse pencil (F, E) at one airspeed V [m/s]
        (:meth:`propwhirl.model.blocks.BlockSystem.pencil`'s matrices, from the pattern built
        with the model: :class:`~propwhirl.model.pencil.SparsePencil`)."""
        return self._pencil.at(self._blocks(np.array([float(V)]), None))

    def _blocks(self, V, omega) -> BlockSystem:
        """The assembly's blocks at V (checked), from :attr:`recent` at the model's own
        rotational speeds."""
        if omega is not None:
            return self.assembly.second_order_blocks(V, omega)
        V = np.atleast_1d(np.asarray(V, dtype=float))
        return self.recent.get(V) or self.recent.add(self.assembly.second_order_blocks(V))


def reduce(model, speeds, *, cutoff_hz: float | None = None,
           factor: float = CUTOFF_FACTOR, assembly=None,
           structure: tuple[np.ndarray, np.ndarray] | None = None) -> ReducedModel:
    """The :class:`ReducedModel` of ``model`` for ``speeds`` [m/s] (:func:`modal_basis`).
    ``assembly``: ``model.assembly()`` if already built; ``structure``: its structural (M, K)
    over the kept DOFs if already evaluated (an analysis's
    :class:`~propwhirl.analysis.modes.InVacuo`).

    Examples
    --------
    The wingtip propeller-wing of §10.1 (204 states): f_ref is wing 2 (17.74 Hz), so every
    in-vacuo mode up to 53.2 Hz is kept (7), plus 4 static-correction vectors, and 28 lag states.

    >>> import numpy as np
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> R = reduce(wingtip_propeller_wing(), np.arange(1.0, 351.0, 10.0))
    >>> round(R.basis.reference_hz, 2), round(R.basis.cutoff_hz, 2), R.basis.n_modes
    (17.74, 53.23, 7)
    >>> R.basis.r, R.basis.L, R.n_states
    (11, 28, 50)
    """
    assembly = model.assembly() if assembly is None else assembly
    basis, blocks = _modal_basis(assembly, speeds, cutoff_hz, factor, structure)
    recent = RecentBlocks()
    recent.add(blocks)                  # the basis's three speeds (the first, for one)
    return ReducedModel(assembly, basis, blocks, recent)
