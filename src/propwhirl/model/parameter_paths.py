"""A model's parameter paths and, per path, how its derivative is computed: the part of the
model contract (:mod:`propwhirl.model.protocol`, issue 34 item 1) that ``propwhirl
sensitivity``, the studies' checks of a path and the capability table (docs/capabilities.md)
ask.

A model says which parameter paths it has in its capabilities
(:attr:`~propwhirl.model.protocol.Capabilities.parameters`, a key of
:data:`~propwhirl.model.protocol.PARAMETER_SETS`); :func:`parameter_paths` lists them, each a
:class:`~propwhirl.model.derivatives.Parameter` whose ``derivative`` says how ∂λ/∂p is
computed (:data:`~propwhirl.model.protocol.DERIVATIVE_ROUTES`), from :data:`PARAMETER_LISTS`:

=================================  ========================================================
parameters                         list (derivative)
=================================  ========================================================
"beam" (strip wing)                :func:`beam_parameters`: the generated blocks' parameters
                                   (:func:`propwhirl.model.derivatives.parameters`), the
                                   whole-distribution factors :data:`FACTORS` and
                                   ``flight.density`` ("exact")
"doublet lattice"                  :func:`dlm_parameters`: the same without those the
                                   panels' geometry or the strips hold ("central difference")
"in-plane" (EI_chordwise)          :func:`inplane_parameters`: the beam's ("central
                                   difference")
"modal"                            :func:`modal_parameters`: each mode's frequency, modal
                                   mass and damping, the own mounts, the spin inertias and
                                   ``flight.density`` ("central difference")
=================================  ========================================================

:func:`with_parameter` is the model with one of its parameters set to a value (the central
differences' and the verifications' variants).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

import re
from collections.abc import Callable

from propwhirl import validate as v
from propwhirl.model import derivatives as D
from propwhirl.model.protocol import capabilities
from propwhirl.model.systems import PropellerWing

#: the whole-distribution factors (the studies' scale form, :mod:`propwhirl.studies.paths`):
#: path → the per-element parameter name of :func:`propwhirl.model.derivatives.parameters`
FACTORS = {"wing.EI*": "EI", "wing.GJ*": "GJ", "wing.mass_per_length*": "mass_per_length"}
#: the air density's path (``flight.density`` [kg/m³])
DENSITY = "flight.density"
_FACTOR_DOCS = {"EI": "bending rigidity", "GJ": "torsional rigidity",
                "mass_per_length": "mass per unit span"}
#: the element properties' keys of :meth:`~propwhirl.model.structure.wing.Wing.element_properties`
_ELEMENT_KEYS = {"EI": "EI", "GJ": "GJ", "mass_per_length": "m"}
#: the section fields a doublet-lattice wing's central differences cover: the structural
#: ones.  The chords and the elastic axis move the panels (new AICs for every variant), the
#: aerodynamic centre and the lift slope are the strips' (the panels do not read them).
DLM_SECTION_FIELDS = ("centre_of_gravity", "polar_inertia", "radius_of_gyration")


def _extras(model, derivative: str) -> list[D.Parameter]:
    """The factors :data:`FACTORS` (value 1, kind "factor") and ``flight.density``."""
    out = [D.Parameter(path, "factor", -1, name, 1.0, "",
                       f"factor on the whole {_FACTOR_DOCS[name]} distribution (every element; "
                       "1 = as given)", derivative)
           for path, name in FACTORS.items()]
    out.append(D.Parameter(DENSITY, "flight", -1, "density", float(model.flight.density),
                           "kg/m^3", "air density", derivative))
    return out


def beam_parameters(model: PropellerWing) -> tuple[D.Parameter, ...]:
    """A strip wing's parameters, all with exact derivatives: those of
    :func:`propwhirl.model.derivatives.parameters`, then the whole-distribution factors
    :data:`FACTORS` (value 1, kind "factor") and ``flight.density`` [kg/m³] (kind "flight")."""
    return tuple(D.parameters(model)) + tuple(_extras(model, "exact"))


def dlm_parameters(model: PropellerWing) -> tuple[D.Parameter, ...]:
    """A doublet-lattice wing's parameters, their derivatives central differences (of its
    critical eigenvalue, :func:`propwhirl.analysis.sensitivity.critical_sensitivities`): the
    beam parameters of :func:`beam_parameters` but the lift slopes and the sections' chords,
    elastic axis and aerodynamic centre (:data:`DLM_SECTION_FIELDS`), so that every variant
    has the panels of the model: one set of AICs for all."""
    keep = []
    for p in D.parameters(model, check=False):
        if p.kind == "node" or (p.kind == "section" and p.name not in DLM_SECTION_FIELDS):
            continue
        keep.append(replace(p, derivative="central difference"))
    return tuple(keep) + tuple(_extras(model, "central difference"))


def inplane_parameters(model: PropellerWing) -> tuple[D.Parameter, ...]:
    """A strip wing with in-plane bending (``EI_chordwise``): the paths of
    :func:`beam_parameters`, each by central differences of its state matrix (its analyses'
    crossings are roots of the full order: :func:`propwhirl.analysis.sensitivity.
    difference_sensitivities`); the generated derivatives have no in-plane blocks."""
    cd = "central difference"
    return (tuple(replace(p, derivative=cd) for p in D.parameters(model, check=False))
            + tuple(_extras(model, cd)))


def modal_parameters(model) -> tuple[D.Parameter, ...]:
    """The parameters of a modal model (:class:`~propwhirl.model.modal.ModalPropellerWing`),
    their derivatives central differences of its state matrix, each a parameter path of the
    studies (:mod:`propwhirl.studies.paths`): every mode's frequency
    ``structure.frequencies_hz[i]`` [Hz], modal mass ``structure.modal_mass[i]`` [kg] and
    damping ratio ``structure.damping_ratio[i]`` (kind "modal", index the mode from 0); each
    flexibly mounted propeller's mount stiffness (``f_theta``/``f_psi`` [Hz], or
    ``K_theta``/``K_psi`` [N m/rad], whichever the propeller gives) and damping
    (``damping_theta``, ``damping_psi``), and every turning propeller's spin inertia
    ``spin_inertia`` [kg m²] (kind "propeller", index the installation) — an on-grid
    mount's springs and mass are in the modes —; ``flight.density`` [kg/m³] (kind "flight")."""
    cd = "central difference"
    s = model.structure
    out = []
    for name, unit, doc in (("frequencies_hz", "Hz", "natural frequency"),
                            ("modal_mass", "kg", "modal mass"),
                            ("damping_ratio", "", "modal damping ratio")):
        for i in range(s.n_modes):
            out.append(D.Parameter(f"structure.{name}[{i}]", "modal", i, name,
                                   float(getattr(s, name)[i]), unit, f"{doc} of mode {i + 1}",
                                   cd))
    for j, inst in enumerate(model.propellers):
        prop, pre = inst.propeller, f"propellers[{j}].propeller."
        if inst.mount == "flexible":
            for ax in ("theta", "psi"):
                f = getattr(prop, f"f_{ax}")
                name, unit = (f"f_{ax}", "Hz") if f is not None else (f"K_{ax}", "N m/rad")
                out.append(D.Parameter(pre + name, "propeller", j, name,
                                       float(getattr(prop, name)), unit, f"{ax} mount "
                                       + ("frequency" if f is not None else "stiffness"), cd))
                out.append(D.Parameter(pre + f"damping_{ax}", "propeller", j, f"damping_{ax}",
                                       float(getattr(prop, f"damping_{ax}")), "",
                                       f"{ax} mount damping ({prop.damping})", cd))
        if model.rotating:
            out.append(D.Parameter(pre + "spin_inertia", "propeller", j, "spin_inertia",
                                   float(prop.I_Omega), "kg m^2", "spin inertia I_Omega", cd))
    out.append(D.Parameter(DENSITY, "flight", -1, "density", float(model.flight.density),
                           "kg/m^3", "air density", cd))
    return tuple(out)


#: :attr:`Capabilities.parameters <propwhirl.model.protocol.Capabilities.parameters>` → the
#: function listing them ("none": no list)
PARAMETER_LISTS: dict[str, Callable[..., tuple[D.Parameter, ...]]] = {
    "beam": beam_parameters, "doublet lattice": dlm_parameters,
    "in-plane": inplane_parameters, "modal": modal_parameters}


def parameter_paths(model) -> tuple[D.Parameter, ...]:
    """The parameters ``model`` has sensitivities for, each a
    :class:`~propwhirl.model.derivatives.Parameter` (its path, value, unit, meaning and
    ``derivative``, one of :data:`~propwhirl.model.protocol.DERIVATIVE_ROUTES`): the list its
    capabilities name (:attr:`~propwhirl.model.protocol.Capabilities.parameters`,
    :data:`PARAMETER_LISTS`); () for a model without sensitivities (an isolated propeller, a
    typical section, in-plane bending, a model of its own class).  The one list ``propwhirl
    sensitivity``, its ``--list`` and ``--param``, the sensitivities' checks and the
    capability table read.

    Examples
    --------
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> ps = parameter_paths(wingtip_propeller_wing())
    >>> ps[0].path, ps[0].unit, ps[0].derivative
    ('wing.EI[0]', 'N m^2', 'exact')
    """
    key = capabilities(model).parameters
    return () if key == "none" else tuple(PARAMETER_LISTS[key](model))


def parameter_families(model) -> tuple[tuple[str, str, int], ...]:
    """(family, derivative, number of paths) of :func:`parameter_paths`, in order of first
    appearance: each path with its numeric indices as ``[i]`` (``wing.EI[i]``,
    ``propellers[i].propeller.f_theta``)."""
    out: dict[tuple[str, str], int] = {}
    for p in parameter_paths(model):
        key = (re.sub(r"\[\d+\]", "[i]", p.path), p.derivative)
        out[key] = out.get(key, 0) + 1
    return tuple((f, d, n) for (f, d), n in out.items())


def with_parameter(model, p: D.Parameter, value: float):
    """``model`` with its parameter ``p`` (of its ``parameter_paths()``) set to ``value`` [its
    unit], everything else unchanged; the model's own checks apply (a value outside a field's
    range is an InputError).  A factor of :data:`FACTORS` scales every element's value of its
    distribution (as a per-element array); a modal model's mode fields are arrays of the
    structure; every other beam parameter as :func:`propwhirl.model.derivatives.with_value`."""
    value = float(value)
    if p.kind == "flight":
        return model.with_(flight=replace(model.flight, density=value))
    if p.kind == "modal":
        arr = np.array(getattr(model.structure, p.name), dtype=float)
        arr[p.index] = value
        return model.with_(structure=replace(model.structure, **{p.name: arr}))
    if p.kind == "factor":
        wing = model.wing
        arr = wing.element_properties()[_ELEMENT_KEYS[p.name]] * value
        return model.with_(wing=replace(wing, **{p.name: arr}))
    if isinstance(model, PropellerWing):
        return D.with_value(model, p.path, value)
    if p.kind != "propeller":
        raise v.InputError(f"parameter = {p.path!r} is invalid: not a parameter of this model")
    installs = list(model.propellers)
    inst = installs[p.index]
    installs[p.index] = replace(inst, propeller=replace(inst.propeller, **{p.name: value}))
    return model.with_(propellers=tuple(installs))


__all__ = ["DENSITY", "DLM_SECTION_FIELDS", "FACTORS", "PARAMETER_LISTS", "beam_parameters",
           "dlm_parameters", "inplane_parameters", "modal_parameters", "parameter_families", "parameter_paths",
           "with_parameter"]
