"""Models are immutable values (issue 21, item 1): evaluating a model leaves it as it was, a copy
with any field changed — through ``dataclasses.replace`` or ``with_()``, after the original was
evaluated — evaluates to the matrices of a model built fresh with that value, and no private
attribute of a model is read outside its own module."""
import ast
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import propwhirl
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass
from propwhirl.model.protocol import Evaluator, Model
from propwhirl.model.systems import PropellerWingAssembly

SPEEDS = np.array([30.0, 150.0, 290.0])


def _evaluate(model) -> tuple:
    """What a model evaluates to: its dense system at SPEEDS (every matrix, its labels) and
    its DOF map."""
    wing = getattr(model, "wing", None)
    if wing is not None and wing.aero == "dlm":     # no finite-state form: its p-k matrices
        pytest.importorskip("panelaero")
        from propwhirl.model.frequency_domain import pk_system
        return (tuple(pk_system(model, float(V))(10.0) for V in SPEEDS)[0], model.q_labels(),
                (), model.dof_map())
    s = model.second_order(SPEEDS)
    return (tuple(np.asarray(getattr(s, k)) for k in ("S1", "S2", "S3", "S4", "Ww", "Wv", "Wq")),
            s.q_labels, s.w_labels, model.dof_map())


def _same(a: tuple, b: tuple) -> bool:
    (ma, *ra), (mb, *rb) = a, b
    return (all(x.shape == y.shape and np.array_equal(x, y) for x, y in zip(ma, mb))
            and ra == rb)


def _fresh(obj):
    """``obj`` rebuilt from its constructor arguments, all the way down (new objects only)."""
    if isinstance(obj, tuple):
        return tuple(_fresh(x) for x in obj)
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return type(obj)(**{f.name: _fresh(getattr(obj, f.name))
                            for f in dataclasses.fields(obj)
                            if f.init and not f.name.startswith("_")})
    return obj


def _replace_at(model, path: tuple, changes: dict, how: str):
    """``model`` with the fields ``changes`` of the object at ``path`` replaced by
    ``dataclasses.replace`` at every level, the top level by ``how`` ("replace" or "with_")."""
    if not path:
        return dataclasses.replace(model, **changes) if how == "replace" else model.with_(**changes)
    head, rest = path[0], path[1:]
    if head == "propellers":
        j, rest = rest[0], rest[1:]
        inst = _replace_at(model.propellers[j], rest, changes, "replace")
        top = {"propellers": model.propellers[:j] + (inst,) + model.propellers[j + 1:]}
    else:
        top = {head: _replace_at(getattr(model, head), rest, changes, "replace")}
    return dataclasses.replace(model, **top) if how == "replace" else model.with_(**top)


MODEL = wingtip_propeller_wing()
WING, PROP = MODEL.wing, MODEL.propellers[0].propeller

#: (path of the object, its changed fields, whether the matrices change): every init field of
#: the PropellerWing, its Wing, FlightCondition, Installation and Propeller (and the switches)
CHANGES = [
    ((), dict(wing=dataclasses.replace(WING, EI=9e5)), True),
    ((), dict(flight=dataclasses.replace(MODEL.flight, density=0.5)), True),
    ((), dict(propellers=(dataclasses.replace(MODEL.propellers[0], y=4.56),)), True),
    ((), dict(wing_aero=False), True),
    ((), dict(propeller_aero=False), True),
    ((), dict(rotating=False), True),
    ((), dict(name="another name"), False),
    ((), dict(groups={"tip": (0,)}), False),             # names for parameter paths only
    (("wing",), dict(semi_span=6.0), True),
    (("wing",), dict(mass_per_length=30.0), True),
    (("wing",), dict(EI=8e5), True),
    (("wing",), dict(GJ=2.5e5), True),
    (("wing",), dict(root_chord=1.4), True),
    (("wing",), dict(tip_chord=0.7), True),
    (("wing",), dict(chord=lambda y: 1.3 - 0.05 * np.asarray(y)), True),
    (("wing",), dict(polar_inertia=3.0, radius_of_gyration=None), True),
    (("wing",), dict(radius_of_gyration=0.3), True),
    (("wing",), dict(elastic_axis=0.45), True),
    (("wing",), dict(centre_of_gravity=0.55), True),
    (("wing",), dict(lift_slope=5.5), True),
    (("wing",), dict(aerodynamic_centre=0.3), True),
    (("wing",), dict(n_elements=19), True),
    (("wing",), dict(stations=(2.0,)), True),
    (("wing",), dict(max_element_length=0.2), True),
    (("wing",), dict(aero_model="wagner"), True),
    (("wing",), dict(rayleigh=(0.1, 1e-4)), True),
    (("wing",), dict(EI_chordwise=1.4e7), True),
    (("wing",), dict(aero="dlm", dlm_chordwise_panels=2, dlm_spanwise_panels=6), True),
    (("wing",), dict(dlm_chordwise_panels=4), False),      # strip aerodynamics: not used
    (("wing",), dict(dlm_mach=0.3), False),                # strip aerodynamics: not used
    (("wing",), dict(compressibility="prandtl-glauert"), True),
    (("wing",), dict(compressibility="prandtl-glauert", strip_mach=0.3), True),
    (("wing",), dict(strip_mach=0.3), False),              # incompressible strips: not used
    (("wing",), dict(name="another wing"), False),
    (("flight",), dict(density=0.5), True),
    (("flight",), dict(speed_of_sound=300.0), True),
    (("flight",), dict(speed_range=(1.0, 300.0, 5.0)), False),
    (("propellers", 0), dict(propeller=dataclasses.replace(PROP, f_theta=5.0)), True),
    (("propellers", 0), dict(y=4.56), True),
    (("propellers", 0), dict(mount="rigid"), True),
    (("propellers", 0), dict(aero=False), True),
    (("propellers", 0), dict(state="stopped"), True),
    (("propellers", 0), dict(state="feathered"), True),
    (("propellers", 0), dict(rotation=-1), True),
    (("propellers", 0, "propeller"), dict(radius=0.8), True),
    (("propellers", 0, "propeller"), dict(rotor=PointMass(9.0, -1.16)), True),
    (("propellers", 0, "propeller"), dict(masses=(PointMass(36.0, -0.86),)), True),
    (("propellers", 0, "propeller"), dict(pivot_pitch=0.1), True),
    (("propellers", 0, "propeller"), dict(pivot_yaw=0.1), True),
    (("propellers", 0, "propeller"), dict(f_theta=6.0), True),
    (("propellers", 0, "propeller"), dict(f_psi=6.0), True),
    (("propellers", 0, "propeller"), dict(K_theta=2e5, f_theta=None), True),
    (("propellers", 0, "propeller"), dict(K_psi=2e5, f_psi=None), True),
    (("propellers", 0, "propeller"), dict(damping_theta=0.01), True),
    (("propellers", 0, "propeller"), dict(damping_psi=0.01), True),
    (("propellers", 0, "propeller"), dict(damping="zeta"), True),
    (("propellers", 0, "propeller"), dict(spin_inertia=0.5), True),
    (("propellers", 0, "propeller"), dict(n_blades=4), True),
    (("propellers", 0, "propeller"), dict(hub_radius=0.15), True),
    (("propellers", 0, "propeller"), dict(blade_chord=0.1), True),
    (("propellers", 0, "propeller"), dict(operation="constant-speed", rpm=2000.0), True),
    (("propellers", 0, "propeller"), dict(beta_075_deg=30.0), True),
    (("propellers", 0, "propeller"), dict(zero_lift_angle_deg=-2.0), True),
    (("propellers", 0, "propeller"), dict(advance_rule="blade_element"), True),
    (("propellers", 0, "propeller"), dict(inertia={"I_theta_P": 20.0}), True),
    (("propellers", 0, "propeller"), dict(derivatives=MeasuredDerivatives({"CZ_theta": -3.0})), True),
    (("propellers", 0, "propeller"), dict(aero_settings=dataclasses.replace(
        PROP.aero_settings, wake=False)), True),
    (("propellers", 0, "propeller"), dict(rotation=-1), True),
    (("propellers", 0, "propeller"), dict(name="another propeller"), False),
]


def _init_fields(obj) -> set[str]:
    return {f.name for f in dataclasses.fields(obj) if f.init and not f.name.startswith("_")}


def test_the_table_changes_every_field_of_every_model_dataclass():
    covered: dict[tuple, set] = {}
    for path, changes, _ in CHANGES:
        covered.setdefault(path[:1] if path[:1] != ("propellers",) else path[:1] + path[2:],
                           set()).update(changes)
    assert covered[()] == _init_fields(MODEL)
    assert covered[("wing",)] == _init_fields(WING)
    assert covered[("flight",)] == _init_fields(MODEL.flight)
    assert covered[("propellers",)] == _init_fields(MODEL.propellers[0])
    assert covered[("propellers", "propeller")] == _init_fields(PROP)


@pytest.fixture(scope="module")
def evaluated():
    """The model, evaluated (whatever an evaluation might keep, it has kept), and its result."""
    m = wingtip_propeller_wing()
    r0 = _evaluate(m)
    m.without_aerodynamics().second_order(SPEEDS)
    m.assembly()
    return m, r0


@pytest.mark.parametrize("how", ["replace", "with_"])
@pytest.mark.parametrize("path, changes, matters", CHANGES,
                         ids=[f"{'.'.join(map(str, p)) or 'model'}:{','.join(c)}"
                              for p, c, _ in CHANGES])
def test_a_changed_field_evaluates_as_a_fresh_model(evaluated, how, path, changes, matters):
    m, r0 = evaluated
    changed = _replace_at(m, path, changes, how)
    fresh = _fresh(changed)
    r1 = _evaluate(changed)
    assert _same(r1, _evaluate(fresh))
    assert _same(_evaluate(m), r0)                      # the original is as it was
    assert _same(r1, r0) is not matters


def _state(m) -> dict:
    """Every attribute of ``m``: the object, and for a container what it holds."""
    return {k: (x, sorted(map(repr, x)) if isinstance(x, (dict, list, set)) else None)
            for k, x in vars(m).items()}


def test_evaluating_a_model_leaves_it_as_it_was():
    for m in (wingtip_propeller_wing(), isolated_baseline_propeller()):
        before = _state(m)
        _evaluate(m)
        m.without_aerodynamics()
        m.assembly()
        m.state_matrix(SPEEDS)
        after = _state(m)
        assert after.keys() == before.keys()
        assert all(after[k][0] is x and after[k][1] == held for k, (x, held) in before.items())


def test_an_assembly_is_built_anew_and_its_parts_are_read_only():
    m = wingtip_propeller_wing()
    a, b = m.assembly(), m.assembly()
    assert isinstance(a, PropellerWingAssembly) and a is not b
    assert isinstance(a, Evaluator) and isinstance(m, Model)
    assert isinstance(isolated_baseline_propeller().assembly(), Evaluator)
    assert a.structure[0] is not b.structure[0]
    for X in a.structure + (a.keep_q, a.propellers[0].dofs):
        assert not X.flags.writeable
    with pytest.raises(TypeError):
        a.propellers[0].constants["K_theta"] = 1.0
    for x in a.propellers[0].constants.values():
        assert not isinstance(x, np.ndarray) or not x.flags.writeable
    assert not any(k in a.propellers[0].constants for k in ("V", "Omega", "CZ_theta"))


def test_with_switches_shares_only_what_the_switches_do_not_decide():
    m = wingtip_propeller_wing()
    a = m.assembly()
    q = a.with_switches(wing_aero=False, propeller_aero=False, rotating=False)
    assert q.structure is a.structure and q.propellers is a.propellers
    assert _same(_evaluate(q), _evaluate(m.with_(wing_aero=False, propeller_aero=False,
                                                  rotating=False)))
    with pytest.raises(propwhirl.validate.InputError, match="not switches"):
        a.with_switches(flight=dataclasses.replace(m.flight, density=0.5))


# ----------------------------------------------------------------------------- privates
MODEL_CLASSES = ("PropellerWing", "PropellerWingAssembly", "InstalledPropeller",
                 "IsolatedPropeller", "TypicalSection", "StateSpaceModel", "EvaluatorBase", "Wing",
                 "Propeller", "Installation", "FlightCondition", "ReducedModel")
SRC = Path(propwhirl.__file__).parent


def _private_names() -> dict[str, str]:
    """{private attribute name: module} of every model class (methods, fields, properties)."""
    out = {}
    for path in (SRC / "model").glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef) and node.name in MODEL_CLASSES:
                for item in node.body:
                    names = []
                    if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)):
                        names = [item.name]
                    elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                        names = [item.target.id]
                    names += [n.args[1].value for n in ast.walk(item)
                              if isinstance(n, ast.Call) and getattr(n.func, "attr", "") == "__setattr__"
                              and len(n.args) > 1 and isinstance(n.args[1], ast.Constant)]
                    for name in names:
                        if name.startswith("_") and not name.startswith("__"):
                            out.setdefault(name, set()).add(str(path.relative_to(SRC)))
    return out


def test_no_private_attribute_of_a_model_is_read_outside_its_module():
    private = _private_names()
    assert "_meshed_wing" in private                  # the scan sees the classes
    bad = []
    for path in SRC.rglob("*.py"):
        rel = str(path.relative_to(SRC))
        for node in ast.walk(ast.parse(path.read_text())):
            if (isinstance(node, ast.Attribute) and node.attr in private
                    and rel not in private[node.attr]
                    and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))):
                bad.append(f"{rel}:{node.lineno} .{node.attr}")
    assert not bad, bad


# ----------------------------------------------------------------------------- the other models
def _section():
    from propwhirl.model.section import TypicalSection

    return TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=10.0, omega_h=5.0,
                          omega_alpha=10.0, flight=MODEL.flight)


OTHER = [
    (isolated_baseline_propeller, dict(propeller=dataclasses.replace(PROP, f_psi=6.0)), True),
    (isolated_baseline_propeller, dict(flight=dataclasses.replace(MODEL.flight, density=0.5)), True),
    (isolated_baseline_propeller, dict(propeller_aero=False), True),
    (isolated_baseline_propeller, dict(rotating=False), True),
    (isolated_baseline_propeller, dict(name="another"), False),
    (_section, dict(b=1.2), True), (_section, dict(a=-0.1), True),
    (_section, dict(x_alpha=0.2), True), (_section, dict(r_alpha=0.6), True),
    (_section, dict(m=12.0), True), (_section, dict(omega_h=6.0), True),
    (_section, dict(omega_alpha=11.0), True),
    (_section, dict(flight=dataclasses.replace(MODEL.flight, density=0.5)), True),
    (_section, dict(Cla=5.5), True), (_section, dict(ac=-0.4), True),
    (_section, dict(aero_model="wagner"), True), (_section, dict(name="another"), False),
    (_section, dict(aero=False), True),
]


def test_the_other_table_changes_every_field_of_the_other_models():
    for build in (isolated_baseline_propeller, _section):
        assert {k for b, c, _ in OTHER if b is build for k in c} == _init_fields(build())


@pytest.mark.parametrize("how", ["replace", "with_"])
@pytest.mark.parametrize("build, changes, matters", OTHER,
                         ids=[f"{b.__name__}:{','.join(c)}" for b, c, _ in OTHER])
def test_a_changed_field_of_another_model_evaluates_as_a_fresh_model(build, changes, matters, how):
    m = build()
    r0 = _evaluate(m)
    changed = dataclasses.replace(m, **changes) if how == "replace" else m.with_(**changes)
    r1 = _evaluate(changed)
    assert _same(r1, _evaluate(_fresh(changed)))
    assert _same(r1, r0) is not matters
