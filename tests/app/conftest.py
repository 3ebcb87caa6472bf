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
