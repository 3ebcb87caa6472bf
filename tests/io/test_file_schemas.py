"""One declarative schema for every file kind (issue 38 item 3): campaign files and modal
model descriptions are read by propwhirl.io.tables.read from their declarations, their docs
key tables are generated from the same declarations, and a new key is one declaration."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
import tomli_w

from propwhirl.io import campaign_files as CF
from propwhirl.io import docs, modal_files, tables
from propwhirl.io.model_files import Table
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]


def test_the_generated_docs_are_current():
    for name, text in docs.pages(ROOT / "docs").items():
        assert (ROOT / "docs" / name).read_text(encoding="utf-8") == text, (
            f"docs/{name} is stale: rewrite it with `python -m propwhirl.io --update docs`")


def test_every_key_the_readers_take_is_documented():
    campaign = (ROOT / "docs" / "campaign.md").read_text(encoding="utf-8")
    for spec in (CF.TOP, CF.REGULATION, CF.ENVELOPE, CF.CASE, CF.MASS):
        for key in spec.names:
            assert f"| `{key}` |" in campaign, key
    modal = (ROOT / "docs" / "modal-structures.md").read_text(encoding="utf-8")
    for spec in (modal_files.TOP, modal_files.UNITS_TABLE, modal_files.MODES_TABLE,
                 modal_files.STRIPS_TABLE, modal_files.SWITCHES_TABLE, modal_files.INSTALLATION):
        for key in spec.names:
            assert f"| `{key}` |" in modal, key


def test_a_region_without_its_generator_is_refused():
    with pytest.raises(TypeError, match="no generator"):
        tables.update("<!-- generated: nothing -->\n<!-- end generated -->", {})
    with pytest.raises(TypeError, match="no region"):
        tables.update("text", {"campaign top": "x"})


def _spec_with_a_basis() -> type:
    """CampaignSpec with one more field, declared as a new campaign key would be."""
    return dataclasses.make_dataclass("Spec", [(
        "basis", str, CF.spec_field("regulation", tables.Key(
            "basis", "string", "the damping requirement's basis", choices=("g", "zeta"),
            default="g"), default="g"))], bases=(CF.CampaignSpec,), frozen=True)


def test_a_new_campaign_key_is_one_declaration():
    """A field of CampaignSpec declared with spec_field is read, checked, defaulted and
    documented with nothing else written."""
    Spec = _spec_with_a_basis()
    reg = CF._table("regulation", "[regulation]", "", spec=Spec)
    assert reg.names == ("name", "factor", "min_damping_g", "damping", "basis")
    assert tables.read(Table({"name": "cs25", "basis": "zeta"}, "regulation", reg.names),
                       reg)["basis"] == "zeta"
    assert tables.read(Table({"name": "cs25"}, "regulation", reg.names), reg)["basis"] == "g"
    with pytest.raises(InputError, match=r"^\[regulation\] basis = 'G' is invalid: must be one "
                                         r"of g, zeta$"):
        tables.read(Table({"name": "cs25", "basis": "G"}, "regulation", reg.names), reg)
    assert "| `basis` | `\"g\"` or `\"zeta\"` |  | `\"g\"` |" in tables.markdown(reg)


def test_a_new_campaign_key_reaches_the_spec(monkeypatch):
    """...and from a file to the CampaignSpec (the reader builds it from the declarations)."""
    Spec = _spec_with_a_basis()
    reg = CF._table("regulation", "[regulation]", "", spec=Spec)
    top = CF._table("", "Top level", "", CF.TOP.keys[:2], (
        tables.Key("regulation", "table", "", table=reg), CF.TOP["envelope"], CF.TOP["cases"]),
        spec=Spec)
    monkeypatch.setattr(CF, "CampaignSpec", Spec)
    monkeypatch.setattr(CF, "TOP", top)
    monkeypatch.setattr(CF, "REGULATION", reg)
    doc = {"format": CF.FORMAT, "format_version": 1, "model": "wingtip.toml",
           "regulation": {"name": "cs25", "basis": "zeta"},
           "envelope": {"airspeed": "EAS", "V_D_m_per_s": 100.0, "altitudes_m": [0.0]},
           "cases": [{"name": "nominal"}]}
    spec = CF.loads(tomli_w.dumps(doc), "c.toml", ROOT / "examples")
    assert spec.basis == "zeta" and spec.factor == 1.15 and spec.V_D == (100.0,)


def test_old_files_keep_loading():
    """The example campaign (format version 1) reads as before."""
    spec = CF.load_campaign(ROOT / "examples" / "wingtip_campaign.toml")
    assert (spec.regulation, spec.factor, spec.airspeed, spec.altitudes_m) == (
        "cs25", 1.15, "EAS", (0.0, 2438.4, 5000.0))
    assert [c.name for c in spec.cases][:2] == ["nominal", "mount stiffness at 50 %"]
    assert spec.cases[1].transform == {"mount_stiffness": 0.5}
