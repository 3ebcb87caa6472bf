"""Issue 33, item 11: expanding a campaign is bookkeeping.  A campaign of 100 × 100 cases
spent 66 s and 135 MB in ``from_spec`` before any analysis: it built every (case, point)
model.  Now each case as written is built once, each altitude's flight condition once, each
distinct speed grid once, a product's combinations not at all (they are built with their
analyses), and the partial-results file's fingerprint digests the campaign once — the work
is counted here (calls, constructions, bytes per task), never timed (the timings:
benchmarks/campaign_expansion.py, docs/performance.md).  The tasks are those of building
every model the old way, and a campaign's time is estimated before its first analysis."""
from __future__ import annotations

import dataclasses
import tracemalloc
from pathlib import Path

import pytest

from helpers.work import count_calls
from propwhirl.io.campaign_files import loads
from propwhirl.studies import campaign as C
from propwhirl.studies import execution
from propwhirl.studies.clearance import clearance_speeds
from propwhirl.studies.partial import content_digest
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _text(n_cases: int, n_altitudes: int, product: bool = False, extra: str = "",
          model: str = "wingtip.toml") -> str:
    alts = ", ".join(f"{100.0 * i:.1f}" for i in range(n_altitudes))
    head = (f'format = "propwhirl-campaign"\nformat_version = 1\nmodel = "{model}"\n'
            f'combine = "{"product" if product else "list"}"\n[regulation]\nname = "cs25"\n'
            f'[envelope]\nairspeed = "EAS"\nV_D_m_per_s = 100.0\naltitudes_m = [{alts}]\n')
    if product:
        cases = "".join(f'[[cases]]\nname = "k{i}"\ngroup = "mount"\nmount_stiffness = '
                        f'{0.5 + i / n_cases}\n' for i in range(n_cases))
        cases += "".join(f'[[cases]]\nname = "m{i}"\ngroup = "mass"\nadded_masses = '
                         f'[{{ mass_kg = {1.0 + i}, x_m = -0.5 }}]\n' for i in range(n_cases))
    else:
        cases = "".join(f'[[cases]]\nname = "c{i}"\nmount_stiffness = {0.5 + i / n_cases}\n'
                        for i in range(n_cases))
    return head + cases + extra


def _spec(*args, base: Path = EXAMPLES, **kw):
    return loads(_text(*args, **kw), "scale.toml", base)


def _count(calls, file: str, name: str) -> int:
    return sum(n for (f, fn), n in calls.items() if f.endswith(file) and fn == name)


def _work(spec) -> dict[str, int]:
    from propwhirl.model.systems import PropellerWing

    built = []
    real = PropellerWing.__post_init__
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(PropellerWing, "__post_init__", lambda self: (built.append(1), real(self)))
        camp, calls = count_calls(C.from_spec, spec)
    return {"tasks": len(camp.cases) * len(camp.points), "models": len(built),
            "flights": _count(calls, "model/flight.py", "from_altitude"),
            "grids": _count(calls, "studies/clearance.py", "speed_grid")}


def test_the_models_built_grow_with_the_cases_not_with_the_tasks():
    few, many = _work(_spec(6, 4)), _work(_spec(6, 40))
    assert (few["tasks"], many["tasks"]) == (24, 240)
    assert many["models"] == few["models"] <= 6          # one per case: none per altitude
    assert (few["flights"], many["flights"]) == (4, 40)  # one per altitude
    # one per distinct grid: per altitude, a failure case's (V_D) and the others' (1.15 V_D)
    assert few["grids"] <= 2 * 4 and many["grids"] <= 2 * 40


def test_a_product_builds_its_groups_cases_not_their_combinations():
    w = _work(_spec(8, 2, product=True))
    assert w["tasks"] == 8 * 8 * 2
    assert w["models"] <= 8 + 8 and w["flights"] == 2 and w["grids"] <= 2 * 2


def _peak(spec) -> int:
    tracemalloc.start()
    try:
        C.from_spec(spec)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("product, small, large, most", [
    (False, (4, 10), (4, 200), 1000),       # the list: a task's record, key, shared model
    (True, (4, 1), (16, 1), 1500)])         # a product: and its combined Case
def test_the_bytes_per_task_are_bookkeeping(product, small, large, most):
    """The memory a task adds (tracemalloc's peak over a campaign many times as large): its
    record and key (a product's: its Case too), sharing its case's model, flight condition and
    speed grid — not a model of its own (before: 1.2 kB per task of a list, 3.0 kB of a
    product, every model built)."""
    a, b = _spec(*small, product=product), _spec(*large, product=product)
    _peak(a)                                           # caches of the first call: not counted
    n = (large[0] ** 2 if product else large[0] * large[1]) - (
        small[0] ** 2 if product else small[0] * small[1])
    per_task = (_peak(b) - _peak(a)) / n
    assert per_task < most, per_task


def test_the_partial_file_fingerprint_digests_the_campaign_once(tmp_path, monkeypatch):
    """One digest of the model, the cases and the points — not one model per task."""
    camp = C.from_spec(_spec(5, 6))
    seen = []
    monkeypatch.setattr(execution, "map_analyses", lambda func, todo, *a, **k: (
        seen.append(len(todo)), [execution.TaskError("Stop", "no analysis")] * len(todo))[1])
    cp = execution.Checkpoint(tmp_path / "c.partial")
    result, calls = count_calls(C.run_campaign, camp, checkpoint=cp)
    assert seen == [30] and len(result.rows) == 30
    assert _count(calls, "studies/partial.py", "content_digest") == 1
    assert _count(calls, "model/systems.py", "__post_init__") == 0     # no model built


@pytest.mark.parametrize("product", [False, True])
def test_the_tasks_are_those_of_building_every_model(product):
    """Every task's model and speeds are those of the campaign's model transformed by the
    case and put at the altitude (the old way: every model built), to the last bit."""
    extra = ('[[cases]]\nname = "wing"\ngroup = "wing"\nwing_damping = 0.5\nfailure = true\n'
             if product else '[[cases]]\nname = "failed"\nmount_damping = 0.0\n'
             '[[cases]]\nname = "each"\neach_propeller = true\nmount_damping = 0.5\n')
    spec = _spec(2, 3, product=product, extra=extra, model="four_propeller.toml")
    camp = C.from_spec(spec)
    todo, keys = C.tasks(camp)
    assert len(todo) == len(keys) == len(camp.cases) * len(camp.points)
    it = iter(todo)
    for case in camp.cases:
        for p in camp.points:
            t = next(it)
            m = C.at_altitude(case.apply(camp.model), p.altitude_m)
            V_req, _ = camp.required_speed(case, p)
            model, speeds = t.model, t.speeds
            assert content_digest(model) == content_digest(m)
            assert t.V_required == V_req and list(speeds) == list(clearance_speeds(m, V_req))


def test_a_combination_the_model_refuses_is_its_rows_error():
    """Two groups setting one field directly and by its scale: each case alone is fine, the
    combination is refused when its analysis builds it — that point's error, one line."""
    extra = ('[[cases]]\nname = "stiff"\ngroup = "mount"\nvalues = { "wing.EI*" = 1.1 }\n'
             '[[cases]]\nname = "set"\ngroup = "mass"\nvalues = { "wing.EI" = 2e6 }\n')
    camp = C.from_spec(_spec(1, 1, product=True, extra=extra))
    todo, keys = C.tasks(camp)
    bad = [t for t, k in zip(todo, keys) if k.startswith("stiff + set @")]
    assert len(bad) == 1
    with pytest.raises(InputError, match=r"^case 'stiff \+ set': parameter paths 'wing.EI\*' "
                                         r"and 'wing.EI' are invalid together"):
        bad[0].build()
    r = execution._Guarded(C.evaluate_point)(bad[0])
    assert isinstance(r, execution.TaskError) and "stiff + set" in r.message


def test_a_combination_refused_without_a_model_is_an_error_before_any_analysis(tmp_path):
    from propwhirl.io import load_model, save_model

    m = load_model(EXAMPLES / "wingtip.toml")
    cs = m.with_(propellers=(dataclasses.replace(m.propellers[0], propeller=dataclasses.replace(
        m.propellers[0].propeller, operation="constant-speed", rpm=1500.0)),))
    save_model(cs, tmp_path / "cs.toml")
    extra = ('[[cases]]\nname = "wm"\ngroup = "op"\noperation = "windmilling"\n'
             '[[cases]]\nname = "over"\ngroup = "rpm"\nrpm_factor = 1.1\n')
    text = _text(0, 1, product=True, extra=extra, model="cs.toml")
    with pytest.raises(InputError, match=r"^scale.toml: case 'wm \+ over': rpm_factor = 1.1 is "
                                         r"invalid for propeller 1: .*windmilling"):
        C.from_spec(loads(text, "scale.toml", tmp_path))


def test_a_campaign_is_estimated_before_its_first_analysis(monkeypatch, capsys):
    camp = C.from_spec(_spec(5, 4))
    monkeypatch.setattr(C, "evaluate_point", lambda t: pytest.fail("an analysis ran"))
    monkeypatch.setenv("PROPWHIRL_STUDY_TIME_LIMIT", "1s")
    with pytest.raises(InputError, match=r"^the study of 20 analyses of \d+ states: .* exceeds "
                                         r"1 s \(set PROPWHIRL_STUDY_TIME_LIMIT"):
        C.run_campaign(camp)
    monkeypatch.setenv("PROPWHIRL_STUDY_TIME_LIMIT", "none")
    monkeypatch.setattr(execution, "map_analyses", lambda func, todo, *a, **k: [
        execution.TaskError("Stop", "no analysis")] * len(todo))
    big = C.from_spec(_spec(100, 100))
    C.run_campaign(big, progress=True)
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: estimate: 10,000 analyses of "), err


def test_certify_refuses_a_campaign_beyond_the_time_limit(tmp_path, monkeypatch, capsys):
    from propwhirl.app import cli

    (tmp_path / "c.toml").write_text(_text(5, 4, model=(EXAMPLES / "wingtip.toml").as_posix()))
    monkeypatch.setattr(C, "evaluate_point", lambda t: pytest.fail("an analysis ran"))
    monkeypatch.setenv("PROPWHIRL_STUDY_TIME_LIMIT", "1s")
    assert cli.main(["certify", str(tmp_path / "c.toml"), "--out", str(tmp_path / "r"),
                     "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "exceeds 1 s" in err[0], err


def test_a_campaign_replaced_with_another_model_builds_its_own():
    """The models made once belong to their campaign: dataclasses.replace starts afresh."""
    camp = C.from_spec(_spec(2, 2))
    heavier = camp.model.with_(wing=dataclasses.replace(
        camp.model.wing, mass_per_length=camp.model.wing.mass_per_length * 1.1))
    other = dataclasses.replace(camp, model=heavier)
    for t, case in zip(C.tasks(other)[0][::2], other.cases):
        assert content_digest(t.model) == content_digest(C.at_altitude(
            case.apply(heavier), other.points[0].altitude_m))
