"""The capability table (issue 34 item 1): docs/capabilities.md is what the model contract
answers (generated, so it cannot drift), every refused cell is the one line the command or
method prints, and every other cell runs — each command on one model file of each kind
(small models, coarse grids: this bounds the work, not the time)."""
from __future__ import annotations

from pathlib import Path

import pytest

from propwhirl.app import capability_table as ct
from propwhirl.app import cli
from propwhirl.io import save_model, write_modes
from propwhirl.model.protocol import COMMANDS, FEATURES, METHODS, refusal

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGN = """format = "propwhirl-campaign"
format_version = 1
model = "{model}"
[regulation]
name = "cs25"
[envelope]
airspeed = "EAS"
V_D_m_per_s = 60.0
altitudes_m = [0.0]
[[cases]]
name = "nominal"
"""
P, Q = "flight.density", "flight.speed_of_sound"


def test_the_committed_page_is_the_generated_one():
    page = (ROOT / "docs" / "capabilities.md").read_text(encoding="utf-8")
    assert page == ct.page(), ("docs/capabilities.md is stale: run "
                               "`python -m propwhirl.app.capability_table docs/capabilities.md`")
    assert "capabilities.md" in (ROOT / "mkdocs.yml").read_text(encoding="utf-8")


def test_every_sample_states_every_feature():
    for key, _, _, c in ct.sample_capabilities():
        for f in FEATURES:
            why = c.refusal(f)
            assert why is None or (why and "\n" not in why), (key, f)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A model file of each kind the command line reads (the typical section has none)."""
    d = tmp_path_factory.mktemp("kinds")
    samples = {key: build for key, _, _, build in ct.SAMPLES}
    out = {}
    for key in ("beam", "dlm", "wing", "isolated"):
        out[key] = d / f"{key}.toml"
        save_model(samples[key](), out[key])
    for key, beam, mount in (("modal", "beam", "own"), ("on-grid", "beam", "on-grid"),
                             ("modal-dlm", "dlm", "own")):
        out[key] = d / f"{key}.toml"
        write_modes(samples[beam](), out[key], 6, mount=mount)
    for key, f in out.items():
        (d / f"camp-{key}.toml").write_text(CAMPAIGN.format(model=f.name))
    return d, out


def _argv(feature: str, f: Path, d: Path, key: str) -> list[str]:
    grid = ["--speeds", "100", "200", "50"]
    return {
        "analyse": ["analyse", f, *grid, "--quiet"],
        "modes": ["modes", f, "--count", "3"],
        "campbell": ["campbell", f, "--rpm", "0", "2000", "2", "--count", "3"],
        "sweep": ["sweep", f, "--param", P, "0.9", "1.0", "2", *grid, "--quiet"],
        "map": ["map", f, "--param", P, "0.9", "1.0", "2", "--param", Q, "300", "340", "2",
                *grid, "--quiet"],
        "boundary": ["boundary", f, "--params", P, Q, "--speed", "150", "--bounds", "0.5",
                     "1.2", "300", "340", "--grid", "0"],
        "clearance": ["clearance", f, "--vd", "60", "--quiet"],
        "certify": ["certify", d / f"camp-{key}.toml", "--out", d / f"out-{key}", "--no-report",
                    "--quiet"],
        "sensitivity": ["sensitivity", f, "--top", "2"],
        "export": ["export", f, "--out", d / f"{key}.bdf"],
        "upgrade-model": ["upgrade-model", f, d / f"up-{key}.toml"],
        **{m: ["analyse", f, *grid, "--quiet", "--method", m] for m in METHODS},
    }[feature]


CELLS = [(key, f) for key, *_ in ct.SAMPLES if key != "section" for f in COMMANDS + METHODS]


@pytest.mark.parametrize("key, feature", CELLS)
def test_each_cell_runs_or_prints_its_refusal(files, key, feature, capsys):
    d, paths = files
    model = dict((k, b) for k, _, _, b in ct.SAMPLES)[key]()
    why = refusal(model, feature)
    code = cli.main([str(a) for a in _argv(feature, paths[key], d, key)])
    err = capsys.readouterr().err
    if why is None:
        assert code in (0, 1), err                        # ran (1: not cleared)
        return
    src = paths[key] if feature != "certify" else d / f"camp-{key}.toml"
    said = (f"method = {feature!r} is invalid for this model: {why}" if feature in METHODS
            else f"propwhirl {feature} cannot run this model: {why}")
    assert code == 2 and err.count("\n") == 1 and said in err, (src, err)


def test_the_typical_section_refuses_each_command_as_the_table_says():
    from propwhirl.analysis import analyse
    from propwhirl.analysis.reduced import choose_method
    from propwhirl.analysis.sensitivity import critical_sensitivities
    from propwhirl import validate as v

    section = dict((k, b) for k, _, _, b in ct.SAMPLES)["section"]()
    for f in COMMANDS:
        assert "no model file" in refusal(section, f)
    with pytest.raises(v.InputError, match="nothing to reduce"):
        choose_method(section, "reduced")
    a = analyse(section, speeds=[10.0, 50.0, 100.0], method="pk")   # dense and p-k run
    assert a.events
    with pytest.raises(v.InputError, match="full-order pencil"):   # the exact route's check
        critical_sensitivities(section, a)
