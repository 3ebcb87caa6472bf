"""A traced boundary and a clearance result are saved and read back (JSON): the same result,
a non-finite number as NaN, errors naming the file for what is not such a file."""
import json

import numpy as np
import pytest

from propwhirl.cases.registry import case_model
from propwhirl.studies.boundary import Boundary, neutral_curve
from propwhirl.studies.clearance import Clearance, clearance
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def isolated():
    return case_model("isolated-propeller")


def test_boundary_round_trip(isolated, tmp_path):
    b = neutral_curve(isolated, ("propeller.f_theta", "propeller.f_psi"), (3.0, 3.0),
                      (12.0, 12.0), 220.0)
    assert b.curves
    path = tmp_path / "boundary.json"
    b.save_json(path)
    r = Boundary.load(path)
    assert r.to_dict() == b.to_dict()
    assert all(np.array_equal(x, y) for x, y in zip(r.curves, b.curves))
    assert r.format() == b.format()


def test_clearance_round_trip(isolated, tmp_path):
    c = clearance(isolated, 130.0, speeds=np.arange(10.0, 351.0, 20.0), n_scan=4)
    path = tmp_path / "clearance.json"
    c.save_json(path)
    r = Clearance.load(path)
    assert r.to_dict() == c.to_dict()
    assert r.format() == c.format() and r.cleared == c.cleared
    assert r.critical is None or isinstance(r.critical.V, float)


def test_a_non_finite_number_is_read_back_as_nan(isolated, tmp_path):
    c = clearance(isolated, 130.0, speeds=np.arange(10.0, 351.0, 20.0), n_scan=4)
    d = c.to_dict()
    d["minimum_frequencies"][0]["critical_speed"] = None
    r = Clearance.from_dict(d)
    assert np.isnan(r.minimum[0].critical_speed)


@pytest.mark.parametrize("cls, what", [(Boundary, "boundary"), (Clearance, "clearance")])
def test_not_such_a_file_is_one_line(cls, what, tmp_path):
    p = tmp_path / "x.json"
    p.write_text(json.dumps({"format": "something else"}))
    with pytest.raises(InputError, match=rf"x.json: not a {what} file"):
        cls.load(p)
    p.write_text("{")
    with pytest.raises(InputError, match="x.json: not valid JSON"):
        cls.load(p)
    from propwhirl.studies import boundary, clearance as cl
    fmt = (boundary if cls is Boundary else cl).FORMAT
    p.write_text(json.dumps({"format": fmt}))
    with pytest.raises(InputError, match=r"x.json: missing keys '"):
        cls.load(p)
