"""The thesis's models as a case library, one module per chapter.

Each module defines named, documented functions returning models, and registers with
:func:`propwhirl.reproduce.harness.register` the functions that recompute the thesis's numbers.
Importing this package imports every case module (so all reproduction cases register).
"""
import importlib
import pkgutil

MODULES = tuple(sorted(m.name for m in pkgutil.iter_modules(__path__)))
for _name in MODULES:
    importlib.import_module(f"{__name__}.{_name}")
