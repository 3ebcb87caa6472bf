"""Old import paths: the one alias table (issue 38, item 5).

The first release (0.1.0) was one flat package; its modules moved into the sub-packages (model/,
engine/, analysis/, app/, reproduce/), and model/'s modules into its rooms (structure/,
aerodynamics/, propellers/: :data:`MOVED`, the very module at its old path).  Users' scripts and notebooks keep importing them at
their old paths — ``import propwhirl.vibration``, ``from propwhirl.wing import Wing``,
``from propwhirl.cli import main`` — through :data:`ALIASES`: each old module is made, on its
first import, from the public names of the modules it moved to (what ``from X import *``
gives: ``__all__``, else every name without a leading underscore) and the listed names of
others.  The alias module's names are the new modules' own objects (re-exports, not copies).
:func:`install` (called by ``import propwhirl``) puts the finder on ``sys.meta_path``;
``tests/test_old_import_paths.py`` imports every old path with its old names.
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
from types import ModuleType

#: old module → the modules its names come from: (new module, None for its public names, or
#: the names taken from it)
ALIASES: dict[str, tuple[tuple[str, tuple[str, ...] | None], ...]] = {
    "propwhirl.aero": (("propwhirl.model.propellers.propeller_aero", None),),
    "propwhirl.assembly": (("propwhirl.model.structure.assembly", None),),
    "propwhirl.propeller": (("propwhirl.model.propellers.propeller", None),),
    "propwhirl.wing": (("propwhirl.model.structure.wing", None),),
    "propwhirl.statespace": (("propwhirl.model.statespace", None),),
    "propwhirl.stability": (
        ("propwhirl.analysis.whirl", ("content", "dominant", "orbit_signed_area",
                                      "rotation_sign_from_gyroscopic", "whirl_sense")),
        ("propwhirl.engine", None),
        ("propwhirl.engine.eigensolve", ("StateMatrixFn",)),
        ("propwhirl.model.statespace", ("second_order_labels", "state_matrix_from_mck"))),
    "propwhirl.vibration": (("propwhirl.analysis.vibration", None),),
    "propwhirl.response": (
        ("propwhirl.analysis.response", None),
        ("propwhirl.reproduce.ch09", ("THESIS_RESPONSE_SPEEDS", "baseline_propeller_responses"))),
    "propwhirl.cli": (("propwhirl.app.cli", None),
                      ("propwhirl.cases.registry", ("CASES", "case_model"))),
    "propwhirl.plots": (("propwhirl.app.plots", None),),
    "propwhirl.mainjob": (("propwhirl.app.run", None),),
}


#: modules moved whole (issue 38, item 1: model/ in rooms named for the physics): the old path
#: IS the new module (the same object in ``sys.modules``: its state, monkeypatching and
#: ``isinstance`` shared), not a copy of its names
MOVED: dict[str, str] = {
    f"propwhirl.model.{name}": f"propwhirl.model.{room}.{name}"
    for room, names in {
        "structure": ("wing", "mesh", "assembly"),
        "aerodynamics": ("theodorsen", "dlm", "dlm_mesh", "dlm_cache", "dlm_rfa", "validity"),
        "propellers": ("propeller", "propeller_aero", "derivatives_blade"),
    }.items() for name in names}


def public_names(module: ModuleType) -> list[str]:
    """The names ``from module import *`` binds: ``__all__``, else those without a leading
    underscore."""
    names = getattr(module, "__all__", None)
    return list(names) if names is not None else [n for n in vars(module) if n[:1] != "_"]


class AliasFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds and builds the old modules of :data:`ALIASES` and :data:`MOVED` (nothing else)."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname not in ALIASES and fullname not in MOVED:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        return None                                   # the default module object

    def exec_module(self, module: ModuleType) -> None:
        if module.__name__ in MOVED:       # the import system returns what sys.modules holds
            sys.modules[module.__name__] = importlib.import_module(MOVED[module.__name__])
            return
        sources = ALIASES[module.__name__]
        for target, names in sources:
            new = importlib.import_module(target)
            for name in public_names(new) if names is None else names:
                setattr(module, name, getattr(new, name))
        moved = ", ".join(f":mod:`{t}`" for t, _ in sources)
        module.__doc__ = (f"Compatibility: `{module.__name__}` moved to {moved} (kept for "
                          "users' scripts; propwhirl.compat.ALIASES).")


def install() -> None:
    """Put one :class:`AliasFinder` on ``sys.meta_path`` (idempotent)."""
    if not any(isinstance(f, AliasFinder) for f in sys.meta_path):
        sys.meta_path.append(AliasFinder())
