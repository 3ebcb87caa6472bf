"""Fixtures shared by the command-line tests."""
import pytest

from propwhirl import io
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.model.systems import Installation, PropellerWing


@pytest.fixture(scope="module")
def small_file(tmp_path_factory):
    """A 5-element wingtip-propeller model file (fast to analyse)."""
    m = PropellerWing(baseline_wing(5), baseline_flight(), (Installation(baseline_propeller(), 5.7),),
                      name="small tip model")
    path = tmp_path_factory.mktemp("models") / "small.toml"
    io.save_model(m, path)
    return path


@pytest.fixture(scope="module")
def small_dlm_file(tmp_path_factory):
    """The 5-element wingtip-propeller model with doublet-lattice wing aerodynamics on 4 x 8
    panels at the fixed Mach 0.3: its analysis reads the 20 AICs of one table column (the
    Roger fit's reduced frequencies), a few seconds."""
    import dataclasses

    pytest.importorskip("panelaero")
    wing = dataclasses.replace(baseline_wing(5), aero="dlm", dlm_chordwise_panels=4,
                               dlm_spanwise_panels=8, dlm_mach=0.3)
    m = PropellerWing(wing, baseline_flight(), (Installation(baseline_propeller(), 5.7),),
                      name="small DLM tip model")
    path = tmp_path_factory.mktemp("models") / "small_dlm.toml"
    io.save_model(m, path)
    return path
