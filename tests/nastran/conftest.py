"""tests/nastran: the NASTRAN bulk data reader, which needs pyNastran (the ``nastran`` extra).

pyNastran 1.4.1 requires numpy < 2, so it lives in an environment of its own: ``make test``
builds ``.venv-nastran`` and runs these tests there (``make test-nastran``).  Where pyNastran
is not installed (the main ``.venv``) every test here is skipped, saying so.
"""
import importlib.util
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
HAVE_PYNASTRAN = importlib.util.find_spec("pyNastran") is not None
REASON = ("pyNastran is not installed in this environment (it needs numpy < 2): `make test` "
          "runs tests/nastran in .venv-nastran (make test-nastran)")


def pytest_collection_modifyitems(config, items):
    if HAVE_PYNASTRAN:
        return
    for item in items:
        if HERE in Path(str(item.fspath)).resolve().parents:
            item.add_marker(pytest.mark.skip(reason=REASON))
