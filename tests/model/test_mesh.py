"""The mesh rule (model/structure/mesh.py): nodes at 0, the semi-span and every station; each interval
divided evenly under the element length; the uniform n_elements mesh without stations."""
import numpy as np
import pytest

from propwhirl import limits
from propwhirl.model.structure import mesh
from propwhirl.validate import InputError


@pytest.mark.parametrize("L, n", [(5.7, 25), (4.8, 20), (16.0, 20), (4.8, 96), (0.37, 3), (1.0, 1)])
def test_without_stations_the_mesh_is_linspace_bit_for_bit(L, n):
    m = mesh.build(L, n)
    assert np.array_equal(m.node_y, np.linspace(0.0, L, n + 1))
    assert m.n_elements == n and m.breakpoints == (0.0, L)


def test_stations_are_nodes_and_no_element_exceeds_the_maximum():
    stations = (0.95, 1.5, 2.05, 3.1)
    m = mesh.build(4.8, 20, stations, max_element_length=0.2)
    for y in stations:
        assert np.min(np.abs(m.node_y - y)) == 0.0
    assert m.element_length.max() <= 0.2 * (1 + 1e-12)
    # each interval holds the fewest equal elements not longer than 0.2 m
    edges = (0.0,) + stations + (4.8,)
    counts = [int(np.sum((m.element_y > a) & (m.element_y < b))) for a, b in zip(edges, edges[1:])]
    assert counts == [5, 3, 3, 6, 9]  # ceil(0.95/0.2), ceil(0.55/0.2), ..., ceil(1.7/0.2)
    for (a, b), k in zip(zip(edges, edges[1:]), counts):
        inside = m.element_length[(m.element_y > a) & (m.element_y < b)]
        np.testing.assert_allclose(inside, (b - a) / k, rtol=1e-12)


def test_a_target_count_sets_the_length_semi_span_over_n():
    m = mesh.build(4.8, 24, (1.0,))  # h = 0.2: [0, 1] in 5, [1, 4.8] in 19
    assert m.n_elements == 24
    m = mesh.build(4.8, 24, (0.95,))  # [0, 0.95] in 5, [0.95, 4.8] in ceil(19.25) = 20
    assert m.n_elements == 25 and m.element_length.max() <= 0.2


def test_a_station_at_the_tip_is_the_tip():
    assert np.array_equal(mesh.build(4.8, 24, (4.8,)).node_y, mesh.build(4.8, 24).node_y)


def test_an_interval_that_holds_k_elements_exactly_is_not_split_further():
    assert 2.1 / 0.3 > 7  # 7.000000000000001 in floating point: ceil would give 8
    m = mesh.build(3.0, 10, (2.1,), max_element_length=0.3)
    assert m.n_elements == 10


@pytest.mark.parametrize("stations, words", [
    ((5.0,), "stations[0] = 5.0 m is outside the wing: must be in (0, 4.8] m"),
    ((1.0, -0.5), "stations[1] = -0.5 m is outside the wing"),
    ((0.0,), "stations[0] = 0.0 m is the clamped root: must be > 0"),
    ((1.0, 2.0, 1.0), "stations[2] = 1.0 m is invalid: a duplicate of stations[0] = 1 m"),
    ((2.0, 2.001), "stations[1] = 2.001 m is invalid: it makes an element of 0.001 m between "
                   "y = 2 and 2.001 m, shorter than the minimum 0.0048 m"),
    ((4.799,), "stations[0] = 4.799 m is invalid: it makes an element of 0.001 m"),
    ((0.002,), "stations[0] = 0.002 m is invalid: it makes an element of 0.002 m"),
])
def test_bad_stations_are_one_line_errors_naming_the_station(stations, words):
    with pytest.raises(InputError) as exc:
        mesh.build(4.8, 20, stations)
    assert words in str(exc.value) and "\n" not in str(exc.value)


def test_the_shortest_element_allowed_is_a_thousandth_of_the_semi_span():
    mesh.build(4.8, 20, (2.0, 2.0 + 1.001e-3 * 4.8))  # just above the minimum: accepted
    with pytest.raises(InputError, match="shorter than the minimum"):
        mesh.build(4.8, 20, (2.0, 2.0 + 0.999e-3 * 4.8))


@pytest.mark.parametrize("h", [0.0, -0.2])
def test_a_non_positive_maximum_length_is_refused(h):
    with pytest.raises(InputError, match="max_element_length"):
        mesh.build(4.8, 20, (), h)


def test_too_many_elements_is_refused_with_the_count():
    with pytest.raises(InputError) as exc:
        mesh.build(4.8, 20, (), 0.01)
    assert "max_element_length = 0.01 m gives 480 elements" in str(exc.value)
    assert f"at most {limits.MAX_ELEMENTS}" in str(exc.value)


def test_node_positions_are_read_only():
    m = mesh.build(4.8, 4)
    with pytest.raises(ValueError):
        m.node_y[1] = 0.0


def test_beam_interpolation_is_the_beam_elements_shape_functions():
    """mesh.beam_interpolation, the one interpolation of the DLM spline and the modal strips,
    is the derivation's own element (Hermite bending 7.5–7.6, linear torsion 7.7–7.8) at
    random points, the nodes and both ends of a non-uniform mesh: each point weighs the two
    nodes of its element, a node the element starting there."""
    sp = pytest.importorskip("sympy")
    from derivations.beam_element import l_e, shape_functions, xi

    N, Tsh = shape_functions()
    ys = mesh.build(6.0, 5, (1.3, 4.0)).node_y
    rng = np.random.default_rng(7)
    y = np.concatenate([rng.uniform(0.0, 6.0, 8), ys])
    H, P, T = mesh.beam_interpolation(ys, y)
    assert H.shape == P.shape == T.shape == (y.size, ys.size)
    for i, yi in enumerate(y):
        e = min(int(np.searchsorted(ys, yi, side="right")) - 1, ys.size - 2)
        le = ys[e + 1] - ys[e]
        at = {xi: 2 * (yi - ys[e]) / le - 1, l_e: le}
        n = [float(sp.N(f.subs(at))) for f in N]          # h1, φ1, h2, φ2
        t = [float(sp.N(f.subs(at))) for f in Tsh]        # α1, α2
        want_H, want_P, want_T = (np.zeros(ys.size) for _ in range(3))
        want_H[[e, e + 1]], want_P[[e, e + 1]], want_T[[e, e + 1]] = n[0::2], n[1::2], t
        np.testing.assert_allclose(H[i], want_H, atol=1e-14)
        np.testing.assert_allclose(P[i], want_P, atol=1e-14)
        np.testing.assert_allclose(T[i], want_T, atol=1e-14)
