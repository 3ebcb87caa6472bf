"""Running a parametric study: the study models, one row per analysis (run by
:func:`propwhirl.studies.sweeps.run_points`: serial, local processes or Dask; failing points
recorded)."""
from __future__ import annotations

from typing import Any, Callable, Mapping, Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.cases.ch09_baseline import baseline_flight
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.systems import IsolatedPropeller
from propwhirl.progress import ProgressCallback
from propwhirl.studies import execution
from propwhirl.studies.execution import TaskError  # noqa: F401 (re-exported)
from propwhirl.studies.critical import convention
from propwhirl.studies.partial import check_checkpoint
from propwhirl.studies.sweeps import run_points
from propwhirl.studies.table import RESULT_UNITS, StudyTable

#: Model names a study can analyse (see :mod:`propwhirl.studies.parametric`).
MODELS: tuple[str, ...] = ("wingtip", "isolated", "rigid")

#: Initial speed grid of the isolated propeller [m/s] (its critical speeds exceed 350 m/s).
ISOLATED_SPEEDS = np.arange(1.0, 1001.0, 10.0)


# ----------------------------------------------------------------------------- models
def build_model(name: str, propeller: Propeller):
    """The study model `name` ("wingtip", "isolated" or "rigid") with `propeller`."""
    if name == "wingtip":
        return wingtip_propeller_wing("flexible", propeller=propeller)
    if name == "isolated":
        return IsolatedPropeller(propeller, baseline_flight())
    if name == "rigid":
        return wingtip_propeller_wing("rigid", propeller=propeller, rotating=False, propeller_aero=False)
    raise v.InputError(f"model = {name!r} is invalid: must be one of {MODELS}")


def check_models(models: Sequence[str]) -> tuple[str, ...]:
    """`models` (one name or several) as a tuple of distinct names of :data:`MODELS`."""
    if isinstance(models, str):
        models = (models,)
    models = tuple(models)
    if not models:
        raise v.InputError(f"models = () is invalid: give at least one of {MODELS}")
    for m in models:
        if m not in MODELS:
            raise v.InputError(f"model = {m!r} is invalid: must be one of {MODELS}")
    if len(set(models)) != len(models):
        raise v.InputError(f"models = {models!r} is invalid: a model appears twice")
    return models


def speeds_for(model: str, speeds) -> np.ndarray | None:
    """The initial speed grid [m/s] of study model `model`: `speeds` (one grid, or one per
    model name), else the isolated propeller's :data:`ISOLATED_SPEEDS`, else None (the
    model's own range)."""
    if isinstance(speeds, Mapping):
        s = speeds.get(model)
    else:
        s = speeds
    if s is None:
        return ISOLATED_SPEEDS if model == "isolated" else None
    return v.increasing(f"speeds ({model})", s, "m/s")


def parameter_grid(name: str, values, unit: str = "",
                   check: Callable[..., np.ndarray] = v.finite) -> np.ndarray:
    """A non-empty 1-D grid of parameter values, each checked with `check`."""
    arr = np.atleast_1d(np.asarray(v.finite(name, values, unit), dtype=float))
    if arr.ndim != 1 or arr.size == 0:
        raise v.InputError(f"{name} is invalid: must be a non-empty 1-D sequence of values, got shape {arr.shape}")
    check(name, arr, unit)
    return arr


# ----------------------------------------------------------------------------- runner
def map_analyses(func: Callable[[Any], Any], tasks: Sequence[Any], processes: int = 1,
                 **options: Any) -> list[Any]:
    """``[func(t) for t in tasks]``, in a process pool of `processes` single-BLAS-thread workers
    (at most one per CPU) when ``processes > 1``; order preserved; `func` and the tasks must be
    picklable.  `options` (client, progress, errors, checkpoint, keys, desc): see
    :func:`propwhirl.studies.execution.map_analyses`, which runs it (Dask, progress,
    partial results, failing points)."""
    return execution.map_analyses(func, tasks, processes, **options)


def study_points(name: str, parameter: str, parameters: Mapping[str, np.ndarray], n: int,
                 models: Sequence[str], xtol: float, static_divergence: bool, low_speed: bool,
                 checkpoint: execution.Checkpoint | None):
    """The checks of a study's columns, one key per (model, point) for the partial-results
    file, and the checkpoint with the study's fingerprint entries (its name, parameter,
    models and parameter columns; :func:`row_checkpoint` adds the content of every model
    analysed, the speeds, xtol, method and convention): the one rule of both study forms."""
    if n == 0:
        raise v.InputError(f"{parameter}: the parameter grid is empty (give at least one value)")
    for k, col in parameters.items():
        if len(col) != n:
            raise v.InputError(f"parameter column {k!r} has {len(col)} values, expected {n}")
    if parameter not in parameters:
        raise v.InputError(f"parameter {parameter!r} is not among the columns {list(parameters)}")
    v.positive("xtol", xtol, "m/s")
    keys = [f"{m} " + " ".join(f"{k}={float(np.asarray(col)[j])!r}" for k, col in parameters.items())
            + f" #{j}" for m in models for j in range(n)]
    if checkpoint is not None:
        check_checkpoint(checkpoint)
        checkpoint = checkpoint.with_entries(
            study=name, parameter=parameter, models=list(models),
            parameters={k: [float(x) for x in np.asarray(col, dtype=float)]
                        for k, col in parameters.items()},
            convention=convention(static_divergence, low_speed))
    return keys, checkpoint


def study_table(name: str, parameter: str, unit: str, parameters: Mapping[str, np.ndarray],
                models: Sequence[str], rows: Sequence[Mapping[str, Any]],
                parameter_units: Mapping[str, str] | None, static_divergence: bool,
                low_speed: bool) -> StudyTable:
    """The :class:`StudyTable` of a study's rows (one per (model, point), model-major): the
    model column, the parameter columns, the results and the ``error`` column."""
    n = len(rows) // max(len(models), 1)
    columns: dict[str, np.ndarray] = {"model": np.array([m for m in models for _ in range(n)], dtype=object)}
    for k, col in parameters.items():
        columns[k] = np.tile(np.asarray(col, dtype=float), len(models))
    for k in RESULT_UNITS:
        vals = [r[k] for r in rows]
        columns[k] = np.array(vals, dtype=float if isinstance(vals[0], float) else object)
    columns["error"] = np.array([r["error"] for r in rows], dtype=object)
    units = {"model": "", **{k: (parameter_units or {}).get(k, unit if k == parameter else "")
                             for k in parameters}, **RESULT_UNITS, "error": ""}
    return StudyTable(name, parameter, columns, units, convention(static_divergence, low_speed))


def propeller_study(name: str, parameter: str, unit: str, parameters: Mapping[str, np.ndarray],
                    propellers: Sequence[Propeller], *, models: Sequence[str] = ("wingtip", "isolated"),
                    parameter_units: Mapping[str, str] | None = None,
                    static_divergence: bool = True, low_speed: bool = True,
                    speeds=None, xtol: float = 0.01, processes: int = 1, client=None,
                    progress: bool | ProgressCallback | None = None,
                    checkpoint: execution.Checkpoint | None = None) -> StudyTable:
    """A study over given propellers: each model of `models` with each propeller; one row per
    (model, propeller).  (The chapter-11 studies set parameter paths instead:
    :func:`propwhirl.studies.parametric.propeller_study`.)

    parameters: columns describing each propeller (equal length to `propellers`), the x-axis
        column `parameter` [unit] among them; speeds, xtol, processes, client, progress,
        checkpoint: as :func:`propwhirl.studies.parametric.propeller_study`.

    A point whose model is invalid or whose analysis fails is recorded, the others go on: its
    row has kind "error", NaN speeds and the message in the column ``error`` ("" elsewhere).
    """
    models = check_models(models)
    keys, checkpoint = study_points(name, parameter, parameters, len(propellers), models, xtol,
                                    static_divergence, low_speed, checkpoint)
    variants, grids = [], []
    for m in models:
        for p in propellers:
            try:
                variants.append(build_model(m, p))
            except v.InputError as exc:              # recorded in its row, the others go on
                variants.append(exc)
            grids.append(speeds_for(m, speeds))
    rows = run_points(variants, speeds_each=grids, xtol=xtol, static_divergence=static_divergence,
                      low_speed=low_speed, processes=processes, client=client, progress=progress,
                      checkpoint=checkpoint, keys=keys, desc=name)
    return study_table(name, parameter, unit, parameters, models, rows, parameter_units,
                       static_divergence, low_speed)
