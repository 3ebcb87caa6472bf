"""Campaign files (propwhirl.io.campaign_files, issue 24.1): the example reads; every bad key
is one line naming the file, the key as written, the value and what is valid; the cases of a
list and of a product, each propeller's own case; the model path relative to the file."""
from __future__ import annotations

import shutil
import tomllib
from pathlib import Path

import pytest
import tomli_w

from propwhirl.io.campaign_files import MAX_TASKS, load_campaign, loads
from propwhirl.studies import campaign as C
from propwhirl.studies.campaign import from_spec
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "wingtip_campaign.toml"


@pytest.fixture()
def doc() -> dict:
    return tomllib.loads(EXAMPLE.read_text())


def _load(doc: dict):
    return from_spec(loads(tomli_w.dumps(doc), "c.toml", EXAMPLE.parent))


def test_example_reads():
    c = from_spec(load_campaign(EXAMPLE))
    assert [x.name for x in c.cases] == [
        "nominal", "mount stiffness at 50 % (propeller 1)", "failed mount damper",
        "rotation reversed", "nacelle battery +20 kg"]
    assert [p.altitude_m for p in c.points] == [0.0, 2438.4, 5000.0]
    assert c.factor == 1.15 and c.regulation == "cs25" and c.min_damping_g is None
    assert c.points[0].V_D == 100.0 and c.points[2].V_D > 128.9        # EAS -> TAS


def test_model_path_is_relative_to_the_file(tmp_path):
    shutil.copy(EXAMPLE.parent / "wingtip.toml", tmp_path / "m.toml")
    doc = tomllib.loads(EXAMPLE.read_text())
    doc["model"] = "m.toml"
    (tmp_path / "c.toml").write_text(tomli_w.dumps(doc))
    assert len(from_spec(load_campaign(tmp_path / "c.toml")).cases) == 5


def _set(doc, path, value):
    *head, last = path
    d = doc
    for k in head:
        d = d[k]
    if value is _DELETE:
        del d[last]
    else:
        d[last] = value


_DELETE = object()

BAD = [
    (("format",), "propwhirl-model", ["format", "propwhirl-campaign"]),
    (("format_version",), 2, ["format_version", "2"]),
    (("model",), "missing.toml", ["model", "missing.toml"]),
    (("model",), 3, ["model", "a string"]),
    (("convention",), "mine", ["convention", "'mine'", "propwhirl, thesis"]),
    (("combine",), "sum", ["combine", "list, product"]),
    (("regulation", "name"), "cs23", ["[regulation] name", "'cs23'", "cs25, far25, far23"]),
    (("regulation", "factor"), 1.2, ["[regulation] factor", "1.15"]),
    (("regulation", "min_damping_g"), -0.1, ["[regulation] min_damping_g", "-0.1", "[0, 1]"]),
    (("regulation", "speed"), 1, ["unknown key 'speed'", "[regulation]"]),
    (("envelope", "airspeed"), "CAS", ["[envelope] airspeed", "'CAS'", "EAS, TAS"]),
    (("envelope", "V_D_m_per_s"), -5.0, ["[envelope] V_D_m_per_s", "-5.0", "[1, 1000]"]),
    (("envelope", "V_D_m_per_s"), [100.0, 110.0], ["[envelope] V_D_m_per_s", "one per altitude"]),
    (("envelope", "V_D_m_per_s"), "fast", ["[envelope] V_D_m_per_s", "'fast'", "a number"]),
    (("envelope", "altitudes_m"), [0.0, 99999.0], ["[envelope] altitudes_m", "[-5000, 32000]"]),
    (("envelope", "altitudes_m"), [], ["[envelope] altitudes_m", "1 to"]),
    (("envelope", "altitudes_ft"), [1000.0], ["altitudes_m, altitudes_ft"]),
    (("envelope", "M_D"), 1.5, ["[envelope] M_D", "1.5", "[0.01, 0.95]"]),
    (("envelope", "V_D_m_per_s"), _DELETE, ["missing key 'V_D_m_per_s'", "[envelope]"]),
    (("cases",), [], ["cases", "1 to"]),
    (("cases", 0, "name"), 7, ["[cases[0]] name", "a string"]),
    (("cases", 0, "name"), _DELETE, ["missing key 'name'", "[cases[0]]"]),
    (("cases", 0, "colour"), "red", ["unknown key 'colour'", "[cases[0]]"]),
    (("cases", 1, "mount_stiffness"), 0.0, ["[cases[1]] mount_stiffness", "0.0", "[0.001, 100]"]),
    (("cases", 1, "mount_stiffness"), True, ["[cases[1]] mount_stiffness", "a number"]),
    (("cases", 2, "mount_damping"), -1.0, ["[cases[2]] mount_damping", "-1.0", "[0, 100]"]),
    (("cases", 2, "wing_damping"), 1e9, ["[cases[2]] wing_damping", "[0, 100]"]),
    (("cases", 2, "operation"), "feathered", ["[cases[2]] operation", "'feathered'",
                                              "windmilling", "feathered or stopped rotors: state"]),
    (("cases", 2, "state"), "windmilling", ["[cases[2]] state", "'windmilling'",
                                            "feathered", "stopped", "operating"]),
    (("cases", 2, "state"), 1, ["[cases[2]] state", "a string"]),
    (("cases", 2, "rpm_factor"), 1.1, ["[cases[2]]", "rpm_factor", "fixed-pitch"]),
    (("cases", 2, "rpm_factor"), 50.0, ["[cases[2]] rpm_factor", "[0.1, 3]"]),
    (("cases", 3, "reverse_rotation"), "yes", ["[cases[3]] reverse_rotation", "true or false"]),
    (("cases", 3, "propellers"), [2], ["[cases[3]] propellers", "[2]", "[1, 1]"]),
    (("cases", 3, "propellers"), [1, 1], ["[cases[3]] propellers", "distinct"]),
    (("cases", 4, "added_masses"), [{"mass_kg": -1.0, "x_m": 0.0}],
     ["[cases[4].added_masses[0]] mass_kg", "-1.0"]),
    (("cases", 4, "added_masses"), [{"mass_kg": 1.0}],
     ["missing key 'x_m'", "[cases[4].added_masses[0]]"]),
    (("cases", 4, "values"), {"wing.EJ": 1.0}, ["[cases[4]]", "wing.EJ"]),
    (("cases", 4, "values"), {"wing.EI*": -2.0}, ["[cases[4]]", "wing.EI"]),
    (("cases", 4, "values"), {"wing.EI*": "x"}, ["[cases[4].values] wing.EI*", "'x'"]),
    (("cases", 4, "name"), "nominal", ["name 'nominal' is given twice"]),
    (("cases", 1, "each_propeller"), 1, ["[cases[1]] each_propeller", "true or false"]),
]


@pytest.mark.parametrize("path, value, words", BAD, ids=[
    f"{'.'.join(map(str, p))}={'del' if v is _DELETE else v!r}" for p, v, _ in BAD])
def test_every_bad_key_is_one_line(doc, path, value, words):
    _set(doc, path, value)
    with pytest.raises(InputError) as e:
        _load(doc)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith("c.toml: "), msg
    for w in words:
        assert w in msg, f"{w!r} not in {msg!r}"


def test_bad_toml_names_the_file():
    with pytest.raises(InputError, match=r"^c\.toml: not valid TOML"):
        loads("format = ", "c.toml")


def test_product_of_groups(doc):
    doc["combine"] = "product"
    doc["cases"] = [
        {"name": "nominal mount", "group": "mount"},
        {"name": "mount at 50 %", "group": "mount", "mount_stiffness": 0.5},
        {"name": "empty", "group": "mass"},
        {"name": "battery", "group": "mass", "added_masses": [{"mass_kg": 20.0, "x_m": -0.5}]},
    ]
    c = _load(doc)
    assert [x.name for x in c.cases] == ["nominal mount + empty", "nominal mount + battery",
                                         "mount at 50 % + empty", "mount at 50 % + battery"]
    both = c.cases[3]
    assert both.mount_stiffness == 0.5 and both.added_masses == ((20.0, -0.5),)
    del doc["cases"][0]["group"]
    with pytest.raises(InputError, match=r"missing key 'group' in \[cases\[0\]\]"):
        _load(doc)


def test_far23_and_explicit_factor_and_tas(doc):
    doc["regulation"] = {"name": "far23", "min_damping_g": 0.03,
                         "damping": {"applies_to": "total", "source": "company practice"}}
    c = _load(doc)
    assert c.factor == 1.2 and c.min_damping_g == 0.03
    assert c.damping_requirement == C.DampingRequirement(0.03, "total", 0.0, "all",
                                                         "company practice")
    doc["regulation"] = {"name": "explicit", "factor": 1.25}
    assert _load(doc).factor == 1.25
    doc["envelope"] = {"airspeed": "TAS", "V_D_m_per_s": [100.0, 110.0],
                       "altitudes_ft": [0.0, 10000.0]}
    c = _load(doc)
    assert [p.V_D for p in c.points] == [100.0, 110.0]
    assert c.points[1].altitude_m == pytest.approx(3048.0)


def test_too_many_analyses_refused_before_work(doc):
    doc["envelope"]["altitudes_m"] = [float(h) for h in range(0, 1000)]
    doc["cases"] = [{"name": f"c{i}"} for i in range(MAX_TASKS // 1000 + 1)]
    with pytest.raises(InputError, match="at most"):
        _load(doc)


# ------------------------------------------------------------------ issue 33, item 3
@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_a_device_as_the_model_is_refused_before_it_is_opened(doc, tmp_path, monkeypatch,
                                                              device):
    """`model = "/dev/zero"` grew past 4 GB; now one line naming the key and the file."""
    from helpers.files import never_opened

    doc["model"] = device
    (tmp_path / "c.toml").write_text(tomli_w.dumps(doc))
    never_opened(monkeypatch, device)
    with pytest.raises(InputError) as e:
        load_campaign(tmp_path / "c.toml")
    assert str(e.value) == (f"{tmp_path / 'c.toml'}: model = {device!r}: cannot read model file "
                            f"{device!r}: it is a character device, not a regular file "
                            "(propwhirl reads regular files only)")


def test_a_campaign_file_beyond_the_limit_is_refused_before_reading(tmp_path):
    from propwhirl import fileio

    path = tmp_path / "c.toml"
    with open(path, "wb") as fh:
        fh.truncate(fileio.MAX_TOML_BYTES + 1)          # sparse
    with pytest.raises(InputError, match=rf"c\.toml': it has {fileio.MAX_TOML_BYTES + 1:,} "
                                         rf"bytes, more than {fileio.MAX_TOML_BYTES:,}"):
        load_campaign(path)


# ----------------------------------------------- issue 35 item 2: [regulation] damping
def test_the_damping_reading_is_chosen_in_the_file_with_its_source(doc):
    doc["regulation"] = {"name": "cs25", "min_damping_g": 0.03, "damping": {
        "applies_to": "aerodynamic", "above_m_per_s": 20.0, "modes": "critical",
        "source": "MIL-A-8870C 3.1.1"}}
    req = _load(doc).damping_requirement
    assert (req.g_min, req.applies_to, req.above_m_per_s, req.modes, req.source) == (
        0.03, "aerodynamic", 20.0, "critical", "MIL-A-8870C 3.1.1")
    assert "aerodynamic increment" in req.describe() and "MIL-A-8870C" in req.describe()


def test_a_file_without_the_damping_reading_keeps_its_old_one(doc):
    """A file written before [regulation] damping existed keeps loading with the reading it
    had (the total damping of every mode at every analysed speed); the report says the
    reading was not stated."""
    doc["regulation"] = {"name": "cs25", "min_damping_g": 0.03}
    camp = _load(doc)
    assert camp.damping is None
    req = camp.damping_requirement
    assert (req.g_min, req.applies_to, req.above_m_per_s, req.modes, req.source) == (
        0.03, "total", 0.0, "all", "")
    assert req.describe().endswith("(its source not given)")


@pytest.mark.parametrize("damping, words", [
    ({"applies_to": "structural", "source": "x"},
     ["[regulation.damping] applies_to = 'structural'", "total, aerodynamic"]),
    ({"applies_to": "total"}, ["missing key 'source' in [regulation.damping]"]),
    ({"applies_to": "total", "source": " "}, ["[regulation.damping] source", "non-empty"]),
    ({"applies_to": "total", "source": "x", "above_m_per_s": -1.0},
     ["[regulation.damping] above_m_per_s = -1.0", "[0, 1000]"]),
    ({"applies_to": "total", "source": "x", "modes": "some"},
     ["[regulation.damping] modes = 'some'", "all, critical"]),
])
def test_a_bad_damping_reading_is_one_line(doc, damping, words):
    doc["regulation"] = {"name": "cs25", "min_damping_g": 0.03}
    if damping is not _DELETE:
        doc["regulation"]["damping"] = damping
    with pytest.raises(InputError) as e:
        _load(doc)
    assert len(str(e.value).splitlines()) == 1
    for w in words:
        assert w in str(e.value), str(e.value)


def test_a_damping_reading_without_a_requirement_is_refused(doc):
    doc["regulation"] = {"name": "cs25", "damping": {"applies_to": "total", "source": "x"}}
    with pytest.raises(InputError, match=r"\[regulation\] damping = .* absent without "
                                         "min_damping_g"):
        _load(doc)
