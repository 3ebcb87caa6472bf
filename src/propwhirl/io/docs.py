"""The documentation generated from the files' declarations: ``docs/model-file.md`` whole
(:func:`propwhirl.io.schema.markdown`), the key tables of ``docs/campaign.md``
(:func:`propwhirl.io.campaign_files.docs_parts`) and of ``docs/modal-structures.md``
(:func:`propwhirl.io.modal_files.docs_parts`), each between ``<!-- generated: NAME -->`` and
``<!-- end generated -->`` (:func:`propwhirl.io.tables.update`).  ``python -m propwhirl.io
--update docs`` writes them (:func:`write`); a test checks that the committed pages are
:func:`pages`."""
from __future__ import annotations

from pathlib import Path

from propwhirl import fileio
from propwhirl.io import campaign_files, modal_files, schema, tables

#: The pages with generated parts → the function giving those parts.
PARTS = {"campaign.md": campaign_files.docs_parts,
         "modal-structures.md": modal_files.docs_parts}


def pages(folder: Path) -> dict[str, str]:
    """Each generated page's text as it should be, from the pages in `folder`."""
    out = {"model-file.md": schema.markdown()}
    for name, parts in PARTS.items():
        out[name] = tables.update((folder / name).read_text(encoding="utf-8"), parts())
    return out


def write(folder: Path) -> list[str]:
    """Rewrite the generated pages in `folder` that are not current; returns their names."""
    written = []
    for name, text in pages(folder).items():
        path = folder / name
        if not path.exists() or path.read_text(encoding="utf-8") != text:
            fileio.write_text(path, text, what="documentation page")
            written.append(name)
    return written
