"""The partial-results file of --resume (issue 20, items 1, 2, 3, 5 and 10).

1. it held pickles, unpickled on --resume (code execution from a file a user can be handed):
   now plain JSON only, a file with a pickle is refused and nothing of it runs;
2. points were keyed by ``path=value`` only: another model, other speeds, method or convention
   resumed silently into a mix; now the file carries a fingerprint of everything that decides a
   point's result, and a mismatch is refused naming what differs;
3. corrupt files gave tracebacks and forged rows were taken: now one-line errors;
5, 10. a scheduler address of an unsupported scheme gave a traceback, an unreachable one took
   tens of seconds of retries: now one line, one connection attempt.
"""
from __future__ import annotations

import base64
import json
import pickle
import socket
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from propwhirl import io
from propwhirl.app import cli
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.studies import partial as X
from propwhirl.studies import sweeps
from propwhirl.studies.execution import Interrupted, map_analyses
from propwhirl.studies.partial import Checkpoint
from propwhirl.validate import InputError

SPEEDS = [100.0, 300.0, 500.0, 700.0]
VALUES = [4.0, 6.0, 8.0]


def model_a():
    return isolated_baseline_propeller()


def model_b():
    m = model_a()
    return replace(m, propeller=replace(m.propeller, damping_psi=0.05, name="damped"))


def study(model, path: Path, resume: bool = False, stop_after: int | None = None, **kw):
    """A 3-point sweep of propeller.f_psi, interrupted after `stop_after` points."""
    def progress(done, total):
        if stop_after is not None and done == stop_after:
            raise KeyboardInterrupt

    options = dict(speeds=SPEEDS, warm_start=False)    # one partial-results file (no passes)
    options.update(kw)
    return sweeps.sweep(model, "propeller.f_psi", VALUES, checkpoint=Checkpoint(path, resume=resume),
                        progress=progress, **options)


@pytest.fixture(scope="module")
def partial(tmp_path_factory) -> Path:
    """A partial-results file of model A's sweep holding one point (and its full result)."""
    path = tmp_path_factory.mktemp("partial") / "r.json.partial"
    with pytest.raises(Interrupted):
        study(model_a(), path, stop_after=1)
    return path


def one_line(exc: BaseException, *parts: str) -> str:
    msg = str(exc)
    assert "\n" not in msg and all(p in msg for p in parts), msg
    return msg


# ----------------------------------------------------------------------------- item 1
class Touch:
    """A pickle whose loading creates a file (the payload of a forged partial file)."""

    def __init__(self, marker: Path):
        self.marker = marker

    def __reduce__(self):
        return (Path.touch, (self.marker,))


def pickled(marker: Path) -> str:
    return base64.b64encode(pickle.dumps(Touch(marker))).decode("ascii")


@pytest.mark.parametrize("layout", ["version 1", "version 2"])
def test_a_forged_pickle_is_never_run(tmp_path, layout):
    """Item 1: a forged file beside the output ran arbitrary code on --resume (a pickle
    payload creating a file was unpickled); now refused, one line, the file not created."""
    marker, path = tmp_path / "pwned", tmp_path / "r.json.partial"
    point = {"index": 0, "key": "0", "pickle": pickled(marker)}
    if layout == "version 1":      # the layout main wrote: unpickled when fingerprints matched
        doc = {"format": "propwhirl partial results", "version": 1, "fingerprint": "",
               "total": 2, "done": 1, "points": [point]}
    else:
        doc = {"format": X.PARTIAL_FORMAT, "done": 1, "points": [point],
               "fingerprint": Checkpoint(path).full_fingerprint(2)}
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError) as info:
        map_analyses(lambda x: x, [1.0, 2.0], checkpoint=Checkpoint(path, resume=True))
    one_line(info.value, str(path), "pickle", "remove it or run without --resume")
    assert not marker.exists()


def test_a_forged_pickle_beside_a_cli_output_is_never_run(tmp_path, capsys):
    """Item 1 through the command line: `sweep ... --json r.json --resume` beside a forged
    r.json.partial (sweeps from the CLI carried an empty fingerprint)."""
    marker, out = tmp_path / "pwned", tmp_path / "r.json"
    keys = [f"propeller.f_psi={x!r}" for x in VALUES]
    doc = {"format": "propwhirl partial results", "version": 1, "fingerprint": "",
           "total": len(keys), "done": 1,
           "points": [{"index": 0, "key": keys[0], "pickle": pickled(marker)}]}
    Path(str(out) + ".partial").write_text(json.dumps(doc))
    code = cli.main(["sweep", "isolated-propeller", "--param", "propeller.f_psi", "4", "8", "3",
                     "--speeds", "100", "700", "200", "--json", str(out), "--resume", "--quiet",
                     "--no-warm-start"])
    err = capsys.readouterr().err
    assert code == 2 and "older propwhirl" in err and err.count("\n") == 1, err
    assert not marker.exists() and not out.exists()


def test_the_file_is_plain_json_with_the_fingerprint(partial):
    text = partial.read_text()
    assert "pickle" not in text
    doc = json.loads(text, parse_constant=lambda c: pytest.fail(f"{c} in the file"))
    assert doc["format"] == "propwhirl.partial/2" and doc["done"] == 1
    fp = doc["fingerprint"]
    assert fp["model"] == X.content_digest(model_a()) and fp["model"].startswith("sha256:")
    assert fp["axes"][0]["path"] == "propeller.f_psi" and fp["axes"][0]["values"] == VALUES
    assert (fp["method"], fp["xtol"], fp["static_divergence"], fp["low_speed"]) == \
        ("auto", sweeps.STUDY_XTOL, True, True)
    assert fp["speeds"] == X.content_digest([np.array(SPEEDS)] * 3)
    assert fp["points"] == "study row" and fp["total"] == 3 and fp["propwhirl"]
    row = doc["points"][0]["value"]
    assert set(row) == {"critical_speed", "critical_frequency", "critical_mode", "content", "kind",
                        "event", "whirl", "propeller", "propeller_share", "static_divergence_speed"}
    assert all(isinstance(x, (str, int, float)) or x is None for x in row.values())


def test_an_interrupted_sweep_resumes_to_the_same_map(partial, tmp_path):
    full = sweeps.sweep(model_a(), "propeller.f_psi", VALUES, speeds=SPEEDS, warm_start=False)
    path = tmp_path / "copy.partial"
    path.write_text(partial.read_text())
    resumed = study(model_a(), path, resume=True)
    assert resumed.to_dict() == full.to_dict()


# ----------------------------------------------------------------------------- item 2
def test_the_model_is_fingerprinted_by_its_content():
    a, b = model_a(), model_a()
    assert a is not b and X.content_digest(a) == X.content_digest(b)
    assert X.content_digest(model_b()) != X.content_digest(a)
    tiny = replace(a, propeller=replace(a.propeller, radius=np.nextafter(a.propeller.radius, 9.0)))
    assert X.content_digest(tiny) != X.content_digest(a)          # the last bit counts


@pytest.mark.parametrize("change, differs", [
    (dict(model=model_b), ["model (sha256 "]),
    (dict(speeds=[100.0, 400.0, 700.0]), ["speeds (sha256 "]),
    (dict(method="dense"), ["method ('auto' vs 'dense')"]),
    (dict(static_divergence=False, low_speed=False), ["static_divergence (True vs False)",
                                                      "low_speed (True vs False)"]),
    (dict(xtol=0.1), ["xtol (0.01 vs 0.1)"]),
])
def test_resuming_another_study_is_refused_naming_what_differs(partial, tmp_path, change, differs):
    """Item 2: another model, speeds, method, convention or tolerance resumed into a mix of
    two studies' points, silently; now refused, naming the entries that differ."""
    path = tmp_path / "copy.partial"
    path.write_text(partial.read_text())
    kw = dict(change)
    model = kw.pop("model", model_a)()
    with pytest.raises(InputError) as info:
        study(model, path, resume=True, **kw)
    one_line(info.value, str(path), "was written for another study", *differs,
             "remove it or run without --resume")


def test_the_passes_of_a_warm_started_map_are_fingerprinted(tmp_path):
    path = tmp_path / "m.json.partial"
    kw = dict(speeds=SPEEDS, warm_start=True)
    axes = [("propeller.f_psi", [4.0, 5.0, 6.0]), ("propeller.f_theta", [4.0, 5.0, 6.0])]
    with pytest.raises(Interrupted):
        sweeps.critical_map(model_a(), axes, checkpoint=Checkpoint(path), progress=_stop(2), **kw)
    coarse = tmp_path / "m.json.partial.coarse"
    assert json.loads(coarse.read_text())["fingerprint"]["pass"] == "coarse"
    with pytest.raises(InputError, match=r"was written for another study: model \(sha256"):
        sweeps.critical_map(model_b(), axes, checkpoint=Checkpoint(path, resume=True), **kw)


def _stop(k):
    def report(done, total):
        if done == k:
            raise KeyboardInterrupt
    return report


def test_a_parametric_study_fingerprints_every_variant(tmp_path):
    from propwhirl.cases.ch09_baseline import baseline_propeller
    from propwhirl.studies import runner

    path = tmp_path / "s.partial"

    def run(props, resume=False):
        return runner.propeller_study("yaw stiffness", "f_psi", "Hz", {"f_psi": [3.0, 5.0]}, props,
                                      models=("isolated",), speeds=SPEEDS,
                                      checkpoint=Checkpoint(path, resume=resume))

    base = baseline_propeller()
    run([replace(base, f_psi=f, K_psi=None) for f in (3.0, 5.0)])
    damped = replace(base, damping_psi=0.05)
    with pytest.raises(InputError, match=r"variants \(sha256"):
        run([replace(damped, f_psi=f, K_psi=None) for f in (3.0, 5.0)], resume=True)


def test_the_reproduction_keeps_plain_case_values(tmp_path):
    from propwhirl.reproduce import harness

    path = tmp_path / "r.partial"
    cp = Checkpoint(path).with_entries(harness.CASE_VALUES, study="reproduce", cases=["t7.2"])
    result = ["t7.2", {"t7.2/a": 1.25, "t7.2/b": float("nan"), "t7.2/c": 3}]
    cp.write(["t7.2"], {0: result})
    doc = json.loads(path.read_text())
    assert doc["points"][0]["value"] == {"prefix": "t7.2", "values": {"t7.2/a": 1.25, "t7.2/b": None,
                                                                      "t7.2/c": 3.0}}
    back = replace(cp, resume=True).load(["t7.2"])[0]
    assert back[0] == "t7.2" and back[1]["t7.2/a"] == 1.25 and np.isnan(back[1]["t7.2/b"])
    doc["points"][0]["value"]["values"]["t4.1/x"] = 2.0          # another case's id
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match=r"id 't4.1/x' is outside the case 't7.2'"):
        replace(cp, resume=True).load(["t7.2"])
    doc["points"][0]["value"] = {"prefix": "t4.1", "values": {}}  # another case in its place
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match=r"prefix = 't4.1' is not the case of this point"):
        replace(cp, resume=True).load(["t7.2"])


def test_resuming_another_model_on_the_command_line_exits_2(tmp_path, monkeypatch, capsys):
    """Item 2 as the issue reproduced it: sweep model A with --json r.json, interrupt, run
    model B with --json r.json --resume: exit 0, half the points A's; now exit 2, one line."""
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    io.save_model(model_a(), a)
    io.save_model(model_b(), b)
    out = tmp_path / "r.json"
    argv = ["--param", "propeller.f_psi", "4", "8", "3", "--speeds", "100", "700", "200",
            "--json", str(out), "--quiet", "--no-warm-start"]
    real, calls = sweeps.evaluate, []

    def interrupted_at_the_second(task):
        calls.append(task)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(task)

    monkeypatch.setattr(sweeps, "evaluate", interrupted_at_the_second)
    assert cli.main(["sweep", str(a), *argv]) == 130
    monkeypatch.setattr(sweeps, "evaluate", real)
    capsys.readouterr()
    partial = Path(str(out) + ".partial")
    assert json.loads(partial.read_text())["done"] == 1
    assert cli.main(["sweep", str(b), *argv, "--resume"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "was written for another study: model (sha256" in err, err
    assert not out.exists()
    for option in (["--method", "dense"], ["--thesis-convention"], ["--speeds", "100", "700", "300"]):
        assert cli.main(["sweep", str(a), *argv, "--resume", *option]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "was written for another study" in err, err
    assert cli.main(["sweep", str(a), *argv, "--resume"]) == 0        # the same study resumes
    assert out.exists() and not partial.exists()


# ----------------------------------------------------------------------------- item 3
def _mutated(partial: Path, tmp_path: Path, mutate) -> Path:
    doc = json.loads(partial.read_text())
    mutate(doc)
    path = tmp_path / "bad.partial"
    path.write_text(doc if isinstance(doc, str) else json.dumps(doc))
    return path


def _set(keys, value):
    def mutate(doc):
        d = doc
        for k in keys[:-1]:
            d = d[k]
        d[keys[-1]] = value
    return mutate


def _delete(keys):
    def mutate(doc):
        d = doc
        for k in keys[:-1]:
            d = d[k]
        del d[keys[-1]]
    return mutate


@pytest.mark.parametrize("mutate, says", [
    (_set(["points", 0, "value", "critical_speed"], "hello"), "critical_speed: must be a finite number"),
    (_set(["points", 0, "value"], "hello"), "must be an object"),
    (_delete(["points", 0, "value", "kind"]), "missing key 'kind'"),
    (_delete(["points", 0, "key"]), "missing"),
    (_delete(["fingerprint"]), "missing keys ['fingerprint']"),
    (_set(["points"], 5), "points: must be a list"),
    (_set(["done"], "1"), "done = '1' is invalid"),
    (_set(["points", 0, "index"], 7), "index = 7 is invalid"),
    (_set(["points", 0, "index"], True), "index = True is invalid"),
    (_set(["points", 0, "value", "propeller"], 2.5), "propeller: must be an integer"),
    (_set(["points", 0, "value", "extra"], 1), "unknown key 'extra'"),
    # forged rows, each entry of the right type: accepted silently before
    (_set(["points", 0, "value", "kind"], "banana"), "kind: = 'banana' is invalid"),
    (_set(["points", 0, "value", "critical_speed"], -5.0), "critical_speed = -5.0 is invalid"),
    (_set(["points", 0, "value", "critical_speed"], None), "does not match its critical speed"),
    (_set(["points", 0, "value", "propeller_share"], 3.0), "propeller_share = 3.0 is invalid"),
    (_set(["fingerprint", "speeds"], [1, "x"]), "speeds ([1, 'x'] vs sha256"),
    (_set(["fingerprint", "model"], "sha256:" + "0" * 64), "model (sha256 000000000000… vs"),
    (_set(["format"], "propwhirl partial results"), "older propwhirl"),
    (_set(["format"], "propwhirl.partial/3"), "not a propwhirl partial results file"),
])
def test_a_corrupt_or_forged_file_is_one_line(partial, tmp_path, mutate, says):
    """Item 3: a point value "hello", missing keys, ``points: 5``, a non-number speed gave
    tracebacks, a forged row was accepted; now one line naming the file, the entry and what to
    do."""
    path = _mutated(partial, tmp_path, mutate)
    with pytest.raises(InputError) as info:
        study(model_a(), path, resume=True)
    one_line(info.value, str(path), says, "remove it or run without --resume")


@pytest.mark.parametrize("text, says", [
    ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
    ('{"a": ' * 100_000 + "1" + "}" * 100_000, "nested too deeply"),
    ("[" * 50 + "]" * 50, "nested too deeply"),
    ('{"format": "propwhirl.partial/2", "points": [' + "9" * 5000 + "]}", "not a partial results file"),
    ('{"points": [', "is not valid JSON"),
    ("\xff", "not UTF-8"),
    ("null", "it is null"),
])
def test_malformed_json_is_one_line(tmp_path, text, says):
    path = tmp_path / "bad.partial"
    path.write_bytes(text.encode("utf-8", "surrogateescape") if text != "\xff" else b"\xff")
    with pytest.raises(InputError) as info:
        study(model_a(), path, resume=True)
    one_line(info.value, str(path), says)


def test_an_oversized_file_is_refused_before_reading(tmp_path, monkeypatch):
    path = tmp_path / "big.partial"
    path.write_text("[" + " " * 2000 + "]")
    monkeypatch.setattr(X, "MAX_PARTIAL_BYTES", 1000)
    with pytest.raises(InputError, match=r"has 2002 bytes, more than a partial results file holds"):
        study(model_a(), path, resume=True)


# ----------------------------------------------------------------------------- items 5, 10
@pytest.mark.parametrize("address, says", [
    ("ucx://host:1", "the scheme 'ucx' is not supported"),
    ("ws://host:8786", "the scheme 'ws' is not supported"),
    ("inproc://nowhere/1/2", "no scheduler of this process listens there"),
    ("tls://127.0.0.1:1", "tls:// needs the certificates"),
    ("garbage", "must be an address such as"),
    ("tcp://host:99999", "a port in [1, 65535]"),
    ("tcp://:8786", "a host and a port"),
])
def test_an_unsupported_scheduler_address_is_one_line(address, says):
    """Item 5: ucx:// and tls:// gave tracebacks from inside dask."""
    pytest.importorskip("distributed")
    with pytest.raises(InputError) as info:
        map_analyses(abs, [1.0], client=address)
    one_line(info.value, repr(address), says)


def _unused_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_an_unreachable_scheduler_fails_after_one_attempt(monkeypatch):
    """Item 10: a refused address was retried by dask for its whole connect timeout (10 s,
    ~24 s through the CLI); now one connection attempt, and the message names the address."""
    pytest.importorskip("distributed")
    port = _unused_port()
    attempts = []
    real = socket.socket.connect, socket.socket.connect_ex

    def connect(self, address, _real=real[0]):
        if isinstance(address, tuple) and address[1] == port:
            attempts.append(address)
        return _real(self, address)

    def connect_ex(self, address, _real=real[1]):
        if isinstance(address, tuple) and address[1] == port:
            attempts.append(address)
        return _real(self, address)

    monkeypatch.setattr(socket.socket, "connect", connect)
    monkeypatch.setattr(socket.socket, "connect_ex", connect_ex)
    with pytest.raises(InputError) as info:
        map_analyses(abs, [1.0], client=f"tcp://127.0.0.1:{port}")
    one_line(info.value, f"tcp://127.0.0.1:{port}", "cannot connect")
    assert len(attempts) == 1, attempts


@pytest.mark.parametrize("address", ["ucx://host:1", "tls://host:8786", "tcp://host", "x://y:1"])
def test_a_bad_scheduler_on_the_command_line_is_one_line_before_any_work(address, monkeypatch,
                                                                          capsys):
    """Item 5 through the CLI: `--scheduler ucx://host:1` gave a traceback; now exit 2, one
    line, checked before a variant is built."""
    pytest.importorskip("distributed")
    from propwhirl.studies import paths

    def fail(*args, **kwargs):
        raise AssertionError("worked before checking the scheduler address")

    monkeypatch.setattr(paths, "set_values", fail)
    assert cli.main(["sweep", "isolated-propeller", "--param", "propeller.f_psi", "4", "8", "3",
                     "--scheduler", address, "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"scheduler = {address!r}" in err and "Traceback" not in err, err
