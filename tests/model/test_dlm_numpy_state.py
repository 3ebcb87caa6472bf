"""PanelAero leaves numpy's floating-point error state alone (issue 33, item 8): importing
panelaero.DLM calls ``np.seterr(all='ignore')``; every call into PanelAero, its import
included, restores the caller's state.  Each case runs in a fresh interpreter: the import's
side effect happens once per process."""
import json
import subprocess
import sys

import pytest

pytest.importorskip("panelaero")

SCRIPT = r"""
import json, warnings
import numpy as np
np.seterr(**json.loads(STATE))
before = np.geterr()
from propwhirl.model.aerodynamics import dlm
from propwhirl.model.structure.wing import Wing
dlm.require_panelaero()                               # the import alone
after_import = np.geterr()
w = Wing(semi_span=2.0, mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25,
         n_elements=4, aero="dlm", dlm_chordwise_panels=2, dlm_spanwise_panels=3)
dlm.DlmAerodynamics(w).aic(0.3, 0.4)                  # a doublet-lattice evaluation
after_call = np.geterr()
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    np.float64(1.0) / np.float64(0.0)                 # the user's own division by zero
print(json.dumps({"before": before, "after_import": after_import, "after_call": after_call,
                  "warned": [str(c.message) for c in caught]}))
"""


def run(state: dict) -> dict:
    out = subprocess.run([sys.executable, "-c", SCRIPT.replace("STATE", repr(json.dumps(state)))],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("state", [
    {"divide": "warn", "over": "warn", "under": "ignore", "invalid": "warn"},   # numpy's default
    {"divide": "warn", "over": "raise", "under": "print", "invalid": "warn"},
])
def test_error_state_is_the_callers_after_import_and_evaluation(state):
    got = run(state)
    assert got["before"] == state
    assert got["after_import"] == state
    assert got["after_call"] == state
    assert any("divide by zero" in w for w in got["warned"])      # the user's NaNs/infs speak
