"""The doublet-lattice kernel of a planar wing with its mirror image, on the half-wing's
receiving points only, its k-independent parts computed once per Mach number (issue 37, item 2).

PanelAero's ``DLM.calc_Ajj`` (Rodden, Taylor & McIntosh 1971, the parabolic approximation of
the spanwise kernel, Laschka's approximation of the integrals I₁, I₂) evaluates the
oscillatory increment of the normalwash matrix D(k̄, M) of every receiving point against every
sending panel of the mirrored wing, (2n)² entries, and its out-of-plane part ("nonplanar", the
kernel K₂) on every entry too.  propwhirl folds the AIC to the symmetric one of the half-wing
(:func:`propwhirl.model.aerodynamics.dlm.symmetric_aic`): with the left half-wing's panel p the
mirror image of the right one's, A = [[D, E], [E, D]] and

    Q_RR + Q_RL = −(A_RR + A_RL)⁻¹,

so only the right half-wing's rows of A are needed (n × 2n entries, half the kernel; the
inverse of an n × n instead of a 2n × 2n matrix, an eighth).  This module evaluates those rows
with PanelAero's formulas (the same equations, checked against its ``calc_Ajj`` to round-off,
tests/model/test_dlm_kernel.py) and, on a planar mesh (every receiving point within
0.001 semiwidths of every sending panel's plane: PanelAero's own "planar" condition, where its
nonplanar part is exactly zero), only the planar part: P₁, I₁ (no K₂, I₂, J₀).  Everything that
does not depend on the reduced frequency — the panels' geometry, the parabolic coefficients,
and at one Mach number u₁, r₁, R, K₁₀ and exp(−n c u₁) of Laschka's series — is computed once
(:class:`PlanarKernel`) and reused at every k̄ of that Mach (:meth:`PlanarKernel.increment`).

PanelAero is BSD-3-Clause (DLR-AE/PanelAero, Arne Voß); the equations and Laschka's
coefficients below are its, as published by Rodden et al. (1971) and Blair (1992).
"""
from __future__ import annotations

import numpy as np

#: Laschka's coefficients of the exponential approximation of u / (1 + u²)^½ (PanelAero's
#: ``laschka_approximation``; Rodden 1971, Blair 1992 p. 89) and its exponent c
LASCHKA_A = (+0.24186198, -2.7918027, +24.991079, -111.59196, +271.43549, -305.75288,
             -41.183630, +545.98537, -644.78155, +328.72755, -64.279511)
LASCHKA_C = 0.372
#: PanelAero's planar condition: |z̄| / e at or below this for every pair
PLANAR_ZBAR = 0.001
#: entries per block of rows of :meth:`PlanarKernel.increment`: its ~20 temporaries are
#: arrays of this many numbers (a few MB in all, whatever the panels), not of rows × panels
BLOCK = 16384


def is_planar(grid: dict, rows: slice | None = None) -> bool:
    """Whether every receiving point (of ``rows``) of PanelAero ``grid`` lies within
    :data:`PLANAR_ZBAR` semiwidths of every sending panel's plane (PanelAero's condition 1
    for every pair: its nonplanar part D₂ is then zero)."""
    g = _geometry(grid, rows)
    return bool(np.all(np.abs(g["zbar"]) / g["e"] <= PLANAR_ZBAR))


def _geometry(grid: dict, rows: slice | None) -> dict:
    """PanelAero's ``calc_Ajj`` geometry (receiving points ``rows`` × every sending panel)."""
    rows = slice(None) if rows is None else rows
    Pr = grid["offset_j"][rows]
    Pm, Pp, Ps = grid["offset_P1"], grid["offset_P3"], grid["offset_l"]
    e = np.absolute(0.5 * ((Pp[:, 2] - Pm[:, 2]) ** 2.0 + (Pp[:, 1] - Pm[:, 1]) ** 2.0) ** 0.5)
    xsr = Pr[:, 0][:, None] - Ps[:, 0][None, :]
    ysr = Pr[:, 1][:, None] - Ps[:, 1][None, :]
    zsr = Pr[:, 2][:, None] - Ps[:, 2][None, :]
    sinG = (Pp[:, 2] - Pm[:, 2]) / (2.0 * e)
    cosG = (Pp[:, 1] - Pm[:, 1]) / (2.0 * e)
    tanL = (Pp[:, 0] - Pm[:, 0]) / (2.0 * e)
    gamma = np.arcsin(sinG)
    gamma_sr = gamma[None, :] - gamma[rows][:, None]
    ybar = ysr * cosG + zsr * sinG
    zbar = zsr * cosG - ysr * sinG
    return {"e": np.broadcast_to(e, xsr.shape), "chord": np.broadcast_to(grid["l"], xsr.shape),
            "xsr": xsr, "ybar": ybar, "zbar": zbar, "gamma_sr": gamma_sr,
            "tanL": np.broadcast_to(tanL, xsr.shape)}


def steady_rows(grid: dict, mach: float, rows: slice | None = None) -> np.ndarray:
    """PanelAero's steady vortex-lattice normalwash matrix ``VLM.calc_Ajj(grid, mach)[0]``
    (horseshoe vortices on the 1/4-chord lines, Katz & Plotkin 10.4.5-10.4.7, x stretched by
    1/β), its receiving points ``rows`` only (rows × panels): the same operations, the same
    bits, including PanelAero's rule that zeroes a whole row when one of its points lies on a
    vortex (within 1e-5)."""
    rows = slice(None) if rows is None else rows
    beta = (1 - (mach ** 2.0)) ** 0.5
    P0 = np.array(grid["offset_j"][rows], float)
    P1 = np.array(grid["offset_P1"], float)
    P3 = np.array(grid["offset_P3"], float)
    for P in (P0, P1, P3):
        P[:, 0] = P[:, 0] / beta
    N = grid["N"][rows]
    n_hat_w, n_hat_wl = N[:, 2][:, None], N[:, 1][:, None]
    r1x, r1y, r1z = (P0[:, i][:, None] - P1[:, i][None, :] for i in range(3))
    r2x, r2y, r2z = (P0[:, i][:, None] - P3[:, i][None, :] for i in range(3))
    r1Xr2_x = r1y * r2z - r1z * r2y
    r1Xr2_y = -r1x * r2z + r1z * r2x
    r1Xr2_z = r1x * r2y - r1y * r2x
    mod_r1Xr2 = (r1Xr2_x ** 2.0 + r1Xr2_y ** 2.0 + r1Xr2_z ** 2.0) ** 0.5
    r1 = (r1x ** 2.0 + r1y ** 2.0 + r1z ** 2.0) ** 0.5
    r2 = (r2x ** 2.0 + r2y ** 2.0 + r2z ** 2.0) ** 0.5
    r0r1 = (P3[:, 0] - P1[:, 0]) * r1x + (P3[:, 1] - P1[:, 1]) * r1y + (P3[:, 2] - P1[:, 2]) * r1z
    r0r2 = (P3[:, 0] - P1[:, 0]) * r2x + (P3[:, 1] - P1[:, 1]) * r2y + (P3[:, 2] - P1[:, 2]) * r2z
    D1_base = 1.0 / 4.0 / np.pi / mod_r1Xr2 ** 2.0 * (r0r1 / r1 - r0r2 / r2)
    D1_v = r1Xr2_y * D1_base
    D1_w = r1Xr2_z * D1_base
    eps = 10e-6
    for bad in (r1 < eps, r2 < eps):
        ind = np.where(bad)[0]                  # PanelAero: the rows of those points
        D1_v[ind] = 0.0
        D1_w[ind] = 0.0
    ind = np.where(mod_r1Xr2 < eps)
    D1_v[ind] = 0.0
    D1_w[ind] = 0.0
    D = D1_w * n_hat_w + D1_v * n_hat_wl
    # inner semi-infinite vortex line
    d2 = (r1y ** 2.0 + r1z ** 2.0) ** 0.5
    D2_base = -(1.0 / (4.0 * np.pi)) * (1.0 - (-r1x / r1)) / d2
    D2_v = (-r1z / d2) * D2_base
    D2_w = (r1y / d2) * D2_base
    ind = np.where((r1 < eps) + (d2 < eps))[0]
    D2_v[ind] = 0.0
    D2_w[ind] = 0.0
    D2 = D2_w * n_hat_w + D2_v * n_hat_wl
    # outer semi-infinite vortex line
    d3 = (r2y ** 2.0 + r2z ** 2.0) ** 0.5
    D3_base = -(1.0 / (4.0 * np.pi)) * (r2x / r2 - (-1.0)) / d3
    D3_v = (r2z / d3) * D3_base
    D3_w = (-r2y / d3) * D3_base
    ind = np.where((r2 < eps) + (d3 < eps))[0]
    D3_v[ind] = 0.0
    D3_w[ind] = 0.0
    D3 = D3_w * n_hat_w + D3_v * n_hat_wl
    A = grid["A"]
    span = A / grid["l"]
    return (D + D2 + D3) * 0.5 * A / span


class PlanarKernel:
    """The oscillatory normalwash increment D(k̄) − D(0) of PanelAero's parabolic DLM for the
    receiving points ``rows`` of a planar ``grid`` (PanelAero's aerogrid: every panel, both
    half-wings) at Mach ``mach``: its k-independent parts computed here, once.

    :meth:`increment` (k̄ = ω/U [1/m]) is PanelAero's ``calc_Ajj(grid, mach, k̄, "parabolic")``
    restricted to those rows (the planar part D₁: the nonplanar D₂ is zero on a planar grid,
    :func:`is_planar`).  Memory kept: about 16 real arrays of rows × panels (five at each of
    the semiwidth's ends and middle, the summed steady term), ≈ 78 bytes per entry of the
    mirrored wing's (2n)² AIC when the rows are the half-wing's n."""

    def __init__(self, grid: dict, mach: float, rows: slice | None = None):
        g = _geometry(grid, rows)
        e, ybar, zbar = g["e"], g["ybar"], g["zbar"]
        self.shape = e.shape
        e2 = e * e
        ybar2, zbar2 = ybar * ybar, zbar * zbar
        # PanelAero: condition 1 (planar) for every pair, so Fparabolic = 2e / (ȳ² − e²)
        F = 2.0 * e / (ybar2 - e2)
        L = np.log(((ybar - e) ** 2.0 + zbar2) / ((ybar + e) ** 2.0 + zbar2))
        # D1 = chord/(8π) [((ȳ² − z̄²) A1 + ȳ B1 + C1) F + (B1/2 + ȳ A1) L + 2 e A1] with
        # A1 = (Pm − 2Ps + Pp)/(2e²), B1 = (Pp − Pm)/(2e), C1 = Ps: linear in (Pm, Ps, Pp)
        c8 = g["chord"] / (np.pi * 8.0)
        wA = c8 * ((ybar2 - zbar2) * F + ybar * L + 2.0 * e) / (2.0 * e2)
        wB = c8 * (ybar * F + 0.5 * L) / (2.0 * e)
        wC = c8 * F
        # P1 = −(K1 e^{−ik x_e} − K10) T1 at each point: T1 into the weights, and the
        # steady Σ w K10 T1 summed once
        T1 = np.cos(g["gamma_sr"])
        weights = (wA - wB, wC - 2.0 * wA, wA + wB)
        beta2 = 1.0 - mach ** 2.0
        self._d0 = np.zeros(self.shape)
        #: per point (−e, 0, +e): its weight w T1 and the k-independent arrays of its P1
        self._points = []
        for s, w in zip((-1.0, 0.0, 1.0), weights):
            ebar = s * e
            xe = g["xsr"] - ebar * g["tanL"]
            r1 = ((ybar - ebar) ** 2.0 + zbar2) ** 0.5
            R = (xe ** 2.0 + beta2 * r1 ** 2.0) ** 0.5
            with np.errstate(all="ignore"):
                u1 = (mach * R - xe) / (beta2 * r1)
                tail = mach * r1 / R / (1.0 + u1 ** 2.0) ** 0.5
            wT = w * T1
            self._d0 += wT * (-1.0 - xe / R)                    # Σ w T1 K10
            zero = r1 == 0
            self._points.append({
                "w": wT, "xe": xe, "r1": r1, "au": np.abs(u1), "neg": u1 < 0.0,
                "E1": np.exp(-LASCHKA_C * np.abs(u1)), "tail": tail,
                # r1 = 0: PanelAero's K1 = −2 (x ≥ 0) or 0 (x < 0)
                "r0pos": zero & (g["xsr"] >= 0.0), "r0neg": zero & (g["xsr"] < 0.0)})

    def increment(self, kbar: float) -> np.ndarray:
        """D(k̄) − D(0) (rows × panels) complex at k̄ = ω/U [1/m] (> 0)."""
        k = float(kbar)
        out = self._d0.astype(complex)
        rows = self.shape[0]
        step = max(1, BLOCK // max(self.shape[1], 1))
        with np.errstate(all="ignore"):       # r1 = 0: NaN, replaced (PanelAero's too)
            for lo in range(0, rows, step):   # blocks of rows: small temporaries
                b = slice(lo, min(rows, lo + step))
                for p in self._points:
                    q = {key: value[b] for key, value in p.items()}
                    out[b] -= q["w"] * (self._K1(q, k) * np.exp(-1j * k * q["xe"]))
        return out

    @staticmethod
    def _K1(p: dict, k: float) -> np.ndarray:
        """PanelAero's ``kernelfunction`` K1 at one semiwidth point (Laschka's I1, planar)."""
        k1 = k * p["r1"]
        au, E1, neg = p["au"], p["E1"], p["neg"]
        kk = k1 * k1
        # Laschka's I0 at |u1| = Σ a_n e^{−ncu} (nc − i k1) / (n²c² + k1²) = S1 − i k1 S0 with
        # S0 = Σ g_n e^{−ncu}, S1 = Σ nc g_n e^{−ncu}, g_n = a_n / (n²c² + k1²); at u1 = 0
        # the same with e^{0} = 1 (T0 = Σ g_n: only its real part is used)
        S0, S1, T0 = np.zeros_like(k1), np.zeros_like(k1), np.zeros_like(k1)
        En = np.ones_like(k1)
        g = np.empty_like(k1)
        for n, a in enumerate(LASCHKA_A, 1):
            nc = n * LASCHKA_C
            np.add(kk, nc * nc, out=g)
            np.divide(a, g, out=g)
            T0 += g
            En *= E1
            g *= En
            S0 += g
            g *= nc
            S1 += g
        # I1(|u|) = (f − i k1 I0) e^{−i k1 |u|}, f = 1 − |u| / (1 + u²)^½:
        # f − i k1 I0 = (f − k1² S0) − i k1 S1
        ph = k1 * au
        c, s = np.cos(ph), np.sin(ph)
        ar = 1.0 - au / (1.0 + au * au) ** 0.5 - kk * S0
        ai = -k1 * S1
        I1 = (ar * c + ai * s) + 1j * (ai * c - ar * s)
        # u1 < 0: I1 = 2 Re I1(0) − Re I1(|u|) + i Im I1(|u|) (Rodden 1971, eq. A.5); at
        # u = 0, f = 1 and the phase is 1: Re I1(0) = 1 − k1² T0
        I1.real[neg] = 2.0 * (1.0 - kk[neg] * T0[neg]) - I1.real[neg]
        # e^{−i k1 u1}: the conjugate of the phase at |u| where u1 < 0
        ejku = c - 1j * np.where(neg, -s, s)
        K1 = -I1 - ejku * p["tail"]
        K1[p["r0pos"]] = -2.0
        K1[p["r0neg"]] = 0.0
        return K1
