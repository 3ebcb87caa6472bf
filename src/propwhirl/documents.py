"""The documentation installed with propwhirl: the pages of the repository's ``docs/`` folder.

``pyproject.toml`` installs ``docs/*.md`` as package data, in the folder ``docs`` of the
installed package (``site-packages/propwhirl/docs/validation.md``, ...).  Run from a source
checkout (an editable install, or ``src`` on the path) the pages are those of ``docs/`` itself.
``propwhirl docs NAME`` prints a page and names its path; output that refers the reader to a
page names it with :func:`cite`, so the reference holds wherever propwhirl is installed.  This
module uses nothing of propwhirl but :mod:`propwhirl.validate`.
"""
from __future__ import annotations

from pathlib import Path

from propwhirl import validate as v

#: The installed folder (a wheel) and the source checkout's folder (src/propwhirl/ → docs/)
_INSTALLED = Path(__file__).resolve().parent / "docs"
_CHECKOUT = Path(__file__).resolve().parents[2] / "docs"


def folder() -> Path:
    """The folder holding the pages (installed, else the source checkout's ``docs/``)."""
    for candidate in (_INSTALLED, _CHECKOUT):
        if (candidate / "validation.md").is_file():
            return candidate
    raise v.InputError(f"the documentation is not installed (no {_INSTALLED}): reinstall "
                       "propwhirl from its wheel or source distribution")


def names() -> tuple[str, ...]:
    """The page names (file names without ``.md``), sorted."""
    return tuple(sorted(p.stem for p in folder().glob("*.md")))


def path(name: str) -> Path:
    """The file of page `name` (``"validation"`` or ``"validation.md"``).

    Examples
    --------
    >>> path("validation").name
    'validation.md'
    """
    stem = name[:-3] if name.endswith(".md") else name
    known = names()
    if stem not in known:
        raise v.InputError(f"document {name!r} is invalid: must be one of {', '.join(known)}")
    return folder() / f"{stem}.md"


def text(name: str) -> str:
    """The Markdown text of page `name`."""
    return path(name).read_text(encoding="utf-8")


def cite(name: str, section: str = "") -> str:
    """How output refers to a page: the command that prints it and where it is installed.

    Examples
    --------
    >>> cite("validation", "chapter 10").startswith("`propwhirl docs validation`, chapter 10 (")
    True
    """
    where = f", {section}" if section else ""
    return f"`propwhirl docs {name}`{where} ({path(name)})"
