"""[flight] by its ISA altitude: altitude_m or altitude_ft instead of density and speed of sound
(issue 11, item 6)."""
from __future__ import annotations

from pathlib import Path

import pytest

from propwhirl import io
from propwhirl.io import schema
from propwhirl.model import atmosphere
from propwhirl.model.flight import FlightCondition
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = (ROOT / "examples" / "wingtip.toml").read_text()
AIR = "density_kg_per_m3 = 0.96287\nspeed_of_sound_m_per_s = 330.8027446243564\n"
assert AIR in EXAMPLE


def _with(flight_keys: str) -> str:
    return EXAMPLE.replace(AIR, flight_keys)


def _error(text: str) -> str:
    with pytest.raises(InputError) as exc:
        io.loads(text, "model.toml")
    msg = str(exc.value)
    assert msg.startswith("model.toml: ") and "\n" not in msg
    return msg


def test_altitude_in_metres_gives_the_isa_density_and_speed_of_sound():
    m = io.loads(_with("altitude_m = 5000.0\n"))
    assert m.flight == FlightCondition.from_altitude(altitude_m=5000.0)
    assert m.flight.density == atmosphere.density(5000.0)
    assert m.flight.speed_of_sound == atmosphere.speed_of_sound(5000.0)
    assert m.flight.speed_range == (1.0, 350.0, 10.0)   # the other keys are read as before


def test_8000_ft_is_the_example_files_air():
    """examples/wingtip.toml states the thesis's 8000 ft air; altitude_ft = 8000 gives it."""
    by_alt = io.loads(_with("altitude_ft = 8000\n"))
    given = io.loads(EXAMPLE)
    assert by_alt.flight.speed_of_sound == given.flight.speed_of_sound
    assert by_alt.flight.density == pytest.approx(given.flight.density, abs=0.5e-6)


def test_a_saved_file_states_the_density_and_speed_of_sound():
    m = io.loads(_with("altitude_m = 3000.0\n"))
    text = io.dumps(m)
    assert "altitude" not in text.split("[flight]")[1].split("[")[0]
    assert io.loads(text) == m


@pytest.mark.parametrize("keys, message", [
    ("altitude_m = 1000.0\naltitude_ft = 3000.0\n",
     "model.toml: [flight]: give one of altitude_m or altitude_ft, not both"),
    ("altitude_m = 1000.0\ndensity_kg_per_m3 = 1.0\n",
     "model.toml: [flight]: altitude_m gives density_kg_per_m3 and speed_of_sound_m_per_s (ISA); "
     "give either altitude_m or density_kg_per_m3, not both"),
    ("altitude_ft = 1000.0\n" + AIR,
     "model.toml: [flight]: altitude_ft gives density_kg_per_m3 and speed_of_sound_m_per_s (ISA); "
     "give either altitude_ft or density_kg_per_m3, speed_of_sound_m_per_s, not both"),
    ("altitude_m = 40000.0\n",
     "model.toml: [flight] altitude_m = 40000.0 is outside the valid range [-5000, 32000] m (ISA"),
    ("altitude_ft = -2e4\n",
     "model.toml: [flight] altitude_ft = -20000.0 is outside the valid range [-16400, 1.0498e5] ft"),
    ('altitude_m = "high"\n', "model.toml: [flight] altitude_m = 'high' is invalid: must be a number"),
    ("altitude_km = 3.0\n", "unknown key 'altitude_km' in [flight] (did you mean altitude_m?)"),
    ("speed_of_sound_m_per_s = 330.8\n",
     "model.toml: missing key 'density_kg_per_m3' in [flight] (air density"),
])
def test_bad_altitude_keys_are_errors_naming_the_file_and_keys(keys, message):
    assert message in _error(_with(keys))


def test_the_documentation_lists_the_altitude_keys():
    rows = {s.title: {r[0]: r for r in s.rows} for s in schema.sections()}["[flight]"]
    assert rows["altitude_m"][2:5] == ("m", "omitted", "[-5000, 32000] m")
    assert rows["altitude_ft"][2] == "ft"
    assert rows["density_kg_per_m3"][3] == "required unless altitude_m or altitude_ft"
    assert rows["speed_of_sound_m_per_s"][3] == "required unless altitude_m or altitude_ft"
    doc = (ROOT / "docs" / "model-file.md").read_text(encoding="utf-8")
    assert "| `altitude_ft` | number | ft |" in doc
