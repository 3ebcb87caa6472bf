"""The named cases: the one table of the thesis's models by short name.

``propwhirl case NAME`` exports them, ``propwhirl run`` analyses one of them (``wingtip``), and
the reproduction (:mod:`propwhirl.reproduce`) builds its models with the same factory functions.
Each entry names its factory as ``"module:function"``; the module is imported when the model is
first asked for, so reading the table (``propwhirl --help``) imports no model code.

Examples
--------
>>> from propwhirl.cases.registry import CASES, case_model
>>> list(CASES)
['patil', 'baseline-wing', 'isolated-propeller', 'inboard', 'wingtip', 'two-propeller']
>>> CASES["wingtip"].section
'section 10.1'
>>> case_model("wingtip", mount="rigid").propellers[0].mount
'rigid'
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable

from propwhirl.validate import InputError

if TYPE_CHECKING:
    from propwhirl.model.systems import IsolatedPropeller, PropellerWing


@dataclass(frozen=True)
class NamedCase:
    """A model of the case library under a short name.

    Attributes
    ----------
    name : str
        The name on the command line, e.g. ``"wingtip"``.
    factory : str
        ``"module:function"`` of the function (in :mod:`propwhirl.cases`) returning the model.
    description : str
        One line: what the model is.
    section : str
        Where the thesis defines it, e.g. ``"section 10.1"`` or ``"Table 7.1"`` (ASCII: the command
        line prints it).

    Examples
    --------
    >>> from propwhirl.cases import CASES
    >>> case = CASES["isolated-propeller"]
    >>> case.summary
    'baseline propeller on a rigid wing (section 9.2)'
    >>> case.model().propeller.radius                    # rotor radius [m]
    0.762
    """

    name: str
    factory: str
    description: str
    section: str

    def function(self) -> Callable[..., PropellerWing | IsolatedPropeller]:
        """The factory function (its module imported on first use)."""
        module, function = self.factory.split(":")
        return getattr(importlib.import_module(module), function)

    def model(self, **options: Any) -> PropellerWing | IsolatedPropeller:
        """The model, built by the factory with `options` (e.g. ``mount="rigid"``)."""
        return self.function()(**options)

    @property
    def summary(self) -> str:
        """``description (section)``, the one line ``propwhirl case`` prints."""
        return f"{self.description} ({self.section})"


_TABLE = (
    NamedCase("patil", "propwhirl.cases.ch07_patil:patil_model",
              "Patil HALE wing", "Table 7.1"),
    NamedCase("baseline-wing", "propwhirl.cases.ch09_baseline:baseline_wing_model",
              "baseline wing alone", "Table 9.1"),
    NamedCase("isolated-propeller", "propwhirl.cases.ch09_baseline:isolated_baseline_propeller",
              "baseline propeller on a rigid wing", "section 9.2"),
    NamedCase("inboard", "propwhirl.cases.ch09_baseline:inboard_propeller_wing",
              "baseline wing with the propeller at 1.6 m", "section 9.3"),
    NamedCase("wingtip", "propwhirl.cases.ch10_other_wings:wingtip_propeller_wing",
              "baseline wing with a wingtip propeller - the headline case", "section 10.1"),
    NamedCase("two-propeller", "propwhirl.cases.ch10_other_wings:two_propeller_wing",
              "baseline wing with propellers at 1.6 m and the tip", "section 10.2"),
)

#: The named cases in the order ``propwhirl case --help`` lists them.
CASES: dict[str, NamedCase] = {c.name: c for c in _TABLE}


def get(name: str) -> NamedCase:
    """The named case `name`.

    Raises
    ------
    InputError
        One line listing the valid names when `name` is not one of them.
    """
    try:
        return CASES[name]
    except KeyError:
        raise InputError(f"case = {name!r} is invalid: must be one of {', '.join(CASES)}") from None


def case_model(name: str, **options: Any) -> PropellerWing | IsolatedPropeller:
    """The model of the named case `name`, built with `options` (see :meth:`NamedCase.model`).

    Parameters
    ----------
    name : str
        A name of :data:`CASES` (``"wingtip"``, ``"patil"``, ...).
    **options
        Keyword arguments of the case's factory (e.g. ``mount="rigid"``).

    Returns
    -------
    PropellerWing or IsolatedPropeller
        The model (SI units).

    Raises
    ------
    InputError
        An unknown name (the error lists the valid ones).

    Examples
    --------
    >>> from propwhirl.cases import case_model
    >>> m = case_model("wingtip")
    >>> m.wing.semi_span, [inst.y for inst in m.propellers], m.propellers[0].mount
    (5.7, [5.7], 'flexible')
    >>> case_model("wingtip", mount="rigid").propellers[0].mount
    'rigid'
    """
    return get(name).model(**options)
