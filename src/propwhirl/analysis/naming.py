"""Names and descriptions of tracked modes: the thesis's mode names, whirl sense, content.

Everything here reads what a state is from the model's :class:`~propwhirl.model.protocol.DofMap`
(``model.dof_map()``), never from its class or its labels.  Modes are named once, at the first
speed of a sweep (a tracked mode keeps its name along the sweep):

* models with a wing structure (propeller–wing models, chapters 7–11, and modal models —
  :attr:`~propwhirl.model.protocol.DofMap.has_structure`: wing DOFs or modal coordinates; the
  propellers that whirl are :meth:`~propwhirl.model.protocol.DofMap.whirling`'s, own mounts'
  θ, ψ or the hub grids of mounts in the modes): each oscillatory
  mode is matched, by an optimal one-to-one MAC assignment on the displacement part, to the
  in-vacuo modes named by :func:`propwhirl.analysis.modes.label_modes` ("wing n",
  "backward k", "forward k": the thesis's names, kept for models with one flexibly mounted
  propeller);
* with two or more flexibly mounted, spinning propellers the whirl modes ("backward k",
  "forward k" above) are renamed by what they are at the first speed V0 (:func:`propeller_names`):
  "backward whirl, propeller 7", "backward whirl, propellers 1–6 (2 of 6)",
  "forward whirl, propellers 1–6 (1 of 6, collective)" — the sense of the propellers' orbits,
  the set of identical propellers that carries most of the mode's kinetic energy and, when that
  set has several modes of that sense, the mode's place among them by frequency at V0.  A name
  thus depends on the model at V0 and on the tracked branch, not on the speed grid, and the
  number no longer counts the other sets' modes (a tip propeller's modes moving through the
  high-lift propellers' leave their names alone).  The wing modes keep "wing n";
* models with a spinning propeller and no wing (chapter 6): "backward" and "forward" whirl from
  the sense of the θ–ψ orbit; not spinning: "pitch" and "yaw" by increasing frequency;
* any other model (the typical section): the dominant content group of each mode ("plunge",
  "pitch");
* the aerodynamic lag roots are "lag k" (by decreasing real part): which roots are
  structural modes and which lag roots is decided in one place, :func:`structural_roots`
  (the strip models' rule — a lag root is real — with the count of structural modes: the
  Roger lag roots of a doublet-lattice wing that the coupling splits into complex pairs are
  lag roots too), and only the structural modes are named, numbered and counted ("(k of n)")
  as above; a real root already unstable at the first speed is "static k" (a range starting
  beyond a divergence speed: a diverged structural mode, described by its content); the
  hidden conjugate partner of mode "x" is "x'".

An event (flutter, divergence) of a tracked mode that is a lag root at the first speed — with
lag states a real branch may start as a lag state and turn right, through zero, as the speed
grows (Goland's divergence on strips) — is named after the structural mode its shape at the
event is (:func:`event_label`); it keeps the id of the branch that crossed.

Content is the share of a mode's kinetic energy x̂ᴴ M x̂ (M the structural mass, aerodynamics
off) in each group of :meth:`~propwhirl.model.protocol.DofMap.groups`: "bending" (h, φ),
"torsion" (wing α), "pitch" (propeller θ or the section's α), "yaw" (ψ), "plunge".
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.analysis.modes import in_vacuo_of, label_modes, model_modes, repeated_groups
from propwhirl.analysis.participation import mode_participation
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.engine import Sweep, mac
from propwhirl.model.protocol import DofMap, Model


def kinetic_energy_shares(X: np.ndarray, M: np.ndarray,
                          groups: Mapping[str, Sequence[int] | np.ndarray]) -> dict[str, np.ndarray]:
    """Share of each mode's (column of X) kinetic energy x̂ᴴMx̂ in each group of DOFs.

    Group g's share is Re Σ_{i∈g} conj(x_i) (M x)_i / x̂ᴴMx̂; over groups covering every DOF the
    shares sum to one.  ``groups`` maps names to indices into x (e.g. :meth:`DofMap.groups`).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.diag([1.0, 3.0])
    >>> shares = kinetic_energy_shares(np.array([[1.0], [1.0]]), M, {"a": [0], "b": [1]})
    >>> {g: float(s[0]) for g, s in shares.items()}
    {'a': 0.25, 'b': 0.75}
    """
    X = np.asarray(X)
    e = np.real(np.conj(X) * (M @ X))
    total = e.sum(axis=0)
    return {name: e[np.asarray(ix, dtype=int)].sum(axis=0) / total for name, ix in groups.items()}


def _oscillatory(sw: Sweep, t: int = 0) -> list[int]:
    lam = sw.eigenvalues[t]
    return [k for k in range(sw.n_modes)
            if sw.physical[t, k] and abs(lam[k].imag) > 1e-9 * max(1.0, abs(lam[k]))]


#: The name of an aerodynamic lag root starts with this word ("lag 3"; its hidden partner
#: "lag 3'"): what :func:`structural_roots` decided, as the names carry it (:func:`is_lag`).
LAG = "lag"


def is_lag(label: str) -> bool:
    """Whether ``label`` names an aerodynamic lag root (:func:`structural_roots`), not a
    structural mode.

    >>> is_lag("lag 3"), is_lag("lag 3'"), is_lag("wing 2"), is_lag("backward whirl, propeller 7")
    (True, True, False, False)
    """
    return label.split(" ", 1)[0] == LAG


def lag_load_share(model: Model, sw: Sweep, t: int = 0, in_vacuo=None,
                   evaluator=None) -> np.ndarray:
    """(n_modes,) share of the aerodynamic lag states' loads in the forces on the structure of
    each root of ``sw`` (a sweep of ``model``) at its speed ``t`` [-].

    A root λ with state x = [q, q̇, w] satisfies (λ² S1 + λ S2 + S3) q = S4 w (the model's
    second-order system at that speed, :class:`~propwhirl.model.statespace.SecondOrder`): the
    lag states' load S4 w on the DOFs against the structure's inertial and elastic forces
    λ² S1 q and S3 q, each measured as ‖f‖ = (fᴴ M⁻¹ f)^½ with the structural mass M
    (aerodynamics off: the kinetic-energy norm of the acceleration a force gives):

        share = ‖S4 w‖ / (‖λ² S1 q‖ + ‖S3 q‖).

    A structural mode is a resonance of the structure (λ ≈ iω: the inertial and elastic forces
    nearly cancel, the air perturbs them): share ≪ 1.  An aerodynamic lag root (λ near a lag
    state's own root, −β V/b, on or near the negative real axis: inertial and elastic forces
    add) moves the structure only as the lag loads push it: share ≈ 1.  A root that does not
    move the structure (q = 0): +inf; a model without lag states: 0.  Independent of how the
    lag states are scaled (w enters only through the load S4 w).  ``in_vacuo``: the model's
    structure (:func:`named_modes`); ``evaluator``: the model's assembly, if already built
    (``model.assembly()``: its second-order system at that speed).
    """
    iv = in_vacuo_of(model, in_vacuo)
    dm = model.dof_map()
    n = dm.n_dof
    X = np.asarray(sw.eigenvectors[t])
    lam = np.asarray(sw.eigenvalues[t])
    if dm.n_lag == 0:
        return np.zeros(lam.size)
    s = (model if evaluator is None else evaluator).second_order(np.array([float(sw.V[t])]))
    q, w = X[:n], X[2 * n:]
    chol = np.linalg.cholesky(iv.M)

    def norm(f: np.ndarray) -> np.ndarray:
        return np.linalg.norm(np.linalg.solve(chol, f), axis=0)

    load = norm(s.S4[0] @ w)
    own = norm(s.S1[0] @ q * lam ** 2) + norm(s.S3[0] @ q)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(own > 0, load / np.where(own > 0, own, 1.0), np.inf)


def structural_roots(model: Model, sw: Sweep, basis: np.ndarray | None = None,
                     in_vacuo=None, t: int = 0, evaluator=None) -> np.ndarray:
    """Which roots of ``sw`` (a sweep of ``model``) are structural modes at its speed ``t``,
    and which aerodynamic lag roots: (n_modes,) bool, a hidden conjugate partner as its
    partner.  The one place this is decided.

    The rule of the strip models: a lag state's root is real (the lag states alone decay,
    at −β V/b), a structural mode oscillates — so the structural roots are the oscillatory
    roots and the real roots already unstable (a diverged structural mode; a stable real root
    is a lag root).  The count completes it: a system of r structural DOFs (the model's, or
    the columns of a reduced model's ``basis``) has at most r oscillatory modes.  Where the
    coupling splits equal lag roots into complex pairs — the Roger lag states of a
    doublet-lattice wing, a set per mode or DOF with the same roots — there are more: the
    surplus are the pairs whose lag states' loads are the largest share of the forces on the
    structure (:func:`lag_load_share`; an unstable pair is never one).  On
    examples/x57_like.toml on 3 x 12 panels at 20 m/s the shares are below 0.035 for the
    modes and above 0.85 for the lag pairs (modal and full Roger state); strip models have no
    surplus, and their structural roots stay the oscillatory ones.  ``in_vacuo``,
    ``evaluator``: as :func:`lag_load_share`.
    """
    n = sw.n_modes
    r = basis.shape[1] if basis is not None else model.dof_map().n_dof
    lam = sw.eigenvalues[t]
    out = np.zeros(n, dtype=bool)
    for k in range(n):
        if sw.physical[t, k] and (lam[k].real > 0
                                  or abs(lam[k].imag) > 1e-9 * max(1.0, abs(lam[k]))):
            out[k] = True
    osc = [k for k in np.flatnonzero(out) if lam[k].imag != 0]
    if len(osc) > r:                         # complex lag pairs: the surplus by the lag share
        share = lag_load_share(model, sw, t, in_vacuo, evaluator)
        stable = [k for k in osc if lam[k].real <= 0]
        by_share = sorted(stable, key=lambda k: (-share[k] if np.isfinite(share[k])
                                                 else -np.inf, k))
        out[by_share[: len(osc) - r]] = False
    for k in range(n):
        if not sw.physical[t, k] and sw.partner[k] >= 0:
            out[k] = out[sw.partner[k]]
    return out


def event_label(sw: Sweep, names: Sequence[str], mode: int, x: np.ndarray,
                mass: np.ndarray) -> str:
    """The name of an event of tracked mode ``mode`` with shape ``x`` (a state or
    displacement vector, its first ``n_dof`` entries the displacements): ``names[mode]``
    where that is a structural mode; for an aerodynamic lag root (:func:`is_lag`: e.g. a real
    branch that starts as a lag state and turns right, through zero, as the speed grows) the
    name of the structural mode the event's motion is: of the structural modes at the first
    speed, the one whose displacement shape φ holds the largest share of the kinetic energy of
    ``x``'s, |φᴴ M x|² / ((φᴴ M φ)(xᴴ M x)) (the MAC, eq. 5.14, in the kinetic-energy inner
    product of the structural ``mass`` M: bending, torsion and the propellers' motions weighed
    alike whatever their units).  The event keeps ``mode``, the branch that crossed.
    ``names[mode]`` when the sweep has no structural mode or no eigenvectors."""
    if not is_lag(names[mode]) or sw.eigenvectors is None:
        return names[mode]
    ids = [k for k in range(sw.n_modes) if sw.physical[0, k] and not is_lag(names[k])]
    if not ids:
        return names[mode]
    n = int(np.count_nonzero(sw.displacement))
    shapes = np.asarray(sw.eigenvectors[0])[:n][:, ids]
    q = np.asarray(x)[:n]
    Mq = mass @ q
    across = np.abs(shapes.conj().T @ Mq) ** 2
    norms = np.real(np.sum(shapes.conj() * (mass @ shapes), axis=0)) * np.real(q.conj() @ Mq)
    macs = np.where(norms > 0, across / np.where(norms > 0, norms, 1.0), 0.0)
    return names[ids[int(np.argmax(macs))]]


def mode_names(model: Model, sw: Sweep, basis: np.ndarray | None = None,
               thesis: bool = False) -> list[str]:
    """Names of the tracked modes of ``sw`` = a sweep of ``model``, decided at its first speed
    (rules in the module docstring).  ``basis``: a reduced model's basis over the DOFs (the
    reference modes are then its Rayleigh–Ritz modes, :func:`~propwhirl.analysis.modes.model_modes`).
    ``thesis``: the thesis's names ("backward k", "forward k") also with several propellers
    (default: those named by their propellers, :func:`propeller_names`)."""
    names, thesis_names = named_modes(model, sw, basis)
    return thesis_names if thesis else names


def named_modes(model: Model, sw: Sweep, basis: np.ndarray | None = None,
                in_vacuo=None, evaluator=None) -> tuple[list[str], list[str]]:
    """(names, the thesis's names) of the tracked modes of ``sw`` (:func:`mode_names`): the
    same lists but with two or more flexibly mounted, spinning propellers.  ``in_vacuo``: the
    model's structure, evaluated once (:class:`~propwhirl.analysis.modes.InVacuo`), or the model
    without aerodynamics already assembled (:func:`~propwhirl.analysis.modes.model_modes`);
    ``evaluator``: the model's assembly, if already built (:func:`structural_roots`)."""
    dm = model.dof_map()
    n = sw.n_modes
    lam0 = sw.eigenvalues[0]
    X0 = sw.eigenvectors[0]
    names = [f"mode {k}" for k in range(n)]
    in_vacuo = in_vacuo_of(model, in_vacuo)
    structural = structural_roots(model, sw, basis, in_vacuo, evaluator=evaluator)
    osc = [k for k in _oscillatory(sw) if structural[k]]
    by_real = sorted((k for k in range(n) if sw.physical[0, k] and k not in osc),
                     key=lambda k: -lam0[k].real)
    for i, k in enumerate(k for k in by_real if structural[k]):   # diverged: not lag roots
        names[k] = f"static {i + 1}"
    for i, k in enumerate(k for k in by_real if not structural[k]):
        names[k] = f"{LAG} {i + 1}"
    if dm.has_structure:             # a wing: of nodes, or of modes (a modal structure)
        modes, _ = model_modes(model, basis, in_vacuo)
        ref = [lab for lab, _ in label_modes(model, basis, modes, in_vacuo)]
        for k, lab in _matched(X0[sw.displacement][:, osc], lam0[osc], modes, ref):
            names[osc[k]] = lab
        if len(_spinning_flexible(dm)) >= 2:
            whirls = [k for k in osc if not names[k].startswith(("wing", "rigid"))]
            thesis_names = list(names)
            names = propeller_names(model, sw, names, whirls, in_vacuo)
            return _partners(sw, names), _partners(sw, thesis_names)

    elif dm.propellers:
        p = dm.propellers[0]
        order = sorted(osc, key=lambda k: abs(lam0[k].imag))
        if p.spinning and len(order) == 2:
            for k in order:
                names[k] = whirl_sense(X0[p.theta, k], X0[p.psi, k], p.rotation, lam0[k])
        else:
            for k, nm in zip(order, ("pitch", "yaw")):
                names[k] = nm
    else:
        groups = dm.groups()
        for k in osc:
            e = {g: float(np.sum(np.abs(X0[ix, k]) ** 2)) for g, ix in groups.items()}
            names[k] = max(e, key=lambda g: e[g])
    names = _partners(sw, names)
    return names, names


def _matched(X: np.ndarray, lam: np.ndarray, modes, ref: Sequence[str]
             ) -> list[tuple[int, str]]:
    """(column of ``X``, name) pairs: the oscillatory modes ``X`` (displacements, one per
    column; eigenvalues ``lam``) matched one to one to the in-vacuo ``modes`` named ``ref``
    (:func:`~propwhirl.analysis.modes.label_modes`) by an optimal assignment of the MAC.

    A repeated in-vacuo frequency (:func:`~propwhirl.analysis.modes.repeated_groups`) is a
    subspace whose basis LAPACK picks by rounding, so it is matched as a subspace: each of its
    columns scores a mode by the share of the mode in the subspace (‖Qᴴx‖² / ‖x‖², Q an
    orthonormal basis of it: the same whatever the basis), and the names of the group go to
    the modes assigned to it in one fixed order — the modes by increasing frequency |Im λ|
    (their index on a tie), the names in label_modes' order (by frequency just above Ω = 0).
    The names of near-identical propellers' modes thus do not flip with the rounding of the
    platform's LAPACK (issue 36, item 2).
    """
    shapes = modes.shapes.astype(complex)
    M = mac(X[:, :, None], shapes[:, None, :])
    groups = repeated_groups(modes.omega)
    norms = np.sum(np.abs(X) ** 2, axis=0)
    for g in groups:
        Q, _ = np.linalg.qr(shapes[:, g])
        share = np.sum(np.abs(Q.conj().T @ X) ** 2, axis=0) / np.where(norms > 0, norms, 1.0)
        M[:, g] = share[:, None]
    rows, cols = linear_sum_assignment(-M)
    out = dict(zip(cols.tolist(), rows.tolist()))          # in-vacuo column -> mode
    for g in groups:
        members = [int(c) for c in g if int(c) in out]
        ks = sorted((out[c] for c in members), key=lambda k: (abs(lam[k].imag), k))
        for c, k in zip(sorted(members), ks):
            out[c] = k
    return [(k, ref[c]) for c, k in out.items()]


def _partners(sw: Sweep, names: list[str]) -> list[str]:
    names = list(names)
    for k in range(sw.n_modes):  # hidden conjugate partners: "<name>'"
        if not sw.physical[0, k] and sw.partner[k] >= 0:
            names[k] = f"{names[sw.partner[k]]}'"
    return names


def _spinning_flexible(dm: DofMap) -> list:
    """The propellers that whirl on their mounts and spin (:meth:`DofMap.whirling`: own
    pitch and yaw DOFs, or a modal structure's hub grid)."""
    return [p for p in dm.whirling() if p.spinning]


def propeller_sets(model: Model) -> list[tuple[int, ...]]:
    """The propellers that whirl on their mounts (numbered from 1, by number: flexibly mounted,
    or a modal structure's on its hub grid, :meth:`DofMap.whirling`) in sets of identical
    installations: the same propeller (every field of its table) and the same sense of
    rotation; the positions along the span may differ.  Sets in order of their first member."""
    dm = model.dof_map()
    keys: dict[str, list[int]] = {}
    for p in dm.whirling():
        prop = (model.propellers[p.number].propeller if hasattr(model, "propellers")
                else model.propeller)
        keys.setdefault(f"{prop!r}|{p.rotation}|{p.spinning}", []).append(p.number + 1)
    return [tuple(g) for g in keys.values()]


#: mode families, in the order of the legends (:func:`mode_family`)
FAMILIES = ("wing bending", "wing torsion", "backward whirl", "forward whirl", "in-plane",
            "other")


def mode_family(label: str, content: Mapping[str, float] | None = None) -> str:
    """Family of a mode named ``label`` (:data:`FAMILIES`): the one classifier of the V-g-f
    and Campbell diagrams and the Campbell result.

    "backward"/"forward" in the name (the thesis's "backward 3" or "backward whirl,
    propellers 1–6 (collective)"): that whirl family; "in-plane" or "edgewise" in it:
    "in-plane"; an aerodynamic lag root (:func:`is_lag`): "other"; any other mode: "wing
    torsion" where ``content`` (kinetic-energy shares by group, :func:`mode_content`) has more
    torsion than bending, "wing bending" where it has bending or the name is a wing mode's
    ("wing 2": no content, no torsion to tell), otherwise "other".

    Examples
    --------
    >>> mode_family("backward whirl, propellers 1–6 (collective)")
    'backward whirl'
    >>> mode_family("wing 2", {"bending": 0.2, "torsion": 0.7}), mode_family("wing 2")
    ('wing torsion', 'wing bending')
    >>> mode_family("lag 3"), mode_family("plunge")
    ('other', 'other')
    """
    if is_lag(label):
        return "other"
    low = label.lower()
    for word, fam in (("backward", "backward whirl"), ("forward", "forward whirl"),
                      ("in-plane", "in-plane"), ("edgewise", "in-plane")):
        if word in low:
            return fam
    c = content or {}
    tors, bend = float(c.get("torsion", 0.0)), float(c.get("bending", 0.0))
    if tors > bend:
        return "wing torsion"
    if bend > 0.0 or low.startswith("wing"):
        return "wing bending"
    return "other"


def with_content(label: str, content: str) -> str:
    """A mode's name with its dominant content, e.g. "wing 2 (torsion)"; a name that ends in its
    own parenthesis takes the content inside it: "backward whirl, propellers 1–6 (1 of 6;
    pitch)".  No content: the name as it is.

    Examples
    --------
    >>> with_content("wing 2", "torsion")
    'wing 2 (torsion)'
    >>> with_content("backward whirl, propellers 1–6 (2 of 6)", "pitch")
    'backward whirl, propellers 1–6 (2 of 6; pitch)'
    """
    if not content:
        return label
    if label.endswith(")"):
        return f"{label[:-1]}; {content})"
    return f"{label} ({content})"


def numbers_text(numbers: Sequence[int]) -> str:
    """'propeller 7', 'propellers 1–6', 'propellers 1, 3–4' (numbers from 1).

    >>> numbers_text([1, 2, 3, 5]), numbers_text([7])
    ('propellers 1–3, 5', 'propeller 7')
    """
    ns = sorted(set(int(n) for n in numbers))
    runs: list[list[int]] = []
    for n in ns:
        if runs and n == runs[-1][-1] + 1:
            runs[-1].append(n)
        else:
            runs.append([n])
    text = ", ".join(f"{r[0]}" if len(r) == 1 else f"{r[0]}–{r[-1]}" for r in runs)
    return f"propeller{'s' if len(ns) > 1 else ''} {text}"


#: Phase coherence |Σ_j x̂_j| / Σ_j |x̂_j| over a set's propellers (x̂_j = (θ̂_j, ψ̂_j)) at and
#: above which a mode of that set is "collective": every propeller in phase [-].
COLLECTIVE_COHERENCE = 0.9


def propeller_names(model: Model, sw: Sweep, names: Sequence[str],
                    whirls: Sequence[int], in_vacuo=None) -> list[str]:
    """``names`` with the whirl modes ``whirls`` (mode ids of ``sw``) named by their propellers
    at the first speed V0 of the sweep (module docstring), from the modes' kinetic-energy
    shares (:func:`propwhirl.analysis.participation.participation`):

    * the set: of the sets of identical propellers (:func:`propeller_sets`), the one whose
      propellers' shares add up to most;
    * the sense: the whirl sense ("forward"/"backward") of most of that set's share (each
      propeller's orbit relative to its own rotation); the thesis's sense of the name (how the
      frequency moves as the rotors spin up) where the orbits give none;
    * the place: the set's modes of one sense, by increasing frequency at V0, "(k of n)" when
      there are n ≥ 2 of them; ", collective" when every propeller of a set of several moves
      in phase (coherence ≥ :data:`COLLECTIVE_COHERENCE`).

    ``in_vacuo``: the model without aerodynamics, already assembled (:func:`named_modes`).
    """
    out = list(names)
    if not whirls:
        return out
    dm = model.dof_map()
    lam0 = sw.eigenvalues[0]
    X0 = sw.eigenvectors[0]
    part = mode_participation(model, X0[:, list(whirls)], lam0[list(whirls)], float(sw.V[0]),
                              in_vacuo)
    sets = propeller_sets(model)
    col = {int(n): j for j, n in enumerate(part.number)}
    by_number = {p.number + 1: p for p in dm.whirling()}
    q0 = X0[: dm.n_dof]
    found = {}
    for i, k in enumerate(whirls):
        share = {s: sum(float(part.share[col[n], i]) for n in s) for s in sets}
        best = max(sets, key=lambda s: share[s])
        votes = {"forward": 0.0, "backward": 0.0}
        for n in best:
            w = part.whirl[col[n], i]
            if w in votes:
                votes[w] += float(part.share[col[n], i])
        thesis_kind = names[k].split()[0]
        sense = max(votes, key=lambda w: votes[w]) if any(votes.values()) else thesis_kind
        x = np.array([by_number[n].pitch_yaw(q0[:, k]) for n in best])
        mags = np.linalg.norm(x, axis=1)
        coherent = (len(best) > 1 and mags.sum() > 0
                    and np.linalg.norm(x.sum(axis=0)) >= COLLECTIVE_COHERENCE * mags.sum())
        found[k] = (sense, best, coherent)
    for (sense, best), ks in _grouped(found).items():
        ks = sorted(ks, key=lambda k: (abs(lam0[k].imag), k))
        for place, k in enumerate(ks, start=1):
            tags = [f"{place} of {len(ks)}"] if len(ks) > 1 else []
            tags += ["collective"] if found[k][2] else []
            tail = f" ({', '.join(tags)})" if tags else ""
            out[k] = f"{sense} whirl, {numbers_text(best)}{tail}"
    return out


def _grouped(found: Mapping[int, tuple[str, tuple[int, ...], bool]]) -> dict:
    groups: dict[tuple[str, tuple[int, ...]], list[int]] = {}
    for k, (sense, best, _) in found.items():
        groups.setdefault((sense, best), []).append(k)
    return groups


def whirl(dm: DofMap, x: np.ndarray, lam: complex) -> str | None:
    """Whirl sense ("forward"/"backward"/"planar") of the propeller with the largest θ–ψ
    motion in the full-state vector ``x`` at eigenvalue ``lam``, relative to that propeller's
    own sense of rotation; None without spinning flexibly mounted propellers or for a real root.
    """
    props = _spinning_flexible(dm)
    if not props or abs(lam.imag) == 0:
        return None
    u = {p.number: p.pitch_yaw(x) for p in props}
    p = max(props, key=lambda p: abs(u[p.number][0]) ** 2 + abs(u[p.number][1]) ** 2)
    return whirl_sense(u[p.number][0], u[p.number][1], p.rotation, lam)


def mode_content(model: Model, sw: Sweep, names: Sequence[str],
                 in_vacuo=None) -> dict[str, dict[str, float]]:
    """Kinetic-energy shares of each structural mode (oscillatory, or a real root already
    unstable; not the lag roots, :func:`is_lag`) at the first speed of ``sw``, by content
    group, rounded to 4 digits (shares ≤ 1e-3 left out): {name: {group: share}}.  ``in_vacuo``: the model's structure
    (:func:`named_modes`; its mass, which does not depend on the speed)."""
    iv = in_vacuo_of(model, in_vacuo)
    groups = iv.system.dof_map().groups()
    X = sw.eigenvectors[0][sw.displacement]
    out = {}
    for k in range(sw.n_modes):
        if not sw.physical[0, k] or is_lag(names[k]):      # the structural modes only
            continue
        frac = kinetic_energy_shares(X[:, [k]], iv.M, groups)
        out[names[k]] = {g: round(float(f[0]), 4) for g, f in frac.items() if abs(f[0]) > 1e-3}
    return out


def shape_content(model: Model, x: np.ndarray, V: float) -> dict[str, float]:
    """Kinetic-energy shares of one shape (a state vector ``x``, its first ``n_dof`` entries
    the displacements) at speed ``V`` [m/s] by content group (:func:`kinetic_energy_shares`
    with the structural mass, aerodynamics off): {group: share}."""
    quiet = model.without_aerodynamics()
    dm = quiet.dof_map()
    s = quiet.second_order(np.array([float(V)]))
    X = np.asarray(x, dtype=complex).ravel()[: dm.n_dof, None]
    return {g: float(f[0]) for g, f in kinetic_energy_shares(X, s.S1[0], dm.groups()).items()}


def real_root_at_the_event(model: Model, label: str, x: np.ndarray, V: float) -> str:
    """What a real root named "lag k" (an aerodynamic lag state at the first speed) is at an
    event at ``V`` [m/s] with shape ``x``: e.g. "the wing (torsion 71 %, bending 29 % at the
    event; lag 5 at the first speed)" — with lag states a static divergence (λ = 0) need not
    come from a structural mode: the real branch through zero can be one that starts as a lag
    state and turns right as the speed grows.  "the wing" when the wing's bending, torsion or
    other non-mount groups hold at least half the kinetic energy, else "the propeller mounts";
    any other label is returned as it is."""
    if not label.startswith("lag "):
        return label
    shares = shape_content(model, x, V)
    if not shares or not all(np.isfinite(list(shares.values()))):
        return label
    mounts = sum(f for g, f in shares.items() if g in ("pitch", "yaw"))
    who = "the propeller mounts" if mounts > 0.5 and model.dof_map().has_wing else "the wing"
    parts = ", ".join(f"{g} {100 * f:.0f} %" for g, f in sorted(shares.items(),
                                                                key=lambda gf: -gf[1])
                      if f >= 0.005)
    return f"{who} ({parts} at the event; {label} at the first speed)"
