"""The thesis's models as a case library: named, documented functions returning models.

One module per chapter (``ch04_propeller_aero``, ``ch06_isolated``, ``ch07_patil``,
``ch09_baseline``, ``ch10_other_wings``, ``ch11_parametric``, ``appE_constant_speed``); the
short names of the command line (``wingtip``, ``patil``, ...) are in :mod:`propwhirl.cases.registry`.
The cases only build models: the functions recomputing the thesis's numbers from them are in
:mod:`propwhirl.reproduce`, the parametric studies in :mod:`propwhirl.studies`.  Nothing here
imports those packages (tests/cases/test_layering.py).
"""
from propwhirl.cases.registry import CASES, NamedCase, case_model

__all__ = ["CASES", "NamedCase", "case_model"]
