"""Warm-started maps: the speed range of each point clipped to what its neighbours found.

A map of the critical speed over a fine grid of two parameters spends most of its analyses
above the speeds that matter: every point is tracked over the model's whole speed range,
although its critical speed lies close to its neighbours'.  :func:`warm_started_rows` analyses
the points of a map in two passes (three when a point needs it):

1. **Coarse pass**: every ``stride``-th point along each axis (and the last), over the whole
   speed range — an ordinary analysis.
2. **Fine pass**: every other point over its speed grid *clipped* at V_top = ``margin``
   (default 1.05) × the largest critical speed and wing static-divergence speed of the coarse
   points at the corners of its cell (the grid's speeds below V_top, then V_top).  The
   margin trades the speeds analysed against the points analysed twice: on the wingtip
   model's (f_θ, f_ψ) map a clipped range that still holds the forward-whirl flutter at
   159 m/s above the divergence at 143 m/s (margin 1.15) costs 1.5× one that stops at 150 m/s.
3. **Check**: a fine point is accepted when it found its critical instability *and* — on a
   model with wing DOFs — the wing's static divergence below V_top.  Both are then the lowest
   events of their kind over the whole range (the events below V_top do not depend on the
   range's top), so the row is the one a full-range analysis gives, to the crossing
   accuracy ``xtol``.  Any other fine point (nothing found below V_top, an error) is
   analysed again over the whole range.  A fine point is not clipped (analysed once, over the
   whole range) when a corner of its cell failed, has no critical instability, or — on a
   wing — has no wing divergence in the range: it would most likely not find one below its
   top either, and be analysed twice.

Nothing is estimated: a point's result always comes from its own analysis, and a neighbour
only decides where that analysis may stop.  The passes are fixed by the grid alone, so the
result does not depend on the back end (serial, local processes, Dask) or on the order in
which the points finish.  With the thesis's ``low_speed=False`` convention a low-speed
instability counts only if it does not recover, which a clipped range cannot tell: such studies
are not warm-started.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from propwhirl import validate as v

#: default: every STRIDE-th point of each axis is in the coarse pass
STRIDE = 5
#: default: the fine points' speed range ends MARGIN × their coarse corners' highest speed
MARGIN = 1.05

Runner = Callable[..., list[dict[str, Any]]]


def coarse_indices(n: int, stride: int) -> np.ndarray:
    """The coarse points of an axis of ``n`` values: 0, stride, 2 stride, …, and n − 1."""
    return np.union1d(np.arange(0, n, stride), [n - 1])


def _corners(idx: tuple[int, ...], coarse: Sequence[np.ndarray]) -> list[tuple[int, ...]]:
    """The coarse points at the corners of the cell holding ``idx`` (one or two per axis)."""
    per_axis = []
    for i, c in zip(idx, coarse):
        k = int(np.searchsorted(c, i))
        per_axis.append([int(c[k])] if c[k] == i else [int(c[k - 1]), int(c[k])])
    return [tuple(x) for x in np.array(np.meshgrid(*per_axis, indexing="ij")).reshape(
        len(idx), -1).T]


def clipped_grid(grid: np.ndarray, top: float) -> np.ndarray | None:
    """``grid`` [m/s] cut at ``top`` (the speeds below it, then top); None when top is not
    inside the grid's range (the whole grid is then used)."""
    if not (grid[0] < top < grid[-1]):
        return None
    g = grid[grid < top]
    return np.append(g, top) if g.size >= 1 else None


def _highest(row: dict[str, Any], has_wing: bool) -> float:
    """The highest speed a corner's row says matters: its critical speed and the wing's static
    divergence speed.  NaN — the fine point is not clipped — when the corner has no critical
    instability or failed, or (on a wing) has no divergence in the range: the fine point would
    then most likely find none below its top either and be analysed twice."""
    if row.get("error") or row.get("kind") in ("none", "error"):
        return math.nan
    sdiv = float(row["static_divergence_speed"])
    if has_wing and not math.isfinite(sdiv):
        return math.nan
    return float(np.nanmax([row["critical_speed"], sdiv]))


def _accepted(row: dict[str, Any], has_wing: bool) -> bool:
    """A fine point's clipped analysis is its final result (module docstring, step 3)."""
    if row.get("error") or row.get("kind") in ("none", "error"):
        return False
    return (not has_wing) or math.isfinite(row["static_divergence_speed"])


#: the passes, each with its own partial-results file (module docstring)
PASSES = ("coarse", "fine", "full-range")


def _pass_checkpoint(checkpoint, name: str):
    """The partial-results file of one pass: beside the study's, suffixed with the pass."""
    if checkpoint is None:
        return None
    path = Path(checkpoint.path)
    return replace(checkpoint, path=path.with_name(f"{path.name}.{name}")).with_entries(
        **{"pass": name})


def pass_checkpoints(checkpoint) -> list:
    """The partial-results files of the passes of a warm-started study whose own file is
    ``checkpoint`` (to remove them with it once the result is written)."""
    return [] if checkpoint is None else [_pass_checkpoint(checkpoint, n) for n in PASSES]


def warm_started_rows(variants: Sequence[Any], keys: Sequence[str], shape: tuple[int, ...],
                      grids: Sequence[np.ndarray | None], run: Runner, *,
                      stride: int = STRIDE, margin: float = MARGIN, checkpoint=None,
                      stats: dict[str, int] | None = None) -> list[dict[str, Any]]:
    """The result rows of the map's points (row-major over ``shape``), warm-started.

    variants: the model of each point (or the exception that stopped its building); keys: the
    points' names; grids: each point's full initial speed grid [m/s] (its model's own range
    when the study gives none); run(models, speeds_each=…, keys=…, desc=…, checkpoint=…): the
    study's :func:`propwhirl.studies.sweeps.run_points` with its options bound.  ``stats``
    (a dict) receives the number of analyses of each pass.  Module docstring: the passes.
    """
    v.integer_at_least("stride", stride, 2)
    v.in_range("margin", margin, 1.0, 10.0, low_open=True)
    n = len(variants)
    coarse = [coarse_indices(m, stride) for m in shape]
    flat = np.arange(n).reshape(shape)
    is_coarse = np.zeros(shape, dtype=bool)
    is_coarse[np.ix_(*coarse)] = True
    first = [int(i) for i in flat[is_coarse]]
    rows: list[dict[str, Any] | None] = [None] * n

    def go(points: list[int], speeds: list[np.ndarray | None], name: str):
        if not points:
            return
        got = run([variants[i] for i in points], speeds_each=speeds,
                  keys=[keys[i] for i in points], desc=f"points ({name} pass)",
                  checkpoint=_pass_checkpoint(checkpoint, name))
        for i, r in zip(points, got):
            rows[i] = r

    go(first, [grids[i] for i in first], PASSES[0])
    fine, fine_grids, tops = [], [], {}
    wing = {i: not isinstance(variants[i], Exception) and variants[i].dof_map().has_wing
            for i in range(n)}
    for i in (int(j) for j in flat[~is_coarse]):
        idx = np.unravel_index(i, shape)
        corner = [_highest(rows[int(flat[c])], wing[i]) for c in _corners(idx, coarse)]
        full = grids[i]
        clip = None
        if full is not None and corner and all(math.isfinite(x) for x in corner):
            clip = clipped_grid(full, margin * max(corner))
        fine.append(i)
        fine_grids.append(full if clip is None else clip)
        if clip is not None:
            tops[i] = float(clip[-1])
    go(fine, fine_grids, PASSES[1])
    # a point not clipped was analysed over its whole range already
    again = [i for i in fine if i in tops and not _accepted(rows[i], wing[i])]
    go(again, [grids[i] for i in again], PASSES[2])
    if stats is not None:
        stats.update(coarse=len(first), fine=len(fine), clipped=len(tops), again=len(again))
    return rows  # every point filled by one of the passes


__all__ = ["warm_started_rows", "clipped_grid", "coarse_indices", "pass_checkpoints", "PASSES",
           "STRIDE", "MARGIN"]
