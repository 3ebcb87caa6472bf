"""Design studies: sweeps and maps of the critical speed, the chapter-11 studies.

:mod:`.paths` — parameter paths: any numeric field of any model by a string (``wing.GJ``,
``propellers[1].propeller.f_theta``, the scale form ``wing.EI*``); :mod:`.sweeps` — the
critical speed of any model over one parameter (:func:`~.sweeps.sweep`) or two
(:func:`~.sweeps.map2d`), results saved as JSON/CSV; :mod:`.parametric` — the chapter-11
studies (critical speed against one propeller parameter), built on both; :mod:`.runner` — the
study models and the process pool; :mod:`.critical` — which instability of an analysis a study
calls critical; :mod:`.table` — the chapter-11 result table.
"""
