"""V-g-f tables (read_vgf_csv) on corrupt files: header-only, truncated, non-numeric,
NaN-filled, unknown or missing columns — each an InputError naming the file and the line
(issue 9, item 6)."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from propwhirl import io
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.validate import InputError

HEADER = "V_m_per_s,mode,label,frequency_hz,damping_ratio,real_per_s,imag_per_s"


@pytest.fixture(scope="module")
def table_text(tmp_path_factory) -> str:
    a = analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 50.0))
    path = io.write_vgf_csv(a, tmp_path_factory.mktemp("vgf") / "vgf.csv")
    return path.read_text()


def refused(tmp_path: Path, text: str, match: str) -> str:
    path = tmp_path / "vgf.csv"
    path.write_text(text, newline="")
    with pytest.raises(InputError) as err:
        io.read_vgf_csv(path)
    msg = str(err.value)
    assert "\n" not in msg and str(path) in msg, msg
    assert re.search(match, msg.replace(str(path), "FILE")), msg
    return msg


def lines(text: str) -> list[str]:
    return text.splitlines(keepends=True)


def test_the_written_table_is_read(table_text, tmp_path):
    path = tmp_path / "vgf.csv"
    path.write_text(table_text, newline="")
    assert len(io.read_vgf_csv(path)["V"]) == len(lines(table_text)) - 2   # count, header


def test_header_only(table_text, tmp_path):
    """Issue 9.6: a header-only table (a SIGINT right after the header) was accepted."""
    refused(tmp_path, "".join(lines(table_text)[:2]),
            r"has a header but no rows \(its first line says \d+: truncated\?\)")
    refused(tmp_path, lines(table_text)[1], "has a header but no rows$")   # no count line


@pytest.mark.parametrize("text, match", [
    ("", "empty"),
    ("\n\n", "empty"),
    ("a,b\n1,2\n", "line 1: missing columns V_m_per_s, mode, .*; unknown columns 'a', 'b'"),
    (HEADER.replace(",imag_per_s", "") + "\n", "line 1: missing column imag_per_s"),
    (HEADER + ",extra\n", "line 1: unknown column 'extra'"),
    (HEADER.replace("mode,label", "label,mode") + "\n", "line 1: columns out of order"),
])
def test_wrong_header(tmp_path, text, match):
    refused(tmp_path, text, match)


def test_truncated_tables(table_text, tmp_path):
    """Issue 9.6: a table cut by SIGINT mid-write was accepted."""
    ls = lines(table_text)
    # cut inside a row: missing columns
    row = ls[5]
    refused(tmp_path, "".join(ls[:5]) + row[: row.index(",", row.index(",") + 1)],
            r"line 6 has 2 columns, need 7 \(truncated\?\)")
    # cut inside the last number: every column there, but no line break after it
    refused(tmp_path, "".join(ls[:5]) + row.rstrip("\r\n")[:-3],
            r"line 6 is incomplete: the file ends without a line break")
    # a number cut short and a line break (hand-edited): f no longer that of the eigenvalue
    cells = ls[5].rstrip("\r\n").split(",")
    cells[6] = cells[6][:6]
    refused(tmp_path, "".join(ls[:5]) + ",".join(cells) + "\r\n",
            r"line 6: column frequency_hz = .* does not match the eigenvalue")


@pytest.mark.parametrize("column, value, match", [
    (0, "nan", "line 3: column V_m_per_s = 'nan' is invalid: must be finite"),
    (3, "NaN", "line 3: column frequency_hz = 'NaN' is invalid: must be finite"),
    (5, "inf", "line 3: column real_per_s = 'inf' is invalid: must be finite"),
    (6, "-Infinity", "line 3: column imag_per_s = '-Infinity' is invalid: must be finite"),
    (0, "fast", "line 3: column V_m_per_s = 'fast' is not a number"),
    (1, "1.5", "line 3: column mode = '1.5' is not an integer"),
    (1, "-1", "line 3: column mode = -1 is invalid: must be >= 0"),
    (2, "", "line 3: column label is empty"),
    (4, "0.5", "line 3: column damping_ratio = 0.5 does not match the eigenvalue"),
])
def test_bad_cell(table_text, tmp_path, column, value, match):
    ls = lines(table_text)
    cells = ls[2].rstrip("\r\n").split(",")
    cells[column] = value
    ls[2] = ",".join(cells) + "\r\n"
    refused(tmp_path, "".join(ls), match)


def test_nan_filled_table(table_text, tmp_path):
    """Issue 9.6: a table of NaN was accepted."""
    ls = lines(table_text)
    rows = [",".join(c if i == 2 else "nan" for i, c in enumerate(line.split(","))) + "\r\n"
            for line in (x.rstrip("\r\n") for x in ls[2:])]
    refused(tmp_path, "".join(ls[:2] + rows), "line 3: column V_m_per_s = 'nan' is invalid")


def test_rows_out_of_order(table_text, tmp_path):
    ls = lines(table_text)
    ls[2], ls[3] = ls[3], ls[2]
    refused(tmp_path, "".join(ls), r"line \d+: \(V, mode\) = .* does not follow .*sorted by speed")
    ls = lines(table_text)
    refused(tmp_path, "".join(ls[:3] + [ls[2]] + ls[3:]), r"line 4: .* does not follow")


def test_binary_and_unreadable(tmp_path):
    path = tmp_path / "vgf.csv"
    path.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(InputError, match=r"vgf\.csv.*not UTF-8"):
        io.read_vgf_csv(path)
    with pytest.raises(InputError, match="cannot read"):
        io.read_vgf_csv(tmp_path)
