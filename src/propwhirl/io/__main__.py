"""``python -m propwhirl.io > docs/model-file.md``: print the model-file documentation.

``python -m propwhirl.io --update DOCS``: rewrite ``DOCS/model-file.md`` and the generated
parts of ``DOCS/campaign.md`` and ``DOCS/modal-structures.md`` (their key tables, from the
declarations of :mod:`propwhirl.io.tables`)."""
import sys
from pathlib import Path

from propwhirl.io import docs
from propwhirl.io.schema import markdown


def main(argv: list[str]) -> int:
    """Print docs/model-file.md, or with ``--update DOCS`` rewrite the generated pages."""
    if argv[:1] == ["--update"] and len(argv) == 2:
        for name in docs.write(Path(argv[1])):
            print(f"wrote {name}", file=sys.stderr)
        return 0
    if argv:
        print("usage: python -m propwhirl.io [--update DOCS_FOLDER]", file=sys.stderr)
        return 2
    sys.stdout.write(markdown())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
