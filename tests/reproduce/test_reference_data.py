"""The package's copy of the thesis reference values equals the shared file."""
from pathlib import Path

import pytest

from propwhirl.reproduce.harness import load_references

ROOT = Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "reference" / "thesis_values.toml"
COPY = ROOT / "src" / "propwhirl" / "data" / "thesis_values.toml"


@pytest.mark.skipif(not SHARED.exists(), reason="../shared is not beside this checkout")
def test_package_copy_equals_shared_reference():
    assert COPY.read_bytes() == SHARED.read_bytes()


def test_references_have_unique_ids_and_positive_tolerances():
    refs = load_references()
    ids = [r.id for r in refs]
    assert len(ids) == len(set(ids)) > 100
    assert all(r.tol > 0 for r in refs)
