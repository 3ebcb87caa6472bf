"""Where each command's work starts, replaced by a counter that raises: a test of the command
line asserts that a bad option was refused with the counter still at 0 (issue 20: every option
is checked before any analysis starts)."""
from __future__ import annotations

import importlib
import pkgutil

#: (module, attribute): the analysis entry points of the commands.
ENTRY_POINTS = [
    ("propwhirl.analysis.stability", "analyse"),
    ("propwhirl.app.run", "analyse"),
    ("propwhirl.app.run", "label_modes"),
    ("propwhirl.analysis.vibration", "campbell"),
    ("propwhirl.analysis.vibration", "model_modes"),
    ("propwhirl.studies.sweeps", "sweep"),
    ("propwhirl.studies.sweeps", "map2d"),
    ("propwhirl.studies.boundary", "neutral_curve"),
    ("propwhirl.studies.boundary", "speed_contour"),
    ("propwhirl.studies.clearance", "clearance"),
    ("propwhirl.reproduce.harness", "run"),
    ("propwhirl.model.propellers.propeller_aero", "windmilling"),
    ("propwhirl.model.propellers.propeller_aero", "constant_speed"),
]


class WorkStarted(AssertionError):
    """An analysis entry point was called."""


def _import_everything() -> None:
    """Import every propwhirl module before the patching: a module that binds an entry point
    by name on import (``from ... import analyse``) keeps the real one."""
    import propwhirl

    for info in pkgutil.walk_packages(propwhirl.__path__, "propwhirl."):
        if not info.name.endswith("__main__"):
            importlib.import_module(info.name)


def count_work(monkeypatch) -> list[str]:
    """Replace every entry point (with `monkeypatch`) by one that records its name in the
    returned list and raises :class:`WorkStarted`."""
    _import_everything()
    calls: list[str] = []
    for module, name in ENTRY_POINTS:
        def started(*args, _name=f"{module}.{name}", **kwargs):
            calls.append(_name)
            raise WorkStarted(f"{_name} called: the work started")
        monkeypatch.setattr(importlib.import_module(module), name, started)
    return calls
