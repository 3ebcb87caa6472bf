"""Analyses of a model: stability (labelled instabilities, the critical one), names of modes,
free vibration, time response, sensitivities of a critical point."""
from propwhirl.analysis.stability import (DEFAULT_SPEEDS, Instability, ModelAnalysis, analyse,
                                          critical, first_of_kind, load, speed_and_frequency)
from propwhirl.analysis.sensitivity import CriticalSensitivities, critical_sensitivities

__all__ = ["DEFAULT_SPEEDS", "Instability", "ModelAnalysis", "analyse", "critical",
           "first_of_kind", "load", "speed_and_frequency", "critical_sensitivities",
           "CriticalSensitivities"]
