"""propwhirl — wing flutter, propeller whirl flutter and divergence of flexible wings carrying
flexibly mounted propellers (the method of Liu Xu, *Propeller-Wing Whirl Flutter*, TU Delft 2020).

SI units throughout.  The equations of motion are derived symbolically (``derivations/``) and
generated into plain NumPy (:mod:`propwhirl.generated`); this package assembles and analyses
them.  The data flow, one way::

    generated  →  model  →  engine  →  analysis  →  studies, reproduce  →  io, app

The main entry points are available here (imported on first use, so ``import propwhirl`` and
the command line stay fast):

=====================  ==================================================================
``analyse``            every instability of a model, tracked and named
                       (:func:`propwhirl.analysis.analyse`)
``load``               re-read a saved analysis (:func:`propwhirl.analysis.load`)
``critical``           the one definition of the critical instability
``load_model``         read a TOML model file (:func:`propwhirl.io.load_model`)
``save_model``         write a TOML model file (:func:`propwhirl.io.save_model`)
``Wing``, ``Propeller``, ``PointMass``, ``Installation``, ``FlightCondition``
                       model components (:mod:`propwhirl.model`)
``PropellerWing``, ``IsolatedPropeller``, ``TypicalSection``
                       the models (:class:`propwhirl.model.protocol.Model`)
``InputError``         the error raised for invalid input
=====================  ==================================================================

Examples
--------
>>> import propwhirl
>>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
>>> a = propwhirl.analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
>>> c = a.critical
>>> c.kind, c.label, round(c.V, 1)
('flutter', 'backward', 221.5)
"""
from importlib import import_module
from typing import Any

from propwhirl import compat as _compat

__version__ = "0.1.0"
_compat.install()              # the old import paths of the flat layout (propwhirl.compat)

_EXPORTS = {
    "analyse": "propwhirl.analysis", "load": "propwhirl.analysis",
    "critical": "propwhirl.analysis", "load_model": "propwhirl.io", "save_model": "propwhirl.io",
    "Wing": "propwhirl.model", "Propeller": "propwhirl.model", "PointMass": "propwhirl.model",
    "Installation": "propwhirl.model", "FlightCondition": "propwhirl.model",
    "PropellerWing": "propwhirl.model", "IsolatedPropeller": "propwhirl.model",
    "TypicalSection": "propwhirl.model", "Model": "propwhirl.model.protocol",
    "InputError": "propwhirl.validate",
}

__all__ = sorted(_EXPORTS) + ["__version__"]


def __getattr__(name: str) -> Any:
    """Import the public names on first use (PEP 562)."""
    if name in _EXPORTS:
        value = getattr(import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'propwhirl' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
