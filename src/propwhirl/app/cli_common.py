"""What the command-line modules share: one-line output of user strings, reading a model file
(or a case of the library by name), the --speeds grid, and the check that every output file can
be written before a long run.
Used by :mod:`propwhirl.app.cli` and the study commands (:mod:`.cli_studies`, :mod:`.cli_design`)."""
from __future__ import annotations

import argparse
import importlib
import re
import sys
from pathlib import Path

from propwhirl import fileio
from propwhirl import limits
from propwhirl import validate as v
from propwhirl.app.execution_options import partial_path
from propwhirl.cases import registry
from propwhirl.studies.partial import Checkpoint
from propwhirl.studies.warmstart import pass_checkpoints
from propwhirl.validate import InputError


#: a value named in a help text, read when the help is printed: ``«module:name»`` or
#: ``«module:name:format»`` (a callable is called)
_LAZY = re.compile(r"«([\w.]+):(\w+)(?::([^»]*))?»")


def lazy(module: str, name: str, spec: str = "") -> str:
    """A placeholder for ``module.name`` (formatted with ``spec``) in a help text, replaced
    by :class:`LazyHelpFormatter` when the help is printed: building the parser imports
    nothing for it (``propwhirl --help`` does not import the model package for a default
    named in one command's help)."""
    return f"«{module}:{name}{':' + spec if spec else ''}»"


def _expand(match: re.Match) -> str:
    value = getattr(importlib.import_module(match.group(1)), match.group(2))
    return format(value() if callable(value) else value, match.group(3) or "")


class LazyHelpFormatter(argparse.HelpFormatter):
    """argparse's formatter, with the :func:`lazy` placeholders of a help text replaced by
    their values (imported then)."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = super()._get_help_string(action)
        return _LAZY.sub(_expand, text) if text and "«" in text else text


def plain(text: str) -> str:
    """A docstring's text for ``--help``: its reST markup dropped (``:func:`x``` and
    ```x``` as x; a ``~`` before a dotted name keeps its last part)."""
    text = re.sub(r":[a-z]+:`~?([^`]+)`", lambda m: m.group(1), text)
    return text.replace("``", "")


def echo(text: str) -> None:
    """Print text that carries user strings (model names): control characters escaped
    (:func:`propwhirl.limits.printable`), line by line."""
    print("\n".join(limits.printable(line) for line in str(text).split("\n")))


def load_model(path: str, command: str = "analyse"):
    """The model of a TOML model file — a beam model's (:func:`propwhirl.io.load_model`) or a
    modal model's (:func:`propwhirl.io.load_modal_model`) —, refused with one line when the
    file holds something that is not a model to analyse, or a model that cannot run
    `command` (:func:`check_runs`: the model says why)."""
    from propwhirl import io  # lazy: model files
    from propwhirl.io.modal_files import is_modal_file  # lazy: model files
    from propwhirl.model.protocol import Model  # lazy: models

    if is_modal_file(path):
        model = io.load_modal_model(path)
    else:
        notes: list[str] = []  # the values assumed for a file of an older format version
        model = io.load_model(path, notes=notes)
        if not isinstance(model, Model):
            raise InputError(f"{path} holds a {type(model).__name__}, not a model to analyse: "
                             "type must be \"propeller-wing\" or \"isolated-propeller\"")
        print_notes(notes)
    check_runs(model, command, path)
    return model


def model_or_case(text: str, command: str = "analyse"):
    """MODEL of `command` (`sweep`, `map`, `boundary`, `clearance`, `sensitivity`, `export`): a
    TOML model file (a beam or a modal model's, :func:`load_model`), or the name of a case of
    the library."""
    if text in registry.CASES and not fileio.exists(text, "model file"):
        model = registry.case_model(text)
        check_runs(model, command, text)
        return model
    if Path(text).suffix.lower() == ".toml" or fileio.exists(text, "model file"):
        return load_model(text, command)
    raise InputError(f"MODEL = {text!r} is invalid: neither a model file (.toml) nor a case "
                     f"name (one of {', '.join(registry.CASES)})")


def check_runs(model, feature: str, source: str) -> None:
    """One line when `model` (read from `source`, a file or a case name) cannot run `feature`
    (a command or method, :data:`propwhirl.model.protocol.FEATURES`), giving the reason the
    model itself gives (:func:`propwhirl.model.protocol.refusal`)."""
    from propwhirl.model.protocol import refusal  # lazy: models

    why = refusal(model, feature)
    if why is not None:
        raise InputError(f"{source}: propwhirl {feature} cannot run this model: {why}")


def print_notes(notes: list[str]) -> None:
    """Each note on stderr as one line ``propwhirl: note: ...``."""
    for note in notes:
        print(f"propwhirl: note: {limits.printable(note)}", file=sys.stderr)


def speed_grid(start: float, stop: float, step: float):
    """Airspeeds START, START+STEP, ... and STOP [m/s] (STOP always included)."""
    import numpy as np

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


def check_outputs(*, model: str | None = None, partial_of: str | None = None,
                  warm_start: bool = False, **paths: str | None) -> None:
    """Fail before any computation if the outputs cannot all be written, with one line naming
    the option (``summary_csv`` is ``--summary-csv``) and the path.

    Each output's folder must exist and be writable and the path must be a regular file or a
    new one — not a folder, a device, a FIFO or a socket
    (:func:`propwhirl.fileio.check_writable`); ``plot``: the suffix names a format matplotlib
    writes, ``animate``: a ``.gif``, and matplotlib must be installed for either.  No two
    outputs may be one file, nor an output one of the inputs — the model file `model` (the
    MODEL argument, when it is a file) and, for a modal model, the modes file it names —, nor
    the partial-results file kept beside the output of option `partial_of` while a study
    runs (``X.partial``; with `warm_start` also those of its passes, ``X.partial.coarse``
    ...): :func:`propwhirl.fileio.check_apart` (paths compared resolved: ``./X`` is ``X``, a
    symbolic link is its target, a hard link its file).
    """
    given = {_option(o): str(p) for o, p in paths.items() if p is not None}
    for label, path in given.items():
        fileio.check_writable(path, what=label)
        if label in ("--plot", "--plot-shape"):
            _check_plot_format(path, label)
        elif label == "--animate":
            _check_animation(path)
    others = model_inputs(model) if model is not None else []    # (what it is, path)
    owner = given.get(_option(partial_of)) if partial_of is not None else None
    if owner is not None:
        for partial in _partial_files(owner, warm_start):
            others.append((f"the partial-results file of {_option(partial_of)} {owner} "
                           "(kept there while the study runs)", partial))
    fileio.check_apart(given.items(), others)


def model_inputs(model: str, label: str = "MODEL") -> list[tuple[str, str | Path]]:
    """The files a model argument reads, each with what it is, for
    :func:`propwhirl.fileio.check_apart`: the model file (when `model` is a file, not a case
    name) and, when it is a modal model file, the modes file its ``[modes] file`` names."""
    from propwhirl.io.modal_files import modes_path  # lazy: model files

    if not fileio.exists(model, "model file") or not Path(model).is_file():
        return []
    out: list[tuple[str, str | Path]] = [(f"the model file {label} {model}", model)]
    modes = modes_path(model)
    if modes is not None:
        out.append((f"the modes file of {label} {model} ([modes] file)", modes))
    return out


def _option(name: str) -> str:
    """The command-line option of a keyword: ``summary_csv`` -> ``--summary-csv``."""
    return "--" + name.replace("_", "-")


def _partial_files(output: str, warm_start: bool) -> list[Path]:
    """The partial-results files a study keeps beside `output` while it runs: ``OUT.partial``
    (:func:`propwhirl.app.execution_options.partial_path`) and, warm-started, one per pass
    (:func:`propwhirl.studies.warmstart.pass_checkpoints`: the one place that names them)."""
    partial = partial_path(output)
    passes = [Path(c.path) for c in pass_checkpoints(Checkpoint(partial))] if warm_start else []
    return [partial, *passes]


def _check_plot_format(path: str, option: str = "--plot") -> None:
    """A plot's suffix names a format matplotlib writes (checked before computing)."""
    _need_matplotlib(option)
    from matplotlib.backend_bases import FigureCanvasBase

    fmt = Path(path).suffix[1:].lower() or "png"
    supported = FigureCanvasBase.get_supported_filetypes()
    if fmt not in supported:
        raise InputError(f"{option} {path}: format {fmt!r} is not supported "
                         f"(suffixes: {', '.join(sorted(supported))})")


def _check_animation(path: str) -> None:
    """An animation is a GIF (:func:`propwhirl.app.plots.animate_mode`), drawn by matplotlib
    and written by Pillow (a dependency of matplotlib)."""
    if Path(path).suffix.lower() != ".gif":
        raise InputError(f"--animate {path}: must end in .gif (the animation is a GIF)")
    _need_matplotlib("--animate")
    try:
        import PIL  # noqa: F401
    except ImportError:
        raise InputError("--animate needs Pillow, which is not installed: "
                         "pip install propwhirl[plots]") from None


def _need_matplotlib(option: str) -> None:
    try:
        import matplotlib.backend_bases  # noqa: F401
    except ImportError:
        raise InputError(f"{option} needs matplotlib, which is not installed: "
                         "pip install propwhirl[plots]") from None
