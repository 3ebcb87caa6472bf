"""Design studies: sweeps and maps of the critical speed, the chapter-11 studies.

:mod:`.paths` — parameter paths: any numeric field of any model by a string (``wing.GJ``,
``propellers[1].propeller.f_theta``, the scale form ``wing.EI*``); :mod:`.sweeps` — the
critical speed of any model over one parameter (:func:`~.sweeps.sweep`) or two
(:func:`~.sweeps.map2d`), results saved as JSON/CSV; :mod:`.parametric` — the chapter-11
studies (critical speed against one propeller parameter), built on both; :mod:`.runner` — the
study models and the process pool; :mod:`.critical` — which instability of an analysis a study
calls critical; :mod:`.table` — the chapter-11 result table.

The names the documentation shows users are importable from here: the studies over parameter
paths (:func:`sweep`, :func:`map2d`, :func:`critical_map`, their :class:`CriticalMap`;
:func:`path_variant`, docs/studies.md), the chapter-11 studies (:func:`nacelle_stiffness`,
:func:`blade_angle_mode_switch`), clearance campaigns (:class:`Case`, :func:`envelope`,
:class:`Campaign`, :func:`from_spec`, :func:`run_campaign`, :class:`CampaignResult`,
docs/campaign.md), sensitivities and optimisation (:func:`verify_sensitivities`,
:func:`minimum_mount_stiffness`, :func:`openmdao_component`, docs/gradients.md) and the
parallel runner they share (:func:`map_analyses`).  They are imported on first use (PEP 562),
as the top-level package's: importing one study module loads no other (the reproduction's
harness, the layering of tests/test_layering.py).
"""
from importlib import import_module
from typing import Any

#: name -> the module defining it; the same imports, for static tools (the API page, type
#: checkers), are in __init__.pyi
_EXPORTS = {
    "sweep": "propwhirl.studies.sweeps", "map2d": "propwhirl.studies.sweeps",
    "critical_map": "propwhirl.studies.sweeps", "CriticalMap": "propwhirl.studies.sweeps",
    "path_variant": "propwhirl.studies.boundary",
    "nacelle_stiffness": "propwhirl.studies.parametric",
    "blade_angle_mode_switch": "propwhirl.studies.parametric",
    "Case": "propwhirl.studies.campaign_cases", "envelope": "propwhirl.studies.flight_envelope",
    "Campaign": "propwhirl.studies.campaign", "from_spec": "propwhirl.studies.campaign",
    "run_campaign": "propwhirl.studies.campaign",
    "CampaignResult": "propwhirl.studies.campaign_result",
    "verify_sensitivities": "propwhirl.studies.sensitivity_check",
    "minimum_mount_stiffness": "propwhirl.studies.gradients",
    "openmdao_component": "propwhirl.studies.gradients",
    "map_analyses": "propwhirl.studies.execution",
}

__all__ = list(_EXPORTS)


def __getattr__(name: str) -> Any:
    """Import the public names on first use (PEP 562)."""
    if name in _EXPORTS:
        value = getattr(import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'propwhirl.studies' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
