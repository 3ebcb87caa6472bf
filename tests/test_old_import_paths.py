"""Old import paths keep working (issue 20, item 11; the README promises it).

Until the restructuring into subpackages (593f546, 2026-12-01) propwhirl was one flat package,
the layout of the first release (0.1.0).  Every module of that layout imports at its old
path, with every public name it had (except the few removed on purpose, listed below), and
the names the README and docs used from the old paths.  The lists are the modules' top-level
public names at 593f546^ (`git show 593f546^:src/propwhirl/NAME.py`).
"""
from __future__ import annotations

import importlib
import importlib.util
import subprocess
import sys

import pytest

#: Public top-level names of each module of the flat layout (git 593f546^).
OLD_NAMES: dict[str, str] = {
    "propwhirl.aero": "DERIVATIVE_NAMES theodorsen Distribution PropellerGeometry AeroSettings "
                      "PropellerDerivatives derivatives constant_speed AdvanceRule "
                      "advance_ratio_from_blade_angle windmilling HouboltReedSource "
                      "houbolt_reed_source",
    "propwhirl.analysis": "DEFAULT_SPEEDS Instability ModelAnalysis load analyse "
                          "speed_and_frequency first_of_kind",
    "propwhirl.assembly": "WING_DOF_NAMES element_dofs scatter wing_structure free_dofs "
                          "wing_dof_labels place LAG_STATES wing_aero",
    "propwhirl.cli": "CASES case_model speed_grid build_parser main",
    "propwhirl.io": "FORMAT FORMAT_VERSION UNIT_SUFFIXES dumps save_model loads load_model "
                    "VGF_COLUMNS write_vgf_csv read_vgf_csv model_fields",
    "propwhirl.mainjob": "VGF_MODES THESIS_EVENTS THESIS_MODES headline_model describe mode_lines "
                         "event_lines write_plots main",
    "propwhirl.model": "FlightCondition Installation node_at PropellerWing IsolatedPropeller "
                       "TypicalSection",
    "propwhirl.plots": "FLUTTER_COLOUR DIVERGENCE_COLOUR INSTALL_HINT save select_modes vgf "
                       "campbell campbell_diagram mode_shape event_eigenvector event_mode_shape "
                       "time_history",
    "propwhirl.propeller": "CROSS_DERIVATIVES DerivativeSource MeasuredDerivatives PointMass "
                           "Propeller",
    "propwhirl.response": "THESIS_RESPONSE_SPEEDS Response simulate rotation_sign "
                          "baseline_propeller_responses",
    "propwhirl.stability": "StateMatrixFn single_thread_blas eigen eigenvalues mac "
                           "state_matrix_from_mck second_order_labels TrackingOptions Sweep "
                           "CriticalPoint Hump Criticals Analysis ANALYSE_INITIAL_STEP sweep "
                           "tracked_eigenvalue critical_points analyse orbit_signed_area "
                           "rotation_sign_from_gyroscopic whirl_sense content dominant "
                           "TimeResponse time_response",
    "propwhirl.statespace": "SecondOrder check_finite state_matrix",
    "propwhirl.validate": "InputError finite positive non_negative in_range integer_at_least "
                          "increasing",
    "propwhirl.vibration": "Modes undamped_modes wing_modes torsion_fraction classify_wing_modes "
                           "model_modes label_modes campbell",
    "propwhirl.wing": "Spanwise LiftSlope TWO_PI Wing",
}

#: Names removed on purpose since (not restored): what replaced them.
REMOVED = {
    "propwhirl.assembly.call": "fa81c86: unused since the runtime calls the generated blocks",
    "propwhirl.response.campbell_table": "153c06a: the tracked Campbell diagram, "
                                         "propwhirl.analysis.vibration.campbell",
    "propwhirl.vibration.energy_fractions": "3242edc: the Model protocol's DOF map "
                                            "(model.dof_map(), kinetic-energy shares)",
    "propwhirl.analysis.CONTENT_GROUPS": "3242edc: the Model protocol's DOF map",
}
# propwhirl.model.SPEED_OF_SOUND_8000FT is at propwhirl.model.flight (model/__init__.py does
# not re-export it; not this item's file).

#: (old path, name) the README and docs used at some time (git log -p README.md docs/).
DOCUMENTED = [
    ("propwhirl.aero", "advance_ratio_from_blade_angle"),     # docs/validation.md
    ("propwhirl.stability", "analyse"), ("propwhirl.stability", "Sweep"),
    ("propwhirl.vibration", "label_modes"), ("propwhirl.vibration", "classify_wing_modes"),
    ("propwhirl.wing", "Wing"), ("propwhirl.propeller", "Propeller"),
    ("propwhirl.analysis", "analyse"), ("propwhirl.analysis", "load"),
    ("propwhirl.analysis", "critical"), ("propwhirl.analysis", "ModelAnalysis"),
    ("propwhirl.analysis", "Instability"),
    ("propwhirl.io", "load_model"), ("propwhirl.io", "save_model"),
    ("propwhirl.model", "Wing"), ("propwhirl.model", "Propeller"),
    ("propwhirl.model", "PropellerWing"), ("propwhirl.model", "IsolatedPropeller"),
    ("propwhirl.model", "TypicalSection"), ("propwhirl.model", "FlightCondition"),
    ("propwhirl.model", "PointMass"), ("propwhirl.model", "Installation"),
    ("propwhirl.cli", "main"),                                 # the former console script
    ("propwhirl", "critical"), ("propwhirl", "load_model"), ("propwhirl", "save_model"),
]


@pytest.mark.parametrize("path", sorted(OLD_NAMES))
def test_every_old_module_imports_with_its_names(path):
    module = importlib.import_module(path)
    missing = [n for n in OLD_NAMES[path].split() if not hasattr(module, n)]
    assert not missing, f"{path} lacks {missing}"


@pytest.mark.parametrize("path, name", DOCUMENTED)
def test_the_documented_names_import_from_their_old_paths(path, name):
    assert hasattr(importlib.import_module(path), name)


def test_old_paths_give_the_objects_of_the_new_ones():
    """Re-exports, not copies: isinstance and equality hold across old and new paths."""
    from propwhirl import aero, stability, vibration
    from propwhirl.analysis import vibration as new_vibration
    from propwhirl.engine import analyse
    from propwhirl.model.propellers import propeller_aero

    assert aero.HouboltReedSource is propeller_aero.HouboltReedSource
    assert stability.analyse is analyse
    assert vibration.label_modes is new_vibration.label_modes


def test_import_propwhirl_vibration_in_a_fresh_interpreter():
    """The issue's reproduction: `import propwhirl.vibration` failed since the restructure."""
    code = ("import propwhirl.vibration, propwhirl.stability, propwhirl.aero, propwhirl.cli, "
            "propwhirl.mainjob, propwhirl.response, propwhirl.statespace, propwhirl.assembly")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr


def test_the_removed_names_are_not_silently_claimed():
    """The list of removals is honest: those names are indeed gone from the old paths."""
    for dotted in REMOVED:
        path, name = dotted.rsplit(".", 1)
        assert not hasattr(importlib.import_module(path), name), dotted


def test_one_alias_table_and_no_shim_files():
    """Issue 38, item 5: the old paths come from propwhirl.compat.ALIASES, not from two-line
    modules on the top floor; every old flat module of OLD_NAMES that is not a package today is
    in the table."""
    from pathlib import Path

    import propwhirl
    from propwhirl import compat

    top = Path(propwhirl.__file__).parent
    assert not [m for m in compat.ALIASES if (top / f"{m.split('.')[1]}.py").exists()]
    flat = {p for p in OLD_NAMES if not (top / p.split(".")[1]).is_dir()
            and not (top / f"{p.split('.')[1]}.py").exists()}
    assert flat <= set(compat.ALIASES)
    assert isinstance(importlib.util.find_spec("propwhirl.mainjob").loader, compat.AliasFinder)


@pytest.mark.parametrize("old", sorted(__import__("propwhirl.compat").compat.MOVED))
def test_a_moved_model_module_is_the_same_module_at_its_old_path(old):
    """Issue 38, item 1: model/'s modules moved into rooms (structure/, aerodynamics/,
    propellers/); the old path gives the very module (monkeypatching and module state shared),
    in a fresh interpreter too."""
    from propwhirl import compat

    assert importlib.import_module(old) is importlib.import_module(compat.MOVED[old])
    code = (f"import {old} as a, {compat.MOVED[old]} as b; assert a is b; "
            f"from {old.rsplit('.', 1)[0]} import {old.rsplit('.', 1)[1]} as c; assert c is b")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
