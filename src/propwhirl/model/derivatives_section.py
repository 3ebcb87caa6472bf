"""The chain rule from a wing's section fields to its element and node properties.

The generated beam element takes, per element, x_α b and ρI_p (with m, EI, GJ, the length),
the generated strip aerodynamics, per node, b, a and a_c (with C_lα), and a propeller the
elastic axis a_P b_P at its node (:meth:`~propwhirl.model.structure.wing.Wing.element_properties`,
:meth:`~propwhirl.model.structure.wing.Wing.node_properties`,
:func:`~propwhirl.model.propeller_blocks.propeller_constants`):

    x_α b = (x_cg − x_ea) c                       (elements; chord fractions from the LE)
    ρI_p  = m ((r_g c)² + (x_α b)²)               (with a radius of gyration; else given)
    b = c/2,  a = 2 x_ea − 1,  a_c = 2 x_ac − 1   (nodes)
    a_P b_P = a b                                  (the propeller's node)

so a section field moves these together.  :func:`chain` gives, for one field, the exact
derivatives of x_α b and ρI_p at every element and of b, a, a_c at every node (zero where the
field does not reach); :mod:`propwhirl.model.derivatives` multiplies them into the generated
``blocks_d`` of the beam element and the strip aerodynamics and into the propeller's
``inertia_d`` and ``e_alpha_geometry_d``.

Fields (`wing` = ``model.wing``, the meshed wing; e an element, i a node):

==================================  ===============================================================
``wing.root_chord``                 c(y) = c_r + (c_t − c_r) y/L: ∂c/∂c_r = 1 − y/L (1 when no tip
                                    chord is given: the tip chord follows the root's) [m]
``wing.tip_chord``                  ∂c/∂c_t = y/L (its value: the root chord when not given) [m]
``wing.chord[i]``                   the chord at node i, the chord piecewise linear between the
                                    nodes (element e's chord is the mean of its nodes') [m]
``wing.centre_of_gravity[e]``       x_cg of element e [chord]: x_α b, and ρI_p with r_g
``wing.elastic_axis[e]``            x_ea of element e [chord]: x_α b, ρI_p with r_g, and a at the
                                    nodes through the linear interpolation between element
                                    mid-points (:func:`propwhirl.model.structure.wing._node_value`), hence
                                    a_P b_P of a propeller there
``wing.aerodynamic_centre[e]``      x_ac of element e [chord]: a_c at the nodes (interpolated)
``wing.polar_inertia[e]``           ρI_p of element e [kg m] (when the wing gives it)
``wing.radius_of_gyration[e]``      r_g of element e [chord] (when the wing gives it):
                                    ∂ρI_p = 2 m r_g c²
==================================  ===============================================================

The chord paths need the linear taper (no ``chord`` function; the node chords also a chord
through node values, :class:`NodeChord`, as :func:`with_value` leaves it); ``elastic_axis[e]`` and
``aerodynamic_centre[e]`` a number or one value per element (a function of y is evaluated at
the nodes themselves, which a value per element would not reproduce).  :func:`with_value`
is the wing with one field set (the chord at a node: a chord function through the node
values, equal to the taper everywhere else).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from propwhirl.generated import beam_element, strip_aero
from propwhirl.model.aerodynamics.compressibility import lift_slope_factor, lift_slopes
from propwhirl.model.structure.assembly import LAG_STATES, STRIP_AERO, element_dofs
from propwhirl.model.blocks import LagBlocks, LocalBlocks
from propwhirl.model.structure.wing import Wing

#: the per-element fields: (field, unit, meaning)
_ELEMENT_FIELDS = (("centre_of_gravity", "chord", "centre-of-gravity position"),
                   ("elastic_axis", "chord", "elastic-axis position"),
                   ("aerodynamic_centre", "chord", "aerodynamic-centre position"),
                   ("polar_inertia", "kg m", "polar inertia about the elastic axis"),
                   ("radius_of_gyration", "chord", "radius of gyration"))
#: fields also evaluated at the nodes (a function of y cannot become per-element values)
_NODAL = ("elastic_axis", "aerodynamic_centre")


@dataclass(frozen=True)
class SectionChain:
    """∂(element and node properties)/∂(one field): ``element`` {"x_alpha_b", "rho_Ip"} of
    shape (n_elements,), ``node`` {"b", "a", "ac"} of shape (n_nodes,) (units of the property
    per unit of the field)."""

    element: dict[str, np.ndarray]
    node: dict[str, np.ndarray]


def parameters(wing: Wing) -> list[tuple[str, str, int, float, str, str]]:
    """(path, field, index, value, unit, meaning) of every section field of `wing` with
    derivatives (module docstring): index −1 for the root and tip chords."""
    out = []
    if wing.chord is None:
        tip = wing.root_chord if wing.tip_chord is None else wing.tip_chord
        out.append(("wing.root_chord", "root_chord", -1, float(wing.root_chord), "m",
                    "chord at the root"))
        out.append(("wing.tip_chord", "tip_chord", -1, float(tip), "m", "chord at the tip"))
    if wing.chord is None or (isinstance(wing.chord, NodeChord)
                              and np.array_equal(wing.chord.ys, wing.node_y)):
        c = wing.chord_at(wing.node_y)
        for i in range(wing.n_nodes):
            out.append((f"wing.chord[{i}]", "chord", i, float(c[i]), "m", f"chord at node {i}"))
    props = wing.element_properties()
    y, c = wing.element_y, wing.chord_at(wing.element_y)
    for name, unit, doc in _ELEMENT_FIELDS:
        value = getattr(wing, name)
        if value is None or (name in _NODAL and callable(value)):
            continue
        vals = _element_values(wing, name, props, y, c)
        for e in range(wing.element_count):
            out.append((f"wing.{name}[{e}]", name, e, float(vals[e]), unit,
                        f"{doc} of element {e}"))
    return out


def _element_values(wing: Wing, name: str, props: dict, y: np.ndarray,
                    c: np.ndarray) -> np.ndarray:
    """The field's value at each element (as ``element_properties`` evaluates it)."""
    if name == "polar_inertia":
        return props["rho_Ip"]
    value = getattr(wing, name)
    if callable(value):
        return np.asarray(value(y), dtype=float)
    return np.broadcast_to(np.asarray(value, dtype=float), y.shape).astype(float)


def _interpolation(wing: Wing) -> np.ndarray:
    """W (n_nodes, n_elements): node values = W @ element values, the linear interpolation
    between element mid-points of :func:`propwhirl.model.structure.wing._node_value` (exact: it is linear
    in the values)."""
    ye, yn = wing.element_y, wing.node_y
    eye = np.eye(ye.size)
    return np.stack([np.interp(yn, ye, eye[e]) for e in range(ye.size)], axis=1)


def chain(wing: Wing, name: str, index: int) -> SectionChain:
    """∂(x_α b, ρI_p at the elements; b, a, a_c at the nodes)/∂(field `name` [index]), exact
    (module docstring)."""
    ne, nn = wing.element_count, wing.n_nodes
    ye, yn, L = wing.element_y, wing.node_y, wing.semi_span
    props = wing.element_properties()
    c = wing.chord_at(ye)
    m, xab = props["m"], props["x_alpha_b"]
    rg = (None if wing.radius_of_gyration is None
          else _element_values(wing, "radius_of_gyration", props, ye, c))
    dc, dx, drg, dIp = (np.zeros(ne) for _ in range(4))   # ∂c, ∂(x_cg − x_ea), ∂r_g, ∂ρI_p given
    node = {k: np.zeros(nn) for k in ("b", "a", "ac")}
    if name in ("root_chord", "tip_chord", "chord"):
        if name == "chord":
            dcn = np.zeros(nn)
            dcn[index] = 1.0
            dc = 0.5 * (dcn[:-1] + dcn[1:])               # the mean of the element's nodes
        elif name == "tip_chord":
            dcn, dc = yn / L, ye / L
        elif wing.tip_chord is None:                      # the tip chord is the root chord
            dcn, dc = np.ones(nn), np.ones(ne)
        else:
            dcn, dc = 1.0 - yn / L, 1.0 - ye / L
        node["b"] = 0.5 * dcn
    elif name == "centre_of_gravity":
        dx[index] = 1.0
    elif name == "elastic_axis":
        dx[index] = -1.0
        node["a"] = 2.0 * _interpolation(wing)[:, index]
    elif name == "aerodynamic_centre":
        node["ac"] = 2.0 * _interpolation(wing)[:, index]
    elif name == "polar_inertia":
        dIp[index] = 1.0
    elif name == "radius_of_gyration":
        drg[index] = 1.0
    else:
        raise ValueError(f"not a section field: {name!r}")
    dxab = dx * c + (xab / c) * dc                        # x_α b = (x_cg − x_ea) c
    if rg is None:
        drho = dIp
    else:                                                 # ρI_p = m((r_g c)² + (x_α b)²)
        drho = m * (2.0 * rg * c * (drg * c + rg * dc) + 2.0 * xab * dxab)
    return SectionChain({"x_alpha_b": dxab, "rho_Ip": drho}, node)


def with_value(wing: Wing, name: str, index: int, value: float) -> Wing:
    """`wing` with the section field `name` (at element or node `index`) set to `value`
    (a per-element field becomes one value per element; the chord at a node a chord function
    through the node values)."""
    if name in ("root_chord", "tip_chord"):
        return replace(wing, **{name: value})
    if name == "chord":
        ys = wing.node_y
        c = wing.chord_at(ys)
        c[index] = value
        return replace(wing, chord=NodeChord(ys, c))
    props = wing.element_properties()
    arr = _element_values(wing, name, props, wing.element_y,
                          wing.chord_at(wing.element_y)).copy()
    arr[index] = value
    return replace(wing, **{name: arr})


@dataclass(frozen=True)
class NodeChord:
    """A chord [m] piecewise linear through `values` at the nodes `ys` [m]."""

    ys: np.ndarray
    values: np.ndarray

    def __call__(self, y):
        return np.interp(np.asarray(y, dtype=float), self.ys, self.values)


def wing_blocks(ctx, ch: SectionChain) -> tuple[list[LocalBlocks], LagBlocks | None]:
    """The derivative blocks of the wing for the chain `ch`: the touched elements' mass blocks
    Σ ∂M/∂(x_α b, ρI_p) (generated ``beam_element.blocks_d``) with the Rayleigh μ ∂M (even
    and odd elements in two groups, so that no two blocks of a group share a node) and the
    touched nodes' (i ≥ 1) strip blocks Σ ∂/∂(b, a, a_c) (generated ``strip_aero.*_blocks_d``).
    `ctx`: the derivatives' context of the model at its speeds
    (:mod:`propwhirl.model.derivatives`), whose caches of the generated derivatives it uses."""
    wing = ctx.model.wing
    if ctx.beam is None:
        ctx.beam = beam_element.blocks_d(**{a: ctx.props[a]
                                            for a in beam_element.PARTIALS["blocks_d"][0]})
    dM = sum(ch.element[a][:, None, None] * ctx.beam["mass"][a] for a in ch.element)
    mu = wing.rayleigh[0]
    touched = np.flatnonzero(np.any(dM != 0.0, axis=(1, 2)))
    dofs = element_dofs(wing.element_count)
    groups = []
    for parity in (0, 1):
        es = touched[touched % 2 == parity]
        if es.size:
            M = ctx.const(dM[es])
            groups.append(LocalBlocks(f"wing elements {parity}::2", dofs[es], M, mu * M,
                                      np.zeros_like(M)))
    lag = None
    if ctx.model.wing_aero and any(np.any(x) for x in ch.node.values()):
        block, lag = _strip_blocks(ctx, ch.node)
        groups.append(block)
    return groups, lag


def strip_partials(ctx) -> tuple[dict, np.ndarray, np.ndarray | None]:
    """(the generated ∂/∂(arguments) of the strip blocks at ``ctx``'s speeds, the strips'
    widths [m], the compressibility factor 1/β (nV,) of the lift-curve slope or None), computed
    once per context.  With ``compressibility = "prandtl-glauert"`` the strips' slope argument
    is C_lα/β (:mod:`propwhirl.model.aerodynamics.compressibility`), so ∂/∂C_lα of the wing's
    own slope is 1/β times the generated ∂/∂Cla."""
    if ctx.strip is None:
        wing = ctx.model.wing
        group, _ = STRIP_AERO[wing.aero_model]
        node = wing.node_properties()
        factor = lift_slope_factor(wing, ctx.V, ctx.model.flight.speed_of_sound)
        values = dict(rho=ctx.model.flight.density, V=ctx.V[:, None], b=node["b"],
                      a=node["a"], Cla=lift_slopes(node["Cla"], factor), ac=node["ac"])
        ctx.strip = (getattr(strip_aero, group + "_d")(**values), node["width"], factor)
    return ctx.strip


def _strip_blocks(ctx, factors: dict[str, np.ndarray]) -> tuple[LocalBlocks, LagBlocks]:
    """Σ_arg factors[arg][i] ∂(strip blocks of node i)/∂arg over the touched nodes i ≥ 1."""
    wing = ctx.model.wing
    _, roles = STRIP_AERO[wing.aero_model]
    d, width, scale = strip_partials(ctx)
    k, nn = LAG_STATES[wing.aero_model], wing.n_nodes
    nodes = np.flatnonzero(np.any([np.asarray(f) != 0.0 for f in factors.values()], axis=0))
    nodes = nodes[nodes >= 1]
    shape = {"M": (2, 2), "C": (2, 2), "K": (2, 2), "W0": (2, k), "Ww": (k, k),
             "Wv": (k, 2), "Wq": (k, 2)}

    def get(role: str) -> np.ndarray:  # (nV, nb, r, c) at the touched nodes
        out = np.zeros((ctx.nV, nodes.size) + shape[role])
        if role in roles:
            for arg, f in factors.items():
                x = d[roles[role]].get(arg)
                if x is not None:
                    x = np.broadcast_to(x, (ctx.nV, nn) + shape[role])[:, nodes]
                    if arg == "Cla" and scale is not None:    # ∂(C_lα/β)/∂C_lα = 1/β
                        x = scale[:, None, None, None] * x
                    out = out + f[nodes][None, :, None, None] * x
        return out

    w = width[nodes][None, :, None, None]
    qrows = 3 * nodes[:, None] + np.array([0, 2])[None, :]
    wrows = k * nodes[:, None] + np.arange(k)[None, :]
    block = LocalBlocks("wing strips", qrows, -w * get("M"), -w * get("C"), -w * get("K"))
    return block, LagBlocks(qrows, wrows, w * get("W0"), get("Ww"), get("Wv"), get("Wq"))
