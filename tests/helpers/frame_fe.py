"""A small independent finite-element solver of NASTRAN decks for the tests (issue 36, item
6d): the normal modes (SOL 103) of a frame of CBARs, CONM2s and RBE2s, so that a
hand-written FE model — a wing with propellers on pylons below it — has modes to write as an
OP2 without NASTRAN.

What it reads (pyNastran parses the deck; SI or any consistent units, no WTMASS): GRID in the
basic frame; CBAR with an orientation vector X1-X3, PBAR (A, I1, I2, J, NSM), MAT1 (E, G,
RHO); CONM2 on its grid (no offset; I11, I22, I33); RBE2 holding 123456 (no chains); SPC1
(any components).  Elements: Euler-Bernoulli beams with the consistent mass matrix (Przemieniecki),
plane 1 (x, the orientation vector) bending with I1, plane 2 with I2, torsion with J and the
polar inertia RHO (I1 + I2); RBE2 by eliminating the dependent grids' DOFs (rigid-body
kinematics u_d = u_i + θ_i × (r_d − r_i)); SPC1 by removing the DOFs.  Anything else is an
AssertionError: it is a test helper, not a reader.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import scipy.linalg


def _beam(L, E, G, A, I1, I2, J, m, polar):
    """Local 12x12 stiffness and consistent mass of a beam (DOFs per end: u v w θx θy θz)."""
    k = np.zeros((12, 12))
    M = np.zeros((12, 12))
    ax = [0, 6]
    k[np.ix_(ax, ax)] = E * A / L * np.array([[1, -1], [-1, 1]])
    M[np.ix_(ax, ax)] = m * L / 6 * np.array([[2, 1], [1, 2]])
    tx = [3, 9]
    k[np.ix_(tx, tx)] = G * J / L * np.array([[1, -1], [-1, 1]])
    M[np.ix_(tx, tx)] = polar * L / 6 * np.array([[2, 1], [1, 2]])
    kb = np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                   [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]]) / L ** 3
    mb = m * L / 420 * np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * L * L, 13 * L, -3 * L * L],
                                 [54, 13 * L, 156, -22 * L],
                                 [-13 * L, -3 * L * L, -22 * L, 4 * L * L]])
    p1 = [1, 5, 7, 11]                     # v, θz: plane 1 (I1)
    k[np.ix_(p1, p1)] = E * I1 * kb
    M[np.ix_(p1, p1)] = mb
    p2 = [2, 4, 8, 10]                     # w, θy: plane 2 (I2); θy = −dw/dx
    s = np.diag([1.0, -1.0, 1.0, -1.0])
    k[np.ix_(p2, p2)] = E * I2 * s @ kb @ s
    M[np.ix_(p2, p2)] = s @ mb @ s
    return k, M


def modes(path: Path, n_modes: int = 40):
    """(grid ids, xyz [n, 3], eigenvalues ω² [n_modes], mass-normalised shapes
    [n_modes, n_grids, 6]) of the deck at ``path``."""
    from pyNastran.bdf.bdf import BDF

    bdf = BDF(debug=None)
    bdf.read_bdf(str(path), xref=False, punch=True)
    ids = sorted(bdf.nodes)
    index = {g: i for i, g in enumerate(ids)}
    xyz = np.array([np.asarray(bdf.nodes[g].xyz, dtype=float) for g in ids])
    for g in ids:
        assert not bdf.nodes[g].cp and not bdf.nodes[g].cd, g
    n = 6 * len(ids)
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for e in bdf.elements.values():
        assert e.type == "CBAR", e.type
        a, b = (index[int(g)] for g in e.node_ids)
        prop = bdf.properties[e.pid]
        mat = bdf.materials[prop.mid]
        d = xyz[b] - xyz[a]
        L = float(np.linalg.norm(d))
        ex = d / L
        vec = np.asarray(e.x, dtype=float)
        ey = vec - (vec @ ex) * ex
        ey /= np.linalg.norm(ey)
        R = np.array([ex, ey, np.cross(ex, ey)])
        rho = mat.rho or 0.0
        k, m = _beam(L, mat.e, mat.g, prop.A, prop.i1, prop.i2, prop.j,
                     rho * prop.A + (prop.nsm or 0.0), rho * (prop.i1 + prop.i2))
        T = scipy.linalg.block_diag(R, R, R, R)
        dofs = np.r_[6 * a:6 * a + 6, 6 * b:6 * b + 6]
        K[np.ix_(dofs, dofs)] += T.T @ k @ T
        M[np.ix_(dofs, dofs)] += T.T @ m @ T
    for c in bdf.masses.values():
        assert c.type == "CONM2" and not np.any(c.X) and int(c.cid) == 0, c
        i11, i21, i22, i31, i32, i33 = c.I
        assert i21 == i31 == i32 == 0.0
        g = 6 * index[int(c.nid)]
        M[g:g + 6, g:g + 6] += np.diag([c.mass] * 3 + [i11, i22, i33])
    # RBE2: the dependent grids' DOFs from their independent grid's
    T = np.eye(n)
    dependent = set()
    for r in bdf.rigid_elements.values():
        assert r.type == "RBE2" and str(r.cm) == "123456", r
        i = index[int(r.gn)]
        for gm in r.Gmi:
            j = index[int(gm)]
            assert j not in dependent and i not in dependent, "no chains"
            dependent.add(j)
            dx, dy, dz = xyz[j] - xyz[i]
            rows = np.zeros((6, n))
            rows[:, 6 * i:6 * i + 6] = np.array([
                [1, 0, 0, 0, dz, -dy], [0, 1, 0, -dz, 0, dx], [0, 0, 1, dy, -dx, 0],
                [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]])
            T[6 * j:6 * j + 6] = rows
    held = set()                           # held DOFs (6 grid + component - 1)
    for spcs in bdf.spcs.values():
        for s in spcs:
            assert s.type == "SPC1", s
            held |= {6 * index[int(g)] + int(c) - 1 for g in s.nodes
                     for c in str(s.components)}
    keep = [k for k in range(n) if k // 6 not in dependent and k not in held]
    T = T[:, keep]
    Kr, Mr = T.T @ K @ T, T.T @ M @ T
    w2, phi = scipy.linalg.eigh(Kr, Mr, subset_by_index=[0, n_modes - 1])
    shapes = (T @ phi).T.reshape(n_modes, len(ids), 6)
    return np.array(ids), xyz, w2, shapes
