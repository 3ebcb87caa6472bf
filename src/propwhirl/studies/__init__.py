"""Design studies: parametric sweeps of the critical speed.

:mod:`.parametric` — the chapter-11 studies (critical speed against one propeller parameter);
:mod:`.runner` — the study models and the process pool; :mod:`.critical` — which instability of
an analysis a study calls critical; :mod:`.table` — the result table.
"""
