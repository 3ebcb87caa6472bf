"""The modal Roger state space of a doublet-lattice wing: what ``analyse(model)`` tracks by
default on a wing with ``aero = "dlm"`` (issue 37, item 1).

The full Roger state space (:func:`propwhirl.model.aerodynamics.dlm_rfa.second_order`) puts the fitted
doublet-lattice loads on every wing DOF, so every structural mode of the beam carries them —
also the modes whose reduced frequency k = ω b_ref / V lies far beyond the fit (k ≤
:data:`~propwhirl.model.aerodynamics.dlm_rfa.K_MAX`) and beyond the panels' own validity (the 0.08 V/f
guideline: k ≲ n_chordwise / 4).  There the fit extrapolates Q, and the doublet lattice itself
is no better: on the Goland wing (4 × 7 panels) the computed Q(k) of every mode feeds energy
into the mode at k = 10 (docs/validation.md, "The modal Roger state space").  Such a mode,
undamped structurally, then shows as "unstable from the start of the range" at hundreds of Hz.

Here the structure is first reduced to its in-vacuo modes below the cut-off of the reduced
strip models (:func:`propwhirl.model.reduction.cutoff`: three times the highest of the second
bending, first torsion, first chordwise and every propeller-dominated mode; at least six
modes, the p-k method's :data:`~propwhirl.analysis.pk.WING_MODES`), and the Roger state space
is built on those modes: with q = Φ η (Φ M-orthonormal over the model's DOFs, propellers
included) and the wing rows Φ_w, the lag states of the fit become x_l = Φ_w z_l with

    ż_l = η̇ − (V/b) β_l z_l,

which is the full Roger system's own lag equation restricted to q = Φ η: the modal system is
the Galerkin projection of the full one (the same fit, the same lags: Φ_wᵀ A_i Φ_w), and
:attr:`ModalRoger.lift` maps its states to the full Roger state exactly.  The modes above the
cut-off are left out of the state space; they are not left out of the answer: every crossing
the modal state space finds is converged by the p-k method on the whole structure with Q(k)
itself at the mode's own k (:func:`propwhirl.analysis.modal_dlm.modal_dlm_analysis`), where
the truncated modes respond to the loads quasi-statically, as in the p-k's own matrices.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from propwhirl import validate as v
from propwhirl.model.aerodynamics.dlm_surface import surface_of
from propwhirl.model.aerodynamics.dlm_rfa import (DEFAULT_LAGS, b_ref, coefficients, fit_ks,
                                                  roger_system, tracking_ks)
from propwhirl.model.reduction import CUTOFF_FACTOR, cutoff
from propwhirl.model.statespace import SecondOrder, rate_label, state_matrix

#: modes a modal Roger state space keeps at least (the p-k method's
#: :data:`~propwhirl.analysis.pk.WING_MODES`)
MIN_MODES = 6


@dataclass(frozen=True)
class ModalRoger:
    """The Roger state space of a doublet-lattice wing on its in-vacuo modes below a cut-off.

    ``assembly``: the model's :class:`~propwhirl.model.systems.PropellerWingAssembly` (built
    once per analysis, with the analysis's doublet-lattice tables, ``assembly.dlm_tables``);
    ``Phi`` (n, r): the kept in-vacuo modes over the model's DOFs
    (M-orthonormal); ``frequencies_hz`` (r,) theirs [Hz]; ``cutoff_hz`` f_c and
    ``reference_hz`` f_ref [Hz] (:func:`~propwhirl.model.reduction.cutoff`); ``in_vacuo_hz``
    every in-vacuo frequency [Hz]; ``n_w`` the free wing DOFs the doublet lattice loads (the
    first ``n_w`` DOFs); ``dry_labels`` the lag states of the model without wing aerodynamics.

    State z = [η, η̇, w, z_1 … z_L] (r, r, n_dry_lags, L r).
    """

    assembly: object
    Phi: np.ndarray
    frequencies_hz: np.ndarray
    cutoff_hz: float
    reference_hz: float
    in_vacuo_hz: np.ndarray = field(repr=False)
    n_w: int = 0
    #: the labels of the lag states of the model without wing aerodynamics (m₀ of them)
    dry_labels: tuple[str, ...] = ()
    lags: tuple[float, ...] = DEFAULT_LAGS
    #: the reduced frequencies of its fits (None: :func:`~propwhirl.model.aerodynamics.dlm_rfa.tracking_ks`)
    ks: tuple[float, ...] | None = None

    @property
    def n_dry_lags(self) -> int:
        return len(self.dry_labels)

    @property
    def model(self):
        """The model whose state space this is."""
        return self.assembly.model

    @property
    def name(self) -> str:
        return self.assembly.model.name

    @property
    def r(self) -> int:
        """Modes kept."""
        return self.Phi.shape[1]

    @property
    def n_states(self) -> int:
        return 2 * self.r + self.n_dry_lags + len(self.lags) * self.r

    def labels(self) -> tuple[str, ...]:
        """State labels: "mode i", their rates, the dry lag states, "mode i lag l"."""
        q = tuple(f"mode {i + 1}" for i in range(self.r))
        lag = tuple(f"mode {i + 1} lag {l + 1}" for l in range(len(self.lags))
                    for i in range(self.r))
        return q + tuple(rate_label(s) for s in q) + self.dry_labels + lag

    @property
    def displacement(self) -> np.ndarray:
        mask = np.zeros(self.n_states, dtype=bool)
        mask[: self.r] = True
        return mask

    @property
    def dof_basis(self) -> np.ndarray:
        """Φ over the model's DOFs (n, r): q = Φ η."""
        return self.Phi

    @property
    def lift(self) -> np.ndarray:
        """(2n + m₀ + L n_w, 2r + m₀ + L r): the full Roger state [q, q̇, w, x_1 … x_L] of a
        modal state [η, η̇, w, z_1 … z_L] (q = Φη, q̇ = Φη̇, x_l = Φ_w z_l)."""
        n, r, m0, nw, L = self.Phi.shape[0], self.r, self.n_dry_lags, self.n_w, len(self.lags)
        out = np.zeros((2 * n + m0 + L * nw, self.n_states))
        out[:n, :r] = self.Phi
        out[n:2 * n, r:2 * r] = self.Phi
        out[2 * n:2 * n + m0, 2 * r:2 * r + m0] = np.eye(m0)
        for l in range(L):
            out[2 * n + m0 + l * nw:2 * n + m0 + (l + 1) * nw,
                2 * r + m0 + l * r:2 * r + m0 + (l + 1) * r] = self.Phi[:nw]
        return out

    def second_order(self, V, omega=None) -> SecondOrder:
        """The modal second-order system at the airspeeds V [m/s] (1-D): Φᵀ(S1, S2, S3)Φ of the
        structure and propellers (wing aerodynamics off) minus the projected Roger terms
        ½ρ b² A₂ʳ, ½ρ V b A₁ʳ, ½ρV² A₀ʳ (Aʳ = Φ_wᵀ A Φ_w, the fit of
        :func:`~propwhirl.model.aerodynamics.dlm_rfa.coefficients` at each speed's Mach), the lag loads
        S4 = ½ρV² A_{2+l}ʳ and ż_l = η̇ − (V/b) β_l z_l.  ``omega`` [rad/s] as
        :meth:`~propwhirl.model.systems.PropellerWingAssembly.blocks`."""
        model = self.model
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        ks = tracking_ks() if self.ks is None else np.asarray(self.ks, float)
        A = coefficients(model, V, ks, self.assembly.dlm_tables)    # (nV, 3 + L, nw, nw)
        with np.errstate(all="ignore"):
            dry = self.assembly.with_switches(wing_aero=False).blocks(V, omega).dense()
        labels = self.labels()
        return roger_system(dry, A, V, b_ref(model), model.flight.density,
                            self.lags, labels[2 * self.r + self.n_dry_lags:], self.Phi,
                            labels[:self.r])

    def state_matrix(self, V, **options) -> np.ndarray:
        """The modal A(V), shape (nV, 2r + m₀ + L r, 2r + m₀ + L r)."""
        V = np.atleast_1d(np.asarray(V, dtype=float))
        return state_matrix(self.second_order(V, **options), V)


def kept_modes(model, assembly, f_all: np.ndarray, shapes: np.ndarray, M: np.ndarray,
               speeds, factor: float = CUTOFF_FACTOR) -> tuple[int, float, float]:
    """(n, f_ref, f_c): how many of the in-vacuo modes (frequencies ``f_all`` [Hz], ascending;
    ``shapes`` M-orthonormal over the model's DOFs, mass ``M``) a doublet-lattice wing's
    modal analyses keep — the modal Roger state space (:func:`modal_roger`) and the p-k's
    followed modes (:func:`propwhirl.analysis.pk.followed_modes`): those up to the reduced
    models' cut-off f_c (:func:`~propwhirl.model.reduction.cutoff`; ``assembly`` the model's
    or the model) and no higher than the fit's highest reduced frequency at the highest of
    ``speeds`` [m/s] (beyond it Q is extrapolated, and beyond the panels' own validity: the
    false criticals of issue 37 item 1), at least :data:`MIN_MODES`; f_ref and f_c [Hz]."""
    ref, fc = cutoff(assembly, f_all, shapes, M, factor)
    fit_hz = fit_ks()[-1] * float(np.max(speeds)) / (2 * np.pi * b_ref(model))
    fc = min(fc, fit_hz)
    return max(int(np.sum(f_all <= fc)), min(MIN_MODES, f_all.size)), ref, fc


def modal_roger(model, speeds, *, assembly=None,
                structure: tuple[np.ndarray, np.ndarray] | None = None,
                factor: float = CUTOFF_FACTOR) -> ModalRoger:
    """The :class:`ModalRoger` state space of ``model`` (a PropellerWing with ``aero = "dlm"``)
    for the airspeeds ``speeds`` [m/s].

    ``assembly``: ``model.assembly()`` if already built; ``structure``: its structural (M, K)
    over the model's DOFs (the non-rotating structure without aerodynamics, an analysis's
    :class:`~propwhirl.analysis.modes.InVacuo`) if already evaluated; ``factor``: the cut-off
    over the reference frequency (:func:`~propwhirl.model.reduction.cutoff`).

    Examples
    --------
    Goland's wing (10 beam elements, 30 DOFs) on 4 × 7 panels: f_ref is its second bending
    mode, and the six modes up to 3 × 39 Hz are kept (12 + 24 states instead of 180):

    >>> import numpy as np
    >>> from propwhirl.model import FlightCondition, PropellerWing, Wing
    >>> wing = Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71,
    ...             polar_inertia=8.64, EI=9.77e6, GJ=0.987e6, elastic_axis=0.33,
    ...             centre_of_gravity=0.43, n_elements=10, aero="dlm", dlm_mach=0.0,
    ...             dlm_chordwise_panels=4, dlm_spanwise_panels=7)
    >>> R = modal_roger(PropellerWing(wing, FlightCondition(1.02)), np.array([120.0, 200.0]))
    >>> R.r, R.n_states, np.round(R.frequencies_hz, 1).tolist()
    (6, 36, [7.7, 15.2, 39.1, 55.6, 72.3, 100.1])
    """
    if getattr(getattr(model, "wing", model), "aero", None) != "dlm" or not model.wing_aero:
        raise v.InputError(f"model = {getattr(model, 'name', model)!r:.60} is invalid for the "
                           "modal Roger state space: needs a wing with aero = 'dlm'")
    V = np.atleast_1d(v.positive("speeds", speeds, "m/s"))
    assembly = model.assembly() if assembly is None else assembly
    if structure is None:
        quiet = assembly.with_switches(rotating=False, wing_aero=False, propeller_aero=False)
        with np.errstate(all="ignore"):
            S = quiet.blocks(V[:1]).dense()
        structure = S.S1[0], S.S3[0]
    M, K = structure
    w2, shapes = sla.eigh(K, M)
    f_all = np.sqrt(np.abs(w2)) / (2 * np.pi)
    n_keep, ref, fc = kept_modes(model, assembly, f_all, shapes, M, V, factor)
    with np.errstate(all="ignore"):
        dry = assembly.with_switches(wing_aero=False).blocks(V[:1]).dense()
    n_w = int(surface_of(model).keep.size)
    return ModalRoger(assembly, shapes[:, :n_keep], f_all[:n_keep], fc, ref, f_all, n_w,
                      tuple(dry.w_labels))
