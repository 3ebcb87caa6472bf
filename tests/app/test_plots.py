"""Plots: what is drawn is the analysis's data; PNGs are written; matplotlib stays optional."""
from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest
from matplotlib.colors import to_rgba

from propwhirl.app import plots
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.engine import time_response
from propwhirl.analysis.stability import ModelAnalysis, analyse
from propwhirl.cases.ch09_baseline import (
    baseline_flight,
    baseline_propeller,
    baseline_wing,
    isolated_baseline_propeller,
)
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.validate import InputError
from propwhirl.analysis.vibration import campbell

PNG = b"\x89PNG\r\n\x1a\n"


def small_tip_model() -> PropellerWing:
    """Baseline wing with 5 elements and the baseline propeller at the tip (fast; has a
    divergence and forward/backward whirl flutter in 1–350 m/s)."""
    return PropellerWing(baseline_wing(5), baseline_flight(),
                         (Installation(baseline_propeller(), 5.7),), name="small tip model")


@pytest.fixture(scope="module")
def model():
    return small_tip_model()


@pytest.fixture(scope="module")
def analysis(model):
    return analyse(model)


def _lines_by_label(ax):
    return {ln.get_label(): ln for ln in ax.get_lines() if not ln.get_label().startswith("_")}


def _markers(ax, colour):
    """Event markers (single points) of one colour: list of (x, y, filled)."""
    out = []
    for ln in ax.get_lines():
        if ln.get_marker() == "o" and len(ln.get_xdata()) == 1 and \
                to_rgba(ln.get_markeredgecolor()) == to_rgba(colour):
            face = ln.get_markerfacecolor()
            filled = not (isinstance(face, str) and face == "none")
            out.append((float(ln.get_xdata()[0]), float(ln.get_ydata()[0]), filled))
    return out


# ----------------------------------------------------------------------------- V-g-f
def test_vgf_draws_each_selected_mode_with_its_data(analysis, tmp_path):
    path = tmp_path / "vgf.png"
    fig = plots.vgf(analysis, n_modes=5, margin=None, path=path)
    assert path.read_bytes().startswith(PNG)
    ax_z, ax_f = fig.axes[:2]
    sw = analysis.sweep
    ids = plots.select_modes(analysis, n_modes=5, margin=None)
    lines = {k.split(" (")[0]: ln for k, ln in _lines_by_label(ax_z).items()
             if not k.startswith("unstable")}
    assert set(lines) == {sw.mode_labels[k] for k in ids}
    assert set(lines) == {"wing 1", "backward 1", "forward 1", "wing 2", "wing 3"}
    k = sw.mode_labels.index("forward 1")
    x, y = (np.asarray(a, dtype=float) for a in lines["forward 1"].get_data())
    keep = ~np.isnan(x)
    oscillatory = sw.physical[:, k] & (sw.eigenvalues[:, k].imag != 0)
    expect = np.where(oscillatory, sw.damping_ratio[:, k], np.nan)
    np.testing.assert_array_equal(x[keep], sw.V)
    np.testing.assert_array_equal(y[keep], expect)
    # frequency panel: the same mode's frequencies
    f_line = next(ln for ln in ax_f.get_lines()
                  if ln.get_color() == lines["forward 1"].get_color() and ln.get_linestyle() == "-")
    np.testing.assert_array_equal(np.asarray(f_line.get_ydata(), float),
                                  np.where(sw.physical[:, k], sw.frequency_hz[:, k], np.nan))


def test_vgf_marks_flutter_red_and_divergence_green(analysis):
    fig = plots.vgf(analysis, n_modes=5)
    ax_z, ax_f = fig.axes[:2]
    flutter = sorted((e.V, e.frequency_hz) for e in analysis.events if e.kind == "flutter")
    divergence = sorted((e.V, e.frequency_hz) for e in analysis.events if e.kind == "divergence")
    assert flutter and divergence  # this model has both
    assert sorted((x, y) for x, y, _ in _markers(ax_z, "red")) == [(V, 0.0) for V, _ in flutter]
    assert sorted((x, y) for x, y, _ in _markers(ax_f, "red")) == flutter
    assert sorted((x, y) for x, y, _ in _markers(ax_z, "green")) == [(V, 0.0) for V, _ in divergence]
    assert all(filled for *_, filled in _markers(ax_z, "red"))  # onsets are filled


def test_vgf_draws_no_damping_for_a_real_root(analysis):
    """ζ of a real root is ±1 by eq. 5.5, no damping of a vibration: where wing 1 has turned
    into real roots (its divergence) its ζ line stops, and the ζ axis is not stretched to ±1."""
    fig = plots.vgf(analysis, labels=["wing 1"])
    line = next(ln for lab, ln in _lines_by_label(fig.axes[0]).items() if lab.startswith("wing 1"))
    y = np.asarray(line.get_ydata(), float)
    ok = ~np.isnan(y)
    assert (~ok).any() and ok.any()
    assert np.all(np.abs(y[ok]) < 0.999)
    lo, hi = fig.axes[0].get_ylim()
    assert lo > -1.0 and hi < 1.0


def test_vgf_lag_roots_only_when_asked(analysis):
    sw = analysis.sweep
    default = {sw.mode_labels[k] for k in plots.select_modes(analysis, margin=None)}
    with_lag = {sw.mode_labels[k] for k in plots.select_modes(analysis, margin=None,
                                                              include_lag=True)}
    assert not any(lab.startswith("lag") for lab in default)
    assert any(lab.startswith("lag") for lab in with_lag)
    assert default < with_lag


def test_select_modes_takes_the_lowest_frequencies(analysis):
    sw = analysis.sweep
    ids = plots.select_modes(analysis, n_modes=4, margin=None)
    f0 = sw.frequency_hz[0]
    others = [k for k in plots.select_modes(analysis, margin=None) if k not in ids]
    assert max(f0[ids]) <= min(f0[others])
    assert [sw.mode_labels[k] for k in plots.select_modes(analysis, labels=["wing 2", "wing 1"])] \
        == ["wing 1", "wing 2"]
    with pytest.raises(InputError, match="not in the analysis"):
        plots.select_modes(analysis, labels=["wing 99"])
    with pytest.raises(InputError, match="n_modes"):
        plots.select_modes(analysis, n_modes=0)


# ----------------------------------------------------------------------------- mode shapes
def _two_node_map(rotation=1):
    from propwhirl.model.protocol import DofMap, PropellerDofs

    labels = ("node 1 h", "node 1 phi", "node 1 alpha", "node 2 h", "node 2 phi", "node 2 alpha",
              "propeller 1 theta", "propeller 1 psi")
    return DofMap(labels, ("h", "phi", "alpha", "h", "phi", "alpha", "theta", "psi"),
                  (1, 1, 1, 2, 2, 2, -1, -1), (-1,) * 6 + (0, 0),
                  propellers=(PropellerDofs(0, 6, 7, rotation, True, 2.0, 2),),
                  node_y=(0.0, 0.7, 2.0))


def test_mode_shape_plots_the_normalised_eigenvector():
    x = np.array([0.1 + 0.2j, 9.0, 0.05j, 0.4 - 0.1j, 9.0, -0.02, 0.3, 0.3j])  # φ is not plotted
    lam = -0.1 + 30.0j
    fig = plots.mode_shape(x, lam, _two_node_map())
    ax_h, ax_a, ax_o = fig.axes[:3]
    ref = x[3]  # the largest |entry| among h, α, θ, ψ
    xn = x / ref
    h_re = next(ln for ln in ax_h.get_lines() if ln.get_linestyle() == "-" and len(ln.get_xdata()) == 3)
    np.testing.assert_allclose(h_re.get_xdata(), [0.0, 0.7, 2.0])   # the nodes' positions [m]
    np.testing.assert_allclose(h_re.get_ydata(), [0.0, xn[0].real, xn[3].real])
    assert h_re.get_ydata()[2] == pytest.approx(1.0)  # normalised: the reference entry is 1
    a_re = next(ln for ln in ax_a.get_lines() if ln.get_linestyle() == "-")   # α: right axis
    np.testing.assert_allclose(a_re.get_ydata(), [0.0, xn[2].real, xn[5].real])
    a_env = next(ln for ln in ax_a.get_lines() if ln.get_linestyle() == ":")  # envelope |x̂|
    np.testing.assert_allclose(a_env.get_ydata(), [0.0, abs(xn[2]), abs(xn[5])])
    orbit = max(ax_o.get_lines(), key=lambda ln: len(ln.get_xdata()))
    phase = np.linspace(0.0, 2 * np.pi, orbit.get_xdata().size)
    np.testing.assert_allclose(orbit.get_xdata(), (xn[6] * np.exp(1j * phase)).real, atol=1e-12)
    np.testing.assert_allclose(orbit.get_ydata(), (xn[7] * np.exp(1j * phase)).real, atol=1e-12)
    sense = whirl_sense(xn[6], xn[7], 1, lam)
    assert f"{sense} whirl" in ax_o.get_title() and "y = 2 m" in ax_o.get_title()
    # the sense is relative to the propeller's own rotation (a clockwise rotor reverses it)
    flipped = plots.mode_shape(x, lam, _two_node_map(rotation=-1)).axes[2].get_title()
    other = {"forward": "backward", "backward": "forward"}[sense]
    assert f"{other} whirl" in flipped


def test_mode_shape_bad_input():
    from propwhirl.model.protocol import DofMap

    lag_only = DofMap(("h",), ("plunge",), (-1,), (-1,))
    with pytest.raises(InputError, match="nothing to plot"):
        plots.mode_shape(np.ones(2), 1j, lag_only)
    with pytest.raises(InputError, match="need 8 .* or 16"):
        plots.mode_shape(np.ones(3), 1j, _two_node_map())
    with pytest.raises(InputError, match="zero"):
        plots.mode_shape(np.zeros(8), 1j, _two_node_map())


def test_event_mode_shapes_of_the_critical_points(analysis, model, tmp_path):
    crit = analysis.critical
    assert crit is not None
    fig = plots.event_mode_shape(analysis, crit, path=tmp_path / "crit.png")
    assert (tmp_path / "crit.png").read_bytes().startswith(PNG)
    assert f"{crit.V:.2f} m/s" in fig.get_suptitle()
    x, lam, V = plots.event_eigenvector(analysis, crit)
    point = next(p for p in analysis.criticals.points if p.mode == crit.mode and p.V == crit.V)
    assert V == point.V and lam == point.eigenvalue
    fw = analysis.first("forward 1", "flutter")
    fig = plots.event_mode_shape(analysis, fw)
    assert f"{fw.whirl} whirl" in fig.axes[-1].get_title()  # the orbit agrees with the analysis


def test_event_without_stored_vector_is_an_input_error(analysis):
    reread = ModelAnalysis.from_dict(analysis.to_dict(include_eigenvectors=False))
    with pytest.raises(InputError, match="without eigenvectors"):
        plots.event_mode_shape(reread, reread.events[0])
    with_vectors = ModelAnalysis.from_dict(analysis.to_dict(include_eigenvectors=True))
    e = with_vectors.events[0]
    x, lam, V = plots.event_eigenvector(with_vectors, e)
    t = int(np.argmin(np.abs(with_vectors.sweep.V - e.V)))
    assert V == with_vectors.sweep.V[t]
    np.testing.assert_array_equal(x, with_vectors.sweep.eigenvectors[t, :, e.mode])


# ----------------------------------------------------------------------------- Campbell
def test_campbell_plots_the_vibration_data(model, tmp_path):
    rpm = np.linspace(0.0, 4000.0, 5)
    fig = plots.campbell(model, rpm, n_modes=4, path=tmp_path / "c.png")
    assert (tmp_path / "c.png").read_bytes().startswith(PNG)
    ax = fig.axes[0]
    f = campbell(model, rpm).frequency_hz
    curves = [ln for ln in ax.get_lines() if ln.get_label().startswith("_")]
    assert len(curves) == 4
    for i, ln in enumerate(curves):
        np.testing.assert_array_equal(ln.get_ydata(), f[:, i])
    one_p = _lines_by_label(ax)["1P (f = n/60)"]
    np.testing.assert_allclose(one_p.get_ydata(), rpm / 60.0)
    names = [t.get_text() for t in ax.texts]
    assert names[:4] == ["wing 1", "backward 1", "forward 1", "wing 2"]


def test_campbell_diagram_shape_check():
    with pytest.raises(InputError, match="shape"):
        plots.campbell_diagram([0.0, 1.0], np.ones((3, 2)))


# ----------------------------------------------------------------------------- time histories
def test_time_history_plots_theta_psi_in_degrees(tmp_path):
    iso = isolated_baseline_propeller()
    t = np.linspace(0.0, 1.0, 201)
    x0 = np.array([np.radians(1.0), 0.0, 0.0, 0.0])
    rs = {f"V = {V:g} m/s": time_response(iso.state_matrix(V)[0], x0, t, iso.state_labels())
          for V in (77.0, 250.0)}
    fig = plots.time_history(rs, path=tmp_path / "t.png")
    assert (tmp_path / "t.png").read_bytes().startswith(PNG)
    ax_t, ax_p, ax_o = fig.axes[:3]
    for ln, (label, r) in zip(ax_t.get_lines(), rs.items()):
        assert ln.get_label() == label
        np.testing.assert_allclose(ln.get_ydata(), np.degrees(r["propeller 1 theta"]))
    np.testing.assert_allclose(ax_p.get_lines()[0].get_ydata(),
                               np.degrees(rs["V = 77 m/s"]["propeller 1 psi"]))
    path = ax_o.get_lines()[0]
    np.testing.assert_allclose(path.get_xdata(), np.degrees(rs["V = 77 m/s"]["propeller 1 theta"]))
    assert ax_t.get_lines()[0].get_ydata()[0] == pytest.approx(1.0)  # initial pitch 1°
    with pytest.raises(InputError, match="no state labelled 'propeller 2 theta'"):
        plots.time_history(rs["V = 77 m/s"], propeller=1)


# ----------------------------------------------------------------------------- optional matplotlib
def test_missing_matplotlib_gives_the_install_hint(monkeypatch, analysis):
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(InputError, match=r"pip install propwhirl\[plots\]"):
        plots.vgf(analysis)


def test_runtime_and_cli_import_without_matplotlib():
    code = textwrap.dedent("""
        import sys
        class Block:
            def find_spec(self, name, path=None, target=None):
                if name.split('.')[0] == 'matplotlib':
                    raise ImportError('matplotlib blocked for this test')
        sys.meta_path.insert(0, Block())
        import propwhirl.app.plots, propwhirl.io, propwhirl.app.cli, propwhirl.app.run
        from propwhirl.app import cli
        assert cli.main(['case', 'isolated-propeller']) == 0
        assert 'matplotlib' not in sys.modules
        try:
            propwhirl.app.plots.campbell_diagram([0.0, 1.0], [[1.0], [1.0]])
        except propwhirl.validate.InputError as exc:
            assert 'pip install propwhirl[plots]' in str(exc)
            print('ok')
        """)
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip().endswith("ok")
