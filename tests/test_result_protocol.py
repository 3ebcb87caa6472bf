"""One result protocol (issue 21, item 4): every result propwhirl saves is a
propwhirl.results.Result — saved and re-read (save/load, to_dict/from_dict), its format tag
``propwhirl.<kind>/<version>``, files of older releases still loading (fixtures written by the
code before this protocol: tests/data/old_results), a file of another kind refused naming both,
a corrupted entry one line naming the file and the key.  And the analysis package without the
stability ↔ files ↔ pk cycle (item 2)."""
from __future__ import annotations

import ast
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from propwhirl.analysis.campbell import CampbellResult, campbell
from propwhirl.analysis.response import Response, simulate
from propwhirl.analysis.sensitivity import CriticalSensitivities, Sensitivity
from propwhirl.analysis.stability import ModelAnalysis, analyse
from propwhirl.analysis.summary import FlutterSummary, Reference
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.engine import Analysis
from propwhirl.engine.free_response import TimeResponse, time_response
from propwhirl.reproduce.harness import Records
from propwhirl.results import FORMAT_PATTERN, Result
from propwhirl.studies.boundary import Boundary
from propwhirl.studies.clearance import Clearance
from propwhirl.studies.campaign_result import CampaignResult, PointRow
from propwhirl.studies.gradients import OptimisationResult
from propwhirl.studies.sensitivity_check import SensitivityCheck, SensitivityVerification
from propwhirl.studies.parametric import ModeSwitch
from propwhirl.studies.sweeps import CriticalMap
from propwhirl.studies.table import StudyTable
from propwhirl.validate import InputError

OLD = Path(__file__).parent / "data" / "old_results"
SRC = Path(__file__).resolve().parent.parent / "src" / "propwhirl"


@pytest.fixture(scope="module")
def results() -> dict[type, Result]:
    """One result of every kind (cheap: three speeds of the isolated propeller; the study
    results and the Campbell diagram from the files written by the code before the
    protocol)."""
    iso = isolated_baseline_propeller()
    a = analyse(iso, speeds=[100.0, 200.0, 250.0])
    A = np.array([[0.0, 1.0], [-4.0, -0.1]])
    sens = CriticalSensitivities(
        221.5, 5.01, "flutter", "onset", "backward", complex(1e-4, 31.5), complex(0.02, -0.01),
        (Sensitivity("propeller.f_theta", 7.0, "Hz", "pitch frequency", complex(0.5, -1.0),
                     12.0, 0.1, 0.38),
         Sensitivity("propeller.f_psi", 7.0, "Hz", "yaw frequency", complex(-0.5, 2.0),
                     -3.0, 0.2, -0.09)))
    table = StudyTable("motor mass", "mass",
                       {"model": np.array(["isolated", "wing"], dtype=object),
                        "mass": np.array([10.0, 20.0]),
                        "critical_speed": np.array([150.0, math.nan]),
                        "kind": np.array(["flutter", "none"], dtype=object)},
                       {"mass": "kg", "critical_speed": "m/s"})
    return {
        ModelAnalysis: a,
        Analysis: Analysis(a.sweep, a.criticals),
        TimeResponse: time_response(A, [1.0, 0.0], np.linspace(0.0, 1.0, 5), ["x", "v"]),
        Clearance: Clearance.load(OLD / "clearance-1.json"),
        Boundary: Boundary.load(OLD / "boundary-1.json"),
        CriticalMap: CriticalMap.load(OLD / "critical-map-1.json"),
        StudyTable: table,
        CriticalSensitivities: sens,
        # one check passed, one whose perturbed analysis failed (its speeds and FD null)
        SensitivityVerification: SensitivityVerification(
            sens, "auto", np.array([100.0, 200.0, 250.0]), 0.01, 1e-3, 0.01, 1e-4, 4, (
                SensitivityCheck("propeller.f_theta", "Hz", 7.0, 0.007, None, 12.0, 221.584,
                                 221.416, 12.0, "ok"),
                SensitivityCheck("propeller.f_psi", "Hz", 7.0, 0.007, None, -3.0, None, None,
                                 None, "failed", "InputError: out of range"))),
        CampbellResult: CampbellResult.load(OLD / "campbell-untagged-1.json"),
        Response: simulate(iso, 200.0, {"propeller 1 theta": 0.01}, duration=0.05, dt=0.01),
        FlutterSummary: a.flutter_summary(),
        # NaN: that mode does not flutter in the speed range (saved as null)
        ModeSwitch: ModeSwitch(73.5, (73.0, 74.0), ((60.0, 151.2, math.nan),
                                                    (73.0, 160.4, 171.0),
                                                    (74.0, 172.3, 160.6),
                                                    (80.0, math.nan, 161.0))),
        Records: Records.load(OLD / "reproduction-untagged-1.json"),
        # V = inf: nothing unstable in the range (saved as null)
        OptimisationResult: OptimisationResult(
            ("propellers[0].propeller.K_theta", "propellers[0].propeller.K_psi"),
            np.array([1.2e5, 0.9e5]), math.inf, 0.93, True, "Optimization terminated "
            "successfully", 14, np.array([1.21e5, 0.9e5]), 47),
        # a point without instability in its range (V_crit and margins null)
        CampaignResult: CampaignResult("c", "wing", "cs25", 1.15, 0.03, "propwhirl", (PointRow(
            "nominal", "nominal", 0.0, "EAS", 100.0, 100.0, False, 115.0, True, "", None, None,
            None, "none", "", "", None, "", (), 351.0, 0.04, 1.0, "wing 1", 0.04, "wing 1",
            0.05, 1e-4, "wing 1", ""),), 1),
    }


def _all_subclasses(cls: type) -> set[type]:
    out = set()
    for sub in cls.__subclasses__():
        out |= {sub} | _all_subclasses(sub)
    return out


def test_every_result_type_is_covered_here(results):
    """A new Result must be added to `results` (so these tests hold it to the protocol)."""
    import propwhirl.analysis  # noqa: F401
    import propwhirl.analysis.campbell  # noqa: F401
    import propwhirl.analysis.modes  # noqa: F401
    import propwhirl.analysis.response  # noqa: F401
    import propwhirl.analysis.summary  # noqa: F401
    import propwhirl.reproduce.harness  # noqa: F401
    import propwhirl.studies.boundary  # noqa: F401
    import propwhirl.studies.gradients  # noqa: F401
    import propwhirl.studies.parametric  # noqa: F401
    import propwhirl.studies.sensitivity_check  # noqa: F401
    import propwhirl.studies.sweeps  # noqa: F401
    import propwhirl.studies.table  # noqa: F401

    assert _all_subclasses(Result) <= set(results)


KINDS = [ModelAnalysis, Analysis, TimeResponse, Clearance, Boundary, CriticalMap, StudyTable,
         CriticalSensitivities, SensitivityVerification, CampbellResult, Response, FlutterSummary,
         ModeSwitch, OptimisationResult, Records, CampaignResult]


def test_the_user_facing_results_are_results():
    """Issue 21.4: every result a public function returns (and the command line prints or
    saves) implements the protocol: a kind of its own, save/load, a checked decode in its
    own module."""
    for cls in KINDS:
        assert issubclass(cls, Result) and cls.KIND, cls
        assert "decode" in vars(cls) and "encode" in vars(cls), cls
    assert len({cls.KIND for cls in KINDS}) == len(KINDS)


@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.KIND)
def test_save_and_load_round_trip(results, cls, tmp_path):
    r = results[cls]
    path = r.save(tmp_path / "r.json")
    doc = json.loads(Path(path).read_text())
    m = FORMAT_PATTERN.fullmatch(doc["format"])
    assert m and m.group(1) == cls.KIND and int(m.group(2)) == cls.VERSION
    assert cls.VERSION in cls.READABLE
    back = cls.load(path)
    assert type(back) is cls
    assert back.to_dict() == r.to_dict()
    assert cls.from_dict(json.loads(json.dumps(r.to_dict()))).to_dict() == r.to_dict()


@pytest.mark.parametrize("name, cls", [
    ("analysis-v2.json", ModelAnalysis),            # "propwhirl-analysis", format_version 2
    ("analysis-untagged-v1.json", ModelAnalysis),   # before the format keys existed
    ("clearance-1.json", Clearance),
    ("boundary-1.json", Boundary),
    ("critical-map-1.json", CriticalMap),
    ("campbell-untagged-1.json", CampbellResult),   # json.dumps(campbell(...).to_dict())
    ("reproduction-untagged-1.json", Records),      # propwhirl reproduce --only t9.5 --json
])
def test_files_of_earlier_releases_still_load(name, cls, tmp_path):
    """Written by propwhirl before the protocol (main at 2d5b893): they load, and saving
    them again writes the current format, which reads back the same."""
    old = cls.load(OLD / name)
    new = old.save(tmp_path / "new.json")
    assert json.loads(Path(new).read_text())["format"] == cls.format_name()
    assert cls.load(new).to_dict() == old.to_dict()


#: Relative agreement of an old file's numbers with the same analysis computed now.  The
#: fixtures were written on another platform's LAPACK: the digits below its rounding (the
#: crossings are refined to 0.01 m/s, the eigenvalues solved to ~1e-14) differ between
#: platforms (numpy 1.26.4 and 2.4 differ by 5e-14 in V, 5e-11 in the benignity dζ/dV, a
#: difference of two nearby slopes), so equality would test the platform, not the format;
#: 1e-9 is far above those and far below any digit the engine resolves.
ACROSS_PLATFORMS = 1e-9


def _same(a, b, path: str = "") -> None:
    """``a`` equals ``b`` (dataclasses, sequences, numbers) with floats to ACROSS_PLATFORMS
    (shares that are 0 in one: to 1e-12 absolute)."""
    import dataclasses

    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        assert type(a) is type(b), path
        for f in dataclasses.fields(a):
            _same(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
    elif isinstance(a, (tuple, list)):
        assert isinstance(b, (tuple, list)) and len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{path}[{i}]")
    elif isinstance(a, float) and not isinstance(a, bool):
        assert math.isclose(a, b, rel_tol=ACROSS_PLATFORMS, abs_tol=1e-12), (path, a, b)
    else:
        assert a == b, (path, a, b)


def test_old_analysis_files_read_as_the_new_ones(results):
    a = results[ModelAnalysis]
    for name in ("analysis-v2.json", "analysis-untagged-v1.json"):
        old = ModelAnalysis.load(OLD / name)
        _same(old.events, a.events, "events")
        _same(old.critical, a.critical, "critical")
        np.testing.assert_allclose(old.sweep.eigenvalues, a.sweep.eigenvalues,
                                   rtol=ACROSS_PLATFORMS, atol=0.0)


def test_old_campbell_file_is_the_diagram_computed_now():
    """The fixture (main at 19687c0: ``json.dumps(campbell(wingtip_propeller_wing(), [0.0,
    2000.0, 4000.0], max_frequency_hz=10.0).to_dict())``) reads back as that diagram."""
    old = CampbellResult.load(OLD / "campbell-untagged-1.json")
    new = campbell(wingtip_propeller_wing(), [0.0, 2000.0, 4000.0], max_frequency_hz=10.0)
    assert (old.labels, old.families, old.rpm_ratio) == (new.labels, new.families, new.rpm_ratio)
    assert np.allclose(old.frequency_hz, new.frequency_hz, rtol=1e-9, atol=0.0)
    assert np.array_equal(old.rpm, new.rpm) and np.array_equal(old.resolved, new.resolved)


def test_a_flutter_summary_with_k_zero_round_trips(results, tmp_path):
    """1/k is infinite where k = 0 (a real root): saved as null, read back as infinity."""
    fs = results[FlutterSummary]
    cols = {key: np.array(col, copy=True) for key, col in fs.columns.items()}
    cols["k"][0], cols["inv_k"][0] = 0.0, math.inf
    path = FlutterSummary(cols, fs.reference, fs.model_name).save(tmp_path / "s.json")
    assert json.loads(Path(path).read_text())["columns"]["inv_k"][0] is None
    back = FlutterSummary.load(path)
    assert back.columns["inv_k"][0] == math.inf and back.to_csv() == FlutterSummary(
        cols, fs.reference, fs.model_name).to_csv()


def test_the_old_records_file_keeps_its_keys(results, tmp_path):
    """`propwhirl reproduce --json`: the same record keys as before the protocol, and the
    records of the old file read back (tolerance not saved: NaN)."""
    old = json.loads((OLD / "reproduction-untagged-1.json").read_text())
    new = json.loads(Path(results[Records].save(tmp_path / "r.json")).read_text())
    assert new["records"] == old["records"] and set(new) == {"format", "records"}
    assert all(math.isnan(r.tol) for r in results[Records].records)


def test_old_untagged_engine_dicts_load(results):
    """The engine's Analysis and TimeResponse dicts and CampbellResult's had no format: read
    as version 1."""
    for cls in (Analysis, TimeResponse, CampbellResult, Records):
        d = results[cls].to_dict()
        del d["format"]
        assert cls.from_dict(d).to_dict() == results[cls].to_dict()


@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.KIND)
@pytest.mark.parametrize("other", KINDS, ids=lambda c: c.KIND)
def test_a_file_of_another_kind_is_refused_naming_both(results, cls, other, tmp_path):
    if cls is other:
        return
    path = results[other].save(tmp_path / "other.json")
    with pytest.raises(InputError) as err:
        cls.load(path)
    text = str(err.value)
    assert "\n" not in text and text.startswith(str(path))
    assert f"is a {other.KIND} file" in text or f"is an {other.KIND} file" in text, text
    assert f"not a {cls.WHAT}" in text or f"not an {cls.WHAT}" in text, text


@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.KIND)
def test_a_newer_version_is_refused(results, cls, tmp_path):
    d = results[cls].to_dict()
    d["format"] = cls.format_name(cls.VERSION + 1)
    path = tmp_path / "r.json"
    path.write_text(json.dumps(d))
    with pytest.raises(InputError, match=rf"version {cls.VERSION + 1} is not supported "
                                         r"\(written by a newer propwhirl\?\)"):
        cls.load(path)


@pytest.mark.parametrize("text", ["", "{", "[]", '{"format": NaN}', "\x00\xff", "null"])
@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.KIND)
def test_not_json_or_not_an_object(cls, text, tmp_path):
    path = tmp_path / "r.json"
    path.write_bytes(text.encode("latin-1"))
    with pytest.raises(InputError) as err:
        cls.load(path)
    assert "\n" not in str(err.value) and str(err.value).startswith(str(path))


def _leaves(d, where=()):
    """Every (path, value) of a JSON document, containers included."""
    yield where, d
    if isinstance(d, dict):
        for k, x in d.items():
            yield from _leaves(x, where + (k,))
    elif isinstance(d, list):
        for i, x in enumerate(d):
            yield from _leaves(x, where + (i,))


def _replaced(d, where, value):
    d = json.loads(json.dumps(d))
    if not where:
        return value
    target = d
    for k in where[:-1]:
        target = target[k]
    target[where[-1]] = value
    return d


JSON_VALUES = st.one_of(st.none(), st.booleans(), st.integers(-10**30, 10**30),
                        st.floats(allow_nan=False, allow_infinity=False), st.text(max_size=5),
                        st.lists(st.integers(-3, 3), max_size=3),
                        st.dictionaries(st.text(max_size=3), st.integers(), max_size=2))


@pytest.mark.parametrize("cls", KINDS, ids=lambda c: c.KIND)
@settings(max_examples=60, suppress_health_check=[HealthCheck.function_scoped_fixture],
          deadline=None)
@given(data=st.data())
def test_a_corrupted_entry_loads_or_is_one_line(results, cls, data, tmp_path):
    """Any entry replaced by any JSON value: the file loads (a value that is still valid) or
    gives one InputError line starting with the file — never another exception."""
    doc = results[cls].to_dict()
    leaves = [w for w, _ in _leaves(doc) if w != ("format",)]
    where = data.draw(st.sampled_from(leaves))
    path = tmp_path / "r.json"
    path.write_text(json.dumps(_replaced(doc, where, data.draw(JSON_VALUES))))
    try:
        cls.load(path)
    except InputError as exc:
        assert "\n" not in str(exc) and str(exc).startswith(str(path)), str(exc)


@pytest.mark.parametrize("cls, where, value, match", [
    (ModelAnalysis, ("events", 0, "V"), "fast", r"events\[0\]\.V: must be a finite number"),
    # an integer beyond a float (was a TypeError from numpy in SavedDict.number)
    (ModelAnalysis, ("events", 0, "V"), 10 ** 400, r"events\[0\]\.V: must be a finite number"),
    (ModelAnalysis, ("reference", "density_kg_per_m3"), 10 ** 30 * 10 ** 300,
     r"reference\.density_kg_per_m3: must be a finite number"),
    (Clearance, ("margins", 0, "counted"), 1, r"margins\[0\]\.counted: must be true or false"),
    (Clearance, ("V_D",), None, r"V_D: must be a finite number, got None"),
    (Boundary, ("curves", 0, "points"), [[1.0]], r"curves\[0\]\.points: shape \(1, 1\)"),
    (CriticalMap, ("columns", "critical_speed"), [1.0], r"columns\.critical_speed: column"),
    (CriticalMap, ("axes", 0, "values"), "x", r"axes\[0\]\.values: must be a list"),
    (StudyTable, ("columns", "mass"), [1.0, "a"], r"columns\.mass: must hold finite numbers"),
    (CriticalSensitivities, ("sensitivities", 1, "dlam_dp"), 3.0,
     r"sensitivities\[1\]\.dlam_dp: must be an object"),
    (TimeResponse, ("x",), [[1.0, 2.0]], r"x: shape \(1, 2\): axis 0 must have 5 entries"),
    (CampbellResult, ("rpm",), [4000.0, 0.0, 2000.0], r"rpm: must be increasing speeds"),
    (CampbellResult, ("unresolved",), [[2000.0, 0.0]], r"unresolved\[0\]: must be a pair"),
    (CampbellResult, ("families",), ["wing bending"], r"families: has 1 entries, need 3"),
    (CampbellResult, ("families", 0), "wing", r"families: 'wing' is invalid"),
    (CampbellResult, ("frequency_hz", 1), [1.0, 2.0], r"frequency_hz: must be a rectangular"),
    (CampbellResult, ("resolved", 0), 1, r"resolved: must hold booleans"),
    (Response, ("n_dof",), 9, r"n_dof: = 9 is outside \[0, 2\]"),
    (Response, ("eigenvectors", "im"), [[0.0]], r"eigenvectors\.im: shape \(1, 1\)"),
    (Response, ("V_m_per_s",), -1.0, r"V_m_per_s = -1\.0 is invalid: must be > 0"),
    (FlutterSummary, ("columns", "inv_k", 0), -1.0,
     r"columns\.inv_k\[0\]: must be a number > 0 or null"),
    (FlutterSummary, ("columns", "mach"), [0.3], r"columns\.mach: shape \(1,\): axis 0"),
    (FlutterSummary, ("columns", "label"), ["a"], r"columns\.label: has 1 entries, need 6"),
    (FlutterSummary, ("reference", "density_kg_per_m3"), 0.0, r"reference: density"),
    (ModeSwitch, ("beta_deg",), 90.0, r"beta_deg = 90\.0 is invalid: must lie in bracket"),
    (ModeSwitch, ("evaluations", 0, "V_forward_m_per_s"), -1.0,
     r"evaluations\[0\]\.V_forward_m_per_s: must be a speed > 0 m/s or null"),
    (OptimisationResult, ("x",), [1.0], r"x: shape \(1,\): axis 0 must have 2 entries"),
    (OptimisationResult, ("V_m_per_s",), 0.0, r"V_m_per_s = 0\.0 is invalid"),
    (OptimisationResult, ("cleared",), "yes", r"cleared: must be true or false"),
    (Records, ("records", 1, "computed"), None,
     r"records\[1\]\.rel_error: must be null exactly when computed is null"),
    (Records, ("records", 0, "reference"), "book", r"records\[0\]\.reference: = 'book' is invalid"),
    (Records, ("records", 2, "id"), "t9.5/whirl_flutter_speed", r"records\[2\]\.id: .* twice"),
])
def test_corrupted_entries_name_the_file_and_key(results, cls, where, value, match, tmp_path):
    path = tmp_path / "r.json"
    path.write_text(json.dumps(_replaced(results[cls].to_dict(), where, value)))
    with pytest.raises(InputError) as err:
        cls.load(path)
    text = str(err.value)
    assert "\n" not in text and text.startswith(f"{path}: "), text
    assert re.search(match, text), text


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 6), st.integers(1, 4), st.data())
def test_time_responses_round_trip(T, n, data):
    t = np.cumsum(data.draw(st.lists(st.floats(1e-3, 10.0), min_size=T, max_size=T)))
    x = np.array(data.draw(st.lists(st.lists(st.floats(-1e6, 1e6), min_size=n, max_size=n),
                                    min_size=T, max_size=T)))
    r = TimeResponse(t, x, tuple(f"s{i}" for i in range(n)))
    back = TimeResponse.from_dict(json.loads(r.to_json()))
    assert np.array_equal(back.t, r.t) and np.array_equal(back.x, r.x)
    assert back.labels == r.labels


def test_a_non_finite_number_is_refused_naming_its_key(results, tmp_path):
    r = results[TimeResponse]
    bad = TimeResponse(r.t, np.where(np.arange(r.x.size).reshape(r.x.shape) == 3, np.nan, r.x),
                       r.labels)
    path = tmp_path / "r.json"
    with pytest.raises(InputError, match=r"r\.json'?: x\[1\]\[1\] is not a finite number"):
        bad.save(path)
    assert not path.exists()


def test_the_old_names_are_aliases(results, tmp_path):
    """save_json, the module-level load and FORMAT keep working for users' scripts."""
    from propwhirl.analysis import load
    from propwhirl.analysis.stability import FORMAT, READABLE_VERSIONS
    from propwhirl.studies import boundary, clearance, sweeps

    assert FORMAT == "propwhirl.analysis/3" and READABLE_VERSIONS == (1, 2, 3)
    assert (clearance.FORMAT, boundary.FORMAT, sweeps.FORMAT) == (
        "propwhirl.clearance/2", "propwhirl.boundary/1", "propwhirl.critical-map/1")
    results[Clearance].save_json(tmp_path / "c.json")
    assert Clearance.load(tmp_path / "c.json") == results[Clearance]
    results[ModelAnalysis].save(tmp_path / "a.json")
    assert load(tmp_path / "a.json").events == results[ModelAnalysis].events


# ----------------------------------------------------------------------------- item 2
ANALYSIS = ("events.py", "stability.py", "pk.py", "participation.py", "sensitivity.py",
            "summary.py")


@pytest.mark.parametrize("name", ANALYSIS)
def test_no_function_level_imports_of_propwhirl(name):
    """The cycle stability ↔ files ↔ pk was broken by imports inside functions; without the
    cycle there are none (optional third-party imports, e.g. pandas, may stay there)."""
    tree = ast.parse((SRC / "analysis" / name).read_text())
    inner = [n.lineno for f in ast.walk(tree)
             if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))
             for n in ast.walk(f)
             if isinstance(n, ast.ImportFrom) and (n.module or "").startswith("propwhirl")]
    assert not inner, f"analysis/{name}: imports inside functions at lines {inner}"


def test_a_class_is_whole_in_one_module():
    """ModelAnalysis's file format is its own (no analysis/files.py holding half of it)."""
    assert not (SRC / "analysis" / "files.py").exists()
    assert "to_dict" in vars(ModelAnalysis) and "decode" in vars(ModelAnalysis)
    assert ModelAnalysis.decode.__module__ == ModelAnalysis.__module__


@pytest.mark.parametrize("module", ["propwhirl.analysis.pk", "propwhirl.analysis.events",
                                    "propwhirl.analysis.sensitivity", "propwhirl.results"])
def test_each_module_imports_first(module):
    """No import cycle: each module imports on its own, as the first import."""
    subprocess.run([sys.executable, "-c", f"import {module}"], check=True)
