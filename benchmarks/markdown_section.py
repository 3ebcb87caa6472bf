"""The one way the benchmarks write their tables into docs/performance.md: the text between a
begin and an end marker is replaced, or the section (title and markers) appended when absent."""
from __future__ import annotations

from pathlib import Path


def replace_section(path: Path, body: str, begin: str, end: str, title: str | None = None) -> None:
    """Put ``body`` between the markers ``begin`` and ``end`` of ``path`` (created if missing);
    without the markers, append them with ``body`` (after ``title`` when given)."""
    text = path.read_text() if path.exists() else ""
    block = f"{begin}\n{body}\n{end}"
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        _, tail = rest.split(end, 1)
        text = head + block + tail
    elif title is not None:
        text = text.rstrip("\n") + f"\n\n{title}\n\n{block}\n"
    else:
        text = text + ("\n" if text and not text.endswith("\n") else "") + block + "\n"
    path.write_text(text)
