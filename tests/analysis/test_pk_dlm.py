"""The p-k method on doublet-lattice aerodynamics (issue 23, stages 3-4): a wing with
aero = "dlm" is analysed by p-k (method "pk"; "auto" is its Roger state space,
tests/analysis/test_dlm_rfa_analysis.py) with the same events, names,
participation and summary as the strip p-k, its strip twin's finite-state events beside them."""
import dataclasses

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.analysis.pk import DLM_NOTE, pk_sweep  # noqa: E402
from propwhirl.analysis.stability import ModelAnalysis  # noqa: E402
from propwhirl.cases.ch07_patil import patil_model  # noqa: E402
from propwhirl.model.aerodynamics import dlm  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

SPEEDS = np.arange(20.0, 42.0, 4.0)


def patil_dlm(nc=4, ns=32):
    m = patil_model(10)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=nc,
                                            dlm_spanwise_panels=ns))


@pytest.fixture(scope="module")
def analysed():
    return analyse(patil_dlm(), speeds=SPEEDS, method="pk")


def test_dlm_analysis_is_a_pk_analysis_with_the_strips_beside(analysed):
    a = analysed
    assert a.doublet_lattice and a.finite_state is not None
    flutter = [e for e in a.events if e.kind == "flutter" and e.event == "onset"]
    assert len(flutter) == 1 and flutter[0].label == "wing 3"
    strip = analyse(patil_model(10), speeds=SPEEDS, method="pk")
    s = [e for e in strip.events if e.kind == "flutter" and e.event == "onset"][0]
    # A = 32: the panels' flutter speed within 15 % of the strips' (3-D pitch damping lower)
    assert abs(flutter[0].V / s.V - 1) < 0.15
    text = a.summary()
    assert "(p-k method, doublet-lattice wing aerodynamics)" in text.splitlines()[0]
    assert "exact (p-k, doublet-lattice panels) vs finite-state (Leishman-Nguyen)" in text
    assert a.warnings[0].startswith(DLM_NOTE)
    assert "4 chordwise x 32 spanwise" in a.warnings[0]
    assert "exact (p-k, Theodorsen's C(k))" in strip.summary()


def test_saved_dlm_analysis_keeps_its_aerodynamics(analysed, tmp_path):
    back = ModelAnalysis.load(analysed.save(tmp_path / "a.json"))
    assert back.doublet_lattice
    assert back.summary() == analysed.summary()


def test_dlm_refused_where_it_has_no_block_form():
    m = patil_dlm()
    # 'reduced' is the default's modal Roger state space (issue 37), not the strips' blocks
    assert analyse(m, speeds=SPEEDS, method="reduced").events == analyse(m, speeds=SPEEDS).events
    with pytest.raises(InputError, match="wing aero = 'dlm' has no local \\(block\\) form"):
        m.second_order_blocks(np.array([10.0]))


def test_supersonic_speeds_refused_before_any_panel_work():
    m = patil_dlm(3, 17)                                   # a geometry no other test builds
    tables = dlm.DlmTables()
    top = 0.95 * m.flight.speed_of_sound
    with pytest.raises(InputError, match=r"Mach = 0.95 \(V = .* m/s\) is invalid for aero = 'dlm'"):
        pk_sweep(m, [10.0, 20.0, top], tables=tables)
    assert m.wing not in tables and len(tables) == 0     # no panels, no AIC built


def test_missing_panelaero_is_said_before_any_work(monkeypatch):
    import builtins
    real = builtins.__import__

    def no_panelaero(name, *args, **kw):
        if name.split(".")[0] == "panelaero":
            raise ImportError("blocked")
        return real(name, *args, **kw)

    monkeypatch.setattr(builtins, "__import__", no_panelaero)
    with pytest.raises(InputError, match=r"aero = 'dlm' needs PanelAero: pip install"):
        analyse(patil_dlm(), speeds=SPEEDS)
