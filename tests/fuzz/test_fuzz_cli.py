"""Fuzz: the command line with hostile numbers — exit code 0 or 2, and on 2 one line on stderr
starting ``propwhirl: error:``, never a traceback."""
from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, record
from propwhirl.app.cli import main

NUM = st.one_of(st.sampled_from(["0", "-1", "1e300", "nan", "inf", "1e-9", "abc", "350"]),
                st.floats(allow_nan=False, allow_infinity=False).map(repr))


PLAUSIBLE = st.tuples(st.floats(1.0, 300.0), st.floats(1.0, 400.0), st.floats(1.0, 100.0)).map(
    lambda t: (repr(t[0]), repr(t[0] + t[1]), repr(t[2])))


@FUZZ
@given(abc=st.one_of(st.tuples(NUM, NUM, NUM), PLAUSIBLE), cmd=st.sampled_from(["analyse", "campbell"]))
def test_cli_ranges(tmp_path_factory, base_text, capsys, abc, cmd):
    a, b, c = abc
    path = tmp_path_factory.mktemp("cli") / "m.toml"
    path.write_text(base_text)
    flag = "--speeds" if cmd == "analyse" else "--rpm"
    try:
        code = main([cmd, str(path), flag, a, b, c])
    except SystemExit as exc:                  # argparse's own usage errors
        code = exc.code
    err = capsys.readouterr().err
    assert code in (0, 2), (code, err)
    if code == 2:
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert len(lines) == 1 and lines[0].startswith("propwhirl: error:"), err
    record(f"cli: {cmd} {flag}", "exit 0" if code == 0 else "exit 2")
