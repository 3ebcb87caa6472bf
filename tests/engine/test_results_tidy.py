"""Tidy access to a sweep (issue 11, item 5): pandas DataFrame and xarray Dataset."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller


@pytest.fixture(scope="module")
def a():
    return analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 10.0), vgf=True)


def test_dataframe_is_the_table(a):
    pytest.importorskip("pandas")
    df = a.to_dataframe()
    t = a.sweep.table()
    assert list(df.columns) == list(t)
    for key, col in t.items():
        assert list(df[key]) == list(col)
    assert df.attrs["units"]["V"] == "m/s" and df.attrs["model_name"] == a.model_name


def test_xarray_dims_speed_by_mode(a):
    pytest.importorskip("xarray")
    ds = a.to_xarray()
    sw = a.sweep
    assert ds["frequency_hz"].dims == ("V", "mode")
    assert ds.sizes == {"V": sw.V.size, "mode": sw.n_modes}
    assert ds["V"].attrs["units"] == "m/s" and ds["frequency_hz"].attrs["units"] == "Hz"
    assert ds["real"].attrs["units"] == "1/s"
    np.testing.assert_array_equal(ds["label"].values, sw.mode_labels)
    phys = sw.physical
    np.testing.assert_array_equal(ds["damping_ratio"].values[phys], sw.damping_ratio[phys])
    assert np.isnan(ds["damping_ratio"].values[~phys]).all()
    assert ds["physical"].values.tolist() == phys.tolist()
