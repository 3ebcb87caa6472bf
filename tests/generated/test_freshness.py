"""generated/ must be exactly what `make generate` produces from derivations/ today."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytest.importorskip("sympy", reason="the freshness check needs the codegen extra")


def test_regenerating_reproduces_generated_exactly(tmp_path):
    from derivations.generate import generate

    written = generate(tmp_path, verbose=False)
    committed = {p.name for p in (ROOT / "generated").glob("*.py")}
    assert set(written) == committed, "generated/ has stale or missing modules"
    for name, text in written.items():
        assert (ROOT / "generated" / name).read_text() == text, f"generated/{name} is stale"


def test_generated_modules_say_do_not_edit_and_name_their_derivation():
    for path in (ROOT / "generated").glob("*.py"):
        head = path.read_text().splitlines()[0]
        assert "do not edit" in head
        if path.name != "__init__.py":
            assert f"derivations/{path.name}" in head


def test_generation_is_deterministic(tmp_path):
    """Two runs of the generator give byte-identical modules (the slowest module suffices)."""
    from derivations.generate import generate

    a = generate(tmp_path / "a", only=["strip_aero", "beam_element"], verbose=False)
    b = generate(tmp_path / "b", only=["strip_aero", "beam_element"], verbose=False)
    assert a == b and set(a) == {"strip_aero.py", "beam_element.py"}
