"""Fuzz (issue 33): the texts propwhirl writes into CSV tables (item 5: any case name, mode
label or message — no cell a spreadsheet evaluates, every text read back exactly), the
scheduler addresses and whatever a server answers on connecting (item 6: one InputError line,
never a MemoryError or a hang), and campaigns of any shape (item 11: every task's model that
of building it the old way)."""
from __future__ import annotations

import csv
import io
import re
import socket
import threading
import tomllib

import numpy as np
import pytest
import tomli_w
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, ROOT, held_to_the_rule
from propwhirl import fileio

FORMULA = re.compile(r"[=+\-@\t\r]")
NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
TEXT = st.one_of(st.text(max_size=16), st.sampled_from(
    ["=1+1", "-1+1", "+1", "@SUM(A1)", "\t=x", "\r=x", "'=x", "-1.5", "=HYPERLINK(\"a\")"]).flatmap(
    lambda s: st.builds(lambda pre, post: pre + s + post, st.text(max_size=2),
                        st.text(max_size=2))))


def _evaluated(cell: str) -> bool:
    return bool(FORMULA.match(cell)) and NUMBER.fullmatch(cell) is None


@FUZZ
@given(name=TEXT.filter(lambda s: s.strip() and s.isprintable()), mode=TEXT, error=TEXT)
def test_campaign_csv_cells(name, mode, error):
    from propwhirl.studies.campaign_result import CampaignResult, PointRow

    row = PointRow(name, name, 0.0, "EAS", 100.0, 100.0, False, 115.0, False, error, 101.5,
                   -13.5, -11.7, "flutter", "onset", mode, 7.0, "", (), 351.0, -0.01, 100.0,
                   mode, -0.01, mode, -0.02, -1.5e-4, mode, error)
    with held_to_the_rule("csv: campaign cells"):
        text = CampaignResult(name, mode, "cs25", 1.15, None, "propwhirl", (row,), 1).to_csv()
        table = list(csv.reader(io.StringIO(text, newline="")))
        assert len(table) == 2 and not [c for r in table for c in r if _evaluated(c)]
        head = table[0]
        assert fileio.csv_text(table[1][head.index("case")]) == name
        assert fileio.csv_text(table[1][head.index("error")]) == error
        assert table[1][head.index("margin_m_per_s")] == "-13.5"


@FUZZ
@given(labels=st.lists(TEXT, min_size=2, max_size=2))
def test_critical_map_text_round_trip(labels):
    from propwhirl.studies.sweeps import RESULT_UNITS, Axis, CriticalMap

    cols = {k: np.zeros(2) for k in RESULT_UNITS}
    cols.update(propeller=np.zeros(2, int), critical_speed=np.array([-1.5, 120.0]),
                kind=np.array(["flutter", "error"], dtype=object),
                critical_mode=np.array(labels, dtype=object),
                error=np.array(["", labels[1]], dtype=object))
    m = CriticalMap("m", (Axis("wing.EI*", np.array([0.5, 1.0]), ""),), cols)
    with held_to_the_rule("csv: critical map"):
        text = m.to_csv()
        assert not [c for r in csv.reader(io.StringIO(text.partition("\n")[2], newline=""))
                    for c in r if _evaluated(c)]
        back = CriticalMap.from_csv(text)
        assert list(back.columns["critical_mode"]) == labels
        assert list(back.critical_speed) == [-1.5, 120.0]


@FUZZ
@given(address=st.one_of(st.text(max_size=30), st.builds(
    lambda scheme, host, port: f"{scheme}{host}:{port}",
    st.sampled_from(["", "tcp://", "TCP://", "tls://", "ucx://", "inproc://", "x://"]),
    st.sampled_from(["127.0.0.1", "[::1]", "host", "", "a b", "h/x"]),
    st.one_of(st.integers(-5, 70000).map(str), st.text(max_size=5)))))
def test_scheduler_addresses(address):
    """Any text as --scheduler: accepted only as [tcp|tls|inproc://]host:port with an ASCII
    port in [1, 65535] (nothing is connected here), else one InputError line."""
    from propwhirl.studies.execution import check_scheduler

    with held_to_the_rule("scheduler: address"):
        check_scheduler(address)
        if re.fullmatch(r"inproc://.+", address.strip(), flags=re.I):
            return                                   # a scheduler of this process, by name
        m = re.fullmatch(r"(?:(tcp|tls)://)?(.+):([0-9]{1,5})", address.strip(), flags=re.I)
        assert m is not None and 1 <= int(m.group(3)) <= 65535, address
        assert m.group(1) is None or m.group(1).lower() != "tls"   # no certificates set


@pytest.fixture(scope="module")
def answering():
    """A throwaway server on a thread: each connection gets the bytes of ``reply[0]``, then
    is closed; yields (address, reply)."""
    reply = [b""]
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(0.1)
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = listener.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            with conn:
                try:
                    conn.sendall(reply[0])
                except OSError:
                    pass

    t = threading.Thread(target=serve, daemon=True)
    t.start()
    yield f"tcp://127.0.0.1:{listener.getsockname()[1]}", reply
    stop.set()
    t.join()
    listener.close()


@FUZZ
@given(data=st.binary(max_size=64), length=st.one_of(st.none(), st.integers(0, 2**64 - 1)))
def test_whatever_a_server_answers(answering, data, length):
    """Any answer (raw bytes, or a Dask-like length prefix then bytes) from a server that then
    closes: one InputError line naming the address, never a MemoryError."""
    from propwhirl.studies.execution import connect

    address, reply = answering
    reply[0] = (b"" if length is None else length.to_bytes(8, "little")) + data
    with held_to_the_rule("scheduler: server answers", address):
        connect(address, timeout=2.0)
        raise AssertionError(f"connected to a server answering {reply[0]!r}")


EXAMPLE = ROOT / "examples" / "wingtip_campaign.toml"
CASE = st.fixed_dictionaries({}, optional={
    "mount_stiffness": st.floats(0.2, 3.0), "mount_damping": st.floats(0.0, 2.0),
    "wing_damping": st.floats(0.0, 2.0), "reverse_rotation": st.booleans(),
    "failure": st.booleans(), "state": st.sampled_from(["stopped", "operating"]),
    "added_masses": st.lists(st.fixed_dictionaries({"mass_kg": st.floats(0.1, 50.0),
                                                    "x_m": st.floats(-1.0, 0.5)}), max_size=1),
    "values": st.dictionaries(st.sampled_from(["wing.EI*", "wing.GJ*", "flight.speed_range[2]",
                                               "propellers[0].propeller.f_psi"]),
                              st.floats(1.0, 12.0), max_size=1)})


@FUZZ
@given(cases=st.lists(st.tuples(st.sampled_from(["a", "b", "c"]), CASE), min_size=1,
                      max_size=5),
       altitudes=st.lists(st.floats(0.0, 9000.0), min_size=1, max_size=3, unique=True),
       combine=st.sampled_from(["list", "product"]))
def test_campaign_tasks_are_those_of_building_every_model(cases, altitudes, combine):
    """Campaigns of any shape: each task's model and speed grid those of the case applied to
    the model at the altitude (the old way), or the task's own one-line error."""
    from propwhirl.io.campaign_files import loads
    from propwhirl.studies import campaign as C
    from propwhirl.studies.clearance import clearance_speeds
    from propwhirl.studies.partial import content_digest

    doc = tomllib.loads(EXAMPLE.read_text())
    doc["combine"] = combine
    doc["envelope"]["altitudes_m"] = altitudes
    doc["cases"] = [{"name": f"case {i}", "group": g, **c} for i, (g, c) in enumerate(cases)]
    camp = None
    with held_to_the_rule("campaign: any shape", "fuzz.toml"):
        camp = C.from_spec(loads(tomli_w.dumps(doc), "fuzz.toml", EXAMPLE.parent))
    if camp is None:
        return
    todo, keys = C.tasks(camp)
    it = iter(todo)
    for case in camp.cases:
        for p in camp.points:
            t = next(it)
            with held_to_the_rule("campaign: a task's model"):
                old = C.at_altitude(case.apply(camp.model), p.altitude_m)
                model, speeds = t.build()
                assert content_digest(model) == content_digest(old)
                assert list(speeds) == list(clearance_speeds(old, t.V_required))
