"""Griffe extension of the documentation site: the docstrings' Sphinx markup as Markdown.

The docstrings are numpydoc (numpy style, parsed by griffe), written with Sphinx cross-reference
roles (``:func:`analyse```, ``:class:`~propwhirl.engine.Sweep```) and literal-block markers
(``text::``).  mkdocstrings renders docstrings as Markdown, where both would print verbatim: this
extension turns a role into a code span of its target and ``text::`` into ``text:`` before
rendering; an attribute documented by ``#:`` comments above it gets them as its docstring.  It
changes only what the site shows, never the source.
"""
from __future__ import annotations

import re
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:func|class|mod|data|attr|meth|obj|exc|const):`~?([^`]+)`")
_LITERAL_MARKER = re.compile(r"(?<=\S)::$", re.MULTILINE)
_BARE_MARKER = re.compile(r"^[ \t]*::[ \t]*$", re.MULTILINE)


def to_markdown(text: str) -> str:
    """Sphinx roles as code spans, ``text::`` as ``text:``, a lone ``::`` line removed."""
    text = _ROLE.sub(lambda m: f"`{m.group(1)}`", text)
    text = _BARE_MARKER.sub("", text)
    return _LITERAL_MARKER.sub(":", text)


class RstRoles(griffe.Extension):
    """Docstrings as Markdown (:func:`to_markdown`); ``#:`` comments as attribute docstrings."""

    def on_instance(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = to_markdown(obj.docstring.value)

    def on_attribute_instance(self, *, attr: griffe.Attribute, **kwargs: Any) -> None:
        """An attribute documented by ``#:`` comment lines just above it (the Sphinx
        convention of the source) gets them as its docstring."""
        if attr.docstring is not None or attr.lineno is None or attr.filepath is None:
            return
        if attr.filepath not in attr.lines_collection:
            return
        lines = attr.lines_collection[attr.filepath]
        comment: list[str] = []
        i = attr.lineno - 2
        while i >= 0 and lines[i].lstrip().startswith("#:"):
            comment.insert(0, lines[i].lstrip()[2:].strip())
            i -= 1
        if comment:
            attr.docstring = griffe.Docstring(to_markdown(" ".join(comment)), parent=attr)
