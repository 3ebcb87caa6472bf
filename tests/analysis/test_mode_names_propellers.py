"""Mode names that say which propellers (issue 25, item 1): with several flexibly mounted,
spinning propellers a whirl mode is named by its propellers at V0; one-propeller models keep the
thesis's names; an event says what its mode is at the event when the name says otherwise; a
sweep point and the same point of a map give one name."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from propwhirl.analysis.events import describe_critical
from propwhirl.analysis.naming import mode_names, numbers_text
from propwhirl.analysis.stability import analyse
from propwhirl.app import cli
from propwhirl.io.model_files import load_model, loads

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: the high-lift propellers' whirl flutter near 80 m/s: a short range around it
X57_SPEEDS = np.arange(60.0, 101.0, 10.0)


def _x57(tip_f_psi: float | None = None):
    text = (EXAMPLES / "x57_like.toml").read_text()
    if tip_f_psi is not None:                   # the cruise (tip) propeller's yaw frequency
        assert text.count("f_psi_hz = 8.0") == 1
        text = text.replace("f_psi_hz = 8.0", f"f_psi_hz = {tip_f_psi}")
    return loads(text, "x57_like.toml")


@pytest.fixture(scope="module")
def x57():
    return analyse(_x57(), speeds=X57_SPEEDS)


@pytest.fixture(scope="module")
def wingtip():
    return analyse(load_model(EXAMPLES / "wingtip.toml"))


def test_numbers_text():
    assert numbers_text([3, 1, 2, 7]) == "propellers 1–3, 7"
    assert numbers_text([7]) == "propeller 7"


def test_several_propellers_names_carry_family_and_propellers(x57):
    whirls = [n for n in x57.sweep.mode_labels
              if n.startswith(("backward", "forward")) and not n.endswith("'")]
    assert whirls and all("whirl, propeller" in n for n in whirls)
    assert "backward whirl, propeller 7" in whirls              # the tip propeller's yaw
    high_lift = [n for n in whirls if n.startswith("backward whirl, propellers 1–6 (")]
    assert sorted(n.split("(")[1].split(" of")[0] for n in high_lift) == [str(k) for k in range(1, 7)]
    c = x57.critical
    assert c.kind == "flutter" and c.label.startswith("backward whirl, propellers 1–6 (")
    thesis = x57.thesis_names[c.label]                          # the thesis's name still finds it
    assert thesis.startswith("backward ") and x57.first(thesis, "flutter") == c


def test_one_propeller_names_unchanged(wingtip):
    model = load_model(EXAMPLES / "wingtip.toml")
    names = mode_names(model, wingtip.sweep)
    assert names == mode_names(model, wingtip.sweep, thesis=True) and not wingtip.thesis_names
    assert {"wing 1", "wing 2", "backward 1", "forward 1"} <= set(names)
    assert wingtip.first("forward 1", "flutter").V == pytest.approx(159.39, abs=0.01)


def test_event_line_says_what_the_mode_is_at_the_event(wingtip, x57):
    e = wingtip.first("forward 1", "flutter")                   # named forward, whirls backward
    line = describe_critical(e, wingtip.describe)
    assert line.startswith("flutter of forward 1 (yaw; backward whirl at the onset) at 159.39 m/s")
    assert "\n" not in line
    assert "at the flutter onset of forward 1 (159.39 m/s; backward whirl at the onset)" in \
        wingtip.summary()
    same = describe_critical(x57.critical, x57.describe)        # the name says it: nothing added
    assert "at the onset" not in same


def test_a_parameter_moving_another_set_keeps_the_names():
    """The tip propeller's yaw frequency moves its modes through the others' (on main: the
    same critical event was 'forward 1' at f_ψ = 6 Hz and 'backward 2' at 8 Hz)."""
    labels = {analyse(_x57(f), speeds=X57_SPEEDS).critical.label for f in (6.0, 8.0)}
    assert len(labels) == 1 and labels.pop().startswith("backward whirl, propellers 1–6")


def _critical_modes(path: Path) -> dict[tuple[str, ...], str]:
    with path.open() as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    head = rows[0]
    mode = next(i for i, h in enumerate(head) if h.startswith("critical_mode"))
    params = [i for i, h in enumerate(head) if h.startswith("propellers[")]
    return {tuple(f"{float(r[i]):g}" for i in params): r[mode] for r in rows[1:]}


def test_sweep_and_map_name_the_same_point_alike(tmp_path):
    """The wingtip model with f_θ = 12, f_ψ = 8 Hz, thesis convention (its critical: the
    whirl flutter near 171 m/s): as a sweep point and as a map point."""
    text = (EXAMPLES / "wingtip.toml").read_text().replace("f_theta_hz = 7.0", "f_theta_hz = 12.0")
    model = tmp_path / "wingtip12.toml"
    model.write_text(text)
    p = "propellers[0].propeller"
    assert cli.main(["sweep", str(model), "--param", f"{p}.f_psi", "8", "8", "1", "--quiet",
                     "--thesis-convention", "--csv", str(tmp_path / "s.csv")]) == 0
    assert cli.main(["map", str(model), "--param", f"{p}.f_theta", "12", "12", "1", "--param",
                     f"{p}.f_psi", "8", "8", "1", "--quiet", "--thesis-convention",
                     "--csv", str(tmp_path / "m.csv")]) == 0
    (swept,) = _critical_modes(tmp_path / "s.csv").values()
    (mapped,) = _critical_modes(tmp_path / "m.csv").values()
    assert swept == mapped == "forward 1"


def test_names_do_not_depend_on_the_basis_lapack_gives_a_repeated_frequency(monkeypatch):
    """The six high-lift propellers' yaw modes of examples/x57_like.toml share one in-vacuo
    frequency (12 Hz, equal to 1e-12): LAPACK returns any basis of that subspace, and numpy
    1.26's gave the critical mode the thesis name "forward 2" where numpy 2's gave
    "backward 3" (issue 36, item 2).  Any other orthonormal basis of the repeated subspaces
    gives the same names now (naming._matched: the group matched as a subspace)."""
    import dataclasses

    from propwhirl.analysis import modes as modes_module
    from propwhirl.analysis import naming

    model = _x57()
    before = analyse(model, speeds=X57_SPEEDS)
    real = naming.model_modes
    rng = np.random.default_rng(36)

    def turned(*args, **kwargs):
        m, mass = real(*args, **kwargs)
        groups = modes_module.repeated_groups(m.omega)
        assert [g.size for g in groups] == [6]
        shapes = m.shapes.copy()
        for g in groups:                   # another mass-orthonormal basis of the subspace
            q, _ = np.linalg.qr(rng.standard_normal((g.size, g.size)))
            shapes[:, g] = shapes[:, g] @ q
        return dataclasses.replace(m, shapes=shapes), mass

    monkeypatch.setattr(naming, "model_modes", turned)
    for _ in range(3):
        after = analyse(model, speeds=X57_SPEEDS)
        assert after.thesis_names == before.thesis_names
        assert after.sweep.mode_labels == before.sweep.mode_labels
    assert before.thesis_names[before.critical.label] == "backward 3"
