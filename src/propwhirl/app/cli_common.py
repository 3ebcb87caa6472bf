"""What the command-line modules share: one-line output of user strings, reading a model file,
the --speeds grid, and the check that every output file can be written before a long run.
Used by :mod:`propwhirl.app.cli` and the study commands (:mod:`.cli_studies`, :mod:`.cli_design`)."""
from __future__ import annotations

import sys
from pathlib import Path

from propwhirl import fileio
from propwhirl import limits
from propwhirl.validate import InputError


def echo(text: str) -> None:
    """Print text that carries user strings (model names): control characters escaped
    (:func:`propwhirl.limits.printable`), line by line."""
    print("\n".join(limits.printable(line) for line in str(text).split("\n")))


def load_model(path: str):
    """The model of a TOML model file (:func:`propwhirl.io.load_model`), refused with one line
    when the file holds something that is not a model to analyse."""
    from propwhirl import io
    from propwhirl.model.protocol import Model

    notes: list[str] = []  # the values assumed for a file of an older format version
    model = io.load_model(path, notes=notes)
    if not isinstance(model, Model):
        raise InputError(f"{path} holds a {type(model).__name__}, not a model to analyse: "
                         "type must be \"propeller-wing\" or \"isolated-propeller\"")
    print_notes(notes)
    return model


def print_notes(notes: list[str]) -> None:
    """Each note on stderr as one line ``propwhirl: note: ...``."""
    for note in notes:
        print(f"propwhirl: note: {limits.printable(note)}", file=sys.stderr)


def speed_grid(start: float, stop: float, step: float):
    """Airspeeds START, START+STEP, ... and STOP [m/s] (STOP always included)."""
    import numpy as np

    from propwhirl import validate as v

    v.positive("--speeds START", start, "m/s")
    v.positive("--speeds STOP", stop, "m/s")
    v.positive("--speeds STEP", step, "m/s")
    if not stop > start:
        raise InputError(f"--speeds STOP = {stop!r} m/s is invalid: must be > START = {start!r} m/s")
    limits.check_speed_count(f"--speeds {start:g} {stop:g} {step:g}",
                             limits.grid_count(start, stop, step), "a larger STEP")
    n = (stop - start) / step
    grid = start + step * np.arange(int(np.floor(n + 1e-9)) + 1)
    return grid if grid[-1] >= stop - 1e-9 * step else np.append(grid, stop)


def check_outputs(**paths: str | None) -> None:
    """Fail before a long computation if an output file cannot be written: its folder does
    not exist or is not writable, the path is a folder, a plot's suffix is not a format."""
    for option, path in paths.items():
        if path is None:
            continue
        fileio.check_writable(path, what=f"--{option}")
        if option == "plot":
            _check_plot_format(path)


def _check_plot_format(path: str) -> None:
    """A plot's suffix names a format matplotlib writes (checked before computing)."""
    try:
        from matplotlib.backend_bases import FigureCanvasBase
    except ImportError:
        raise InputError("--plot needs matplotlib, which is not installed: "
                         "pip install propwhirl[plots]") from None
    fmt = Path(path).suffix[1:].lower() or "png"
    supported = FigureCanvasBase.get_supported_filetypes()
    if fmt not in supported:
        raise InputError(f"--plot {path}: format {fmt!r} is not supported "
                         f"(suffixes: {', '.join(sorted(supported))})")
