"""Fuzz: doublet-lattice panel counts against the memory limit (issue 33, item 7).  Any counts
within dlm_mesh's bounds and any PROPWHIRL_MEMORY_LIMIT: the panels pass when one AIC fits
the limit, else a one-line InputError whose every suggested count fits and whose "at most"
is the largest count that does."""
from __future__ import annotations

import re

from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from propwhirl import limits
from propwhirl.model.aerodynamics.dlm_mesh import MAX_PANELS


@FUZZ
@given(n_chord=st.integers(1, MAX_PANELS), n_span=st.integers(1, MAX_PANELS),
       limit=st.integers(limits.MiB, 16 * limits.GiB))
def test_fuzz_panel_counts_against_the_memory_limit(monkeypatch, n_chord, n_span, limit):
    n_span = max(1, min(n_span, MAX_PANELS // n_chord))
    monkeypatch.setenv(limits.MEMORY_ENV, str(limit))
    refused = None
    with held_to_the_rule("dlm panels", source="dlm_chordwise_panels x dlm_spanwise_panels"):
        try:
            limits.check_panels(n_chord, n_span)
        except Exception as exc:
            refused = exc
            raise
    if refused is None:
        assert limits.aic_bytes(n_chord * n_span) <= limit
        return
    msg = str(refused)
    assert limits.aic_bytes(n_chord * n_span) > limit
    most = int(re.search(r"at most ([0-9,]+) panels fit", msg).group(1).replace(",", ""))
    assert limits.aic_bytes(most) <= limit < limits.aic_bytes(most + 1)
    for a, b in re.findall(r"([0-9,]+) x ([0-9,]+)", msg.split("fit")[1]):
        a, b = int(a.replace(",", "")), int(b.replace(",", ""))
        assert a * b <= most and (a == n_chord or b == n_span)
        limits.check_panels(a, b)
