"""``propwhirl analyse --vd`` ends with the margin to factor x V_D (issue 25.5), and the
summary reads well with several propellers: '-' in the propeller column of a wing's event,
one warning listing the propellers it applies to, text instead of NaN."""
from __future__ import annotations

import re

import pytest

from propwhirl import io
from propwhirl.app import cli
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.model.systems import Installation, PropellerWing

NUMBER = r"[-+]?\d+(?:\.\d+)?"


@pytest.fixture(scope="module")
def two_file(tmp_path_factory):
    """A 5-element wing with propellers at 1.6 m and the tip (fast to analyse)."""
    m = PropellerWing(baseline_wing(5), baseline_flight(),
                      (Installation(baseline_propeller(), 1.6),
                       Installation(baseline_propeller(), 5.7)), name="two small")
    path = tmp_path_factory.mktemp("models") / "two.toml"
    io.save_model(m, path)
    return path


def _run(*argv):
    """(stdout, stderr, exit code) of ``propwhirl *argv``."""
    import contextlib
    import io as _io

    out, err = _io.StringIO(), _io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = cli.main(list(argv))
    return out.getvalue(), err.getvalue(), rc


@pytest.fixture(scope="module")
def analysed(two_file):
    """(stdout, stderr, exit code) of ``analyse two.toml --vd 130``."""
    return _run("analyse", str(two_file), "--vd", "130", "--quiet")


@pytest.fixture(scope="module")
def plain(two_file):
    """(stdout, stderr, exit code) of ``analyse two.toml`` (no --vd)."""
    return _run("analyse", str(two_file), "--quiet")


def _clearance(path, capsys, *extra):
    rc = cli.main(["clearance", str(path), "--vd", "130", "--no-minimum", *extra])
    return capsys.readouterr().out, rc


def test_vd_ends_with_clearance_margin_and_least_damping(two_file, analysed, capsys):
    from propwhirl.studies.campaign import _Task, evaluate_point
    from propwhirl.studies.clearance import clearance_speeds

    out, _, rc = analysed
    assert rc == 0                                  # analyse is no clearance: exit code 0
    last = out.strip().splitlines()[-1]
    cl, crc = _clearance(two_file, capsys)
    # clearance: "critical: divergence (onset) of wing 1 at 141.83 m/s, margin -5.1 %"
    V_req = float(re.search(rf"= ({NUMBER}) m/s: (?:NOT )?CLEARED", cl).group(1))
    cV, cpct = re.search(rf"critical: .* at ({NUMBER}) m/s, margin ({NUMBER}) %", cl).groups()
    assert f"1.15 x 130 = {V_req:.2f} m/s" in last
    m = re.search(rf"at ({NUMBER}) m/s, margin ({NUMBER}) m/s \(({NUMBER}) %\)", last)
    assert m, last
    assert m.group(1) == cV and m.group(3) == cpct
    assert float(m.group(2)) == pytest.approx(float(cV) - V_req, abs=0.006)
    # the least damping g = 2 zeta below factor x V_D: the campaign's (certify's) definition
    model = io.load_model(two_file)
    grid = clearance_speeds(model, V_req)
    r = evaluate_point(_Task(model, grid, 130.0, V_req, 0.01, True, True))
    g = re.search(rf"g = 2 zeta = ({NUMBER}) \((.+) at ({NUMBER}) m/s\)", last)
    assert g, last
    assert float(g.group(1)) == pytest.approx(2 * r["least_zeta"], abs=6e-5)
    assert g.group(2) == r["least_zeta_mode"]
    assert float(g.group(3)) == pytest.approx(r["least_zeta_V"], abs=0.006)
    assert "nan" not in last.lower()
    assert crc == 1 and rc == 0


def test_factor_passed_on(two_file, capsys):
    assert cli.main(["analyse", str(two_file), "--vd", "100", "--factor", "1.2",
                     "--quiet"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "margin to 1.2 V_D = 1.2 x 100 = 120.00 m/s" in last


@pytest.mark.parametrize("argv, says", [
    (["--factor", "1.2"], "--factor 1.2 needs --vd"),
    (["--vd", "130", "--factor", "4"], "--factor = 4.0 is outside the valid range [1, 3]"),
    (["--vd", "0"], "--vd = 0.0 m/s is invalid"),
])
def test_bad_vd_factor_refused_before_the_work(two_file, monkeypatch, capsys, argv, says):
    import propwhirl.analysis.stability as st

    def boom(*a, **k):
        raise AssertionError("analysed before the options were checked")

    monkeypatch.setattr(st, "analyse", boom)
    assert cli.main(["analyse", str(two_file), *argv]) == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1


def test_no_instability_is_text_not_nan(two_file, capsys):
    assert cli.main(["analyse", str(two_file), "--vd", "20", "--speeds", "1", "30", "1",
                     "--quiet"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "margin to 1.15 V_D" in last
    assert "none in the analysed range" in last
    assert "nan" not in last.lower() and "none" in last


def test_divergence_row_without_propeller_share_names_none(plain):
    out = plain[0]
    rows = [ln for ln in out.splitlines() if re.match(r"\s+divergence\s+onset\s+wing", ln)]
    assert rows, out
    for ln in rows:
        cols = re.split(r"\s{2,}", ln.strip())
        assert cols[3] == "-", ln                  # type, event, mode, propeller


def test_divergence_row_in_summary_unit():
    """The rule itself: every share below 0.5 % -> '-'; one at 0.5 % or more -> named."""
    from propwhirl.analysis.participation import ModeParticipation, PropellerShare
    from propwhirl.analysis.stability import Instability, _leading

    def ev(shares):
        props = tuple(PropellerShare(k + 1, 1.6 * (k + 1), s, None, 1.0 - 0.1 * k)
                      for k, s in enumerate(shares))
        part = ModeParticipation(100.0, 1.0 - sum(shares), 0.0, props)
        return Instability("divergence", "onset", 0, "wing 1", 100.0, 0.0, participation=part)

    assert _leading(ev([0.004, 0.001])) == "-"
    assert _leading(ev([0.004, 0.006])).startswith("1")


def test_tip_mach_warning_once_listing_propellers(plain):
    err = plain[1]
    tips = [ln for ln in err.splitlines() if "helical tip Mach" in ln]
    assert len(tips) == 1, err
    assert "propellers 1, 2:" in tips[0]


def test_the_least_damping_line_says_which_damping_and_from_where(two_file, analysed):
    """Issue 35 item 2: the line names the total damping (structural included) and the first
    analysed speed, and gives the aerodynamic increment above each mode's damping there,
    checked mode by mode against the analysis."""
    import numpy as np

    from propwhirl.analysis.margin import DAMPING_MODES, oscillatory_damping
    from propwhirl.analysis.stability import analyse
    from propwhirl.studies.clearance import clearance_speeds

    last = analysed[0].strip().splitlines()[-1]
    model = io.load_model(two_file)
    V_req = 1.15 * 130
    a = analyse(model, clearance_speeds(model, V_req), vgf=True)
    V = a.sweep.V
    assert f"least total damping (structural included) from {V[0]:.2f} m/s (the first " \
           "analysed speed)" in last
    zeta, _ = oscillatory_damping(a.sweep, a.modes_of_interest(DAMPING_MODES))
    best = np.inf
    for k in range(zeta.shape[1]):
        ok = np.flatnonzero(np.isfinite(zeta[:, k]))
        for t in ok:
            if V[t] <= V_req * (1 + 1e-12):
                best = min(best, 2 * (zeta[t, k] - zeta[ok[0], k]))
    m = re.search(rf"aerodynamic increment above each mode's damping at {V[0]:.2f} m/s: least "
                  rf"({NUMBER}) \(", last)
    assert m, last
    assert float(m.group(1)) == pytest.approx(best, abs=6e-5)


def test_vd_plot_draws_both_lines_and_reuses_the_analysis(two_file, tmp_path, monkeypatch):
    """Issue 35 item 5: ``analyse --vd 130 --plot`` draws V_D and 1.15 V_D (read from the
    figure's artists: vertical lines in both axes) and draws the analysis's own sweep — no
    second sweep on a finer grid (fine_sweep is not called)."""
    pytest.importorskip("matplotlib")
    import numpy as np

    from propwhirl.app import plots
    from propwhirl.app.plots import vgf_plot

    def no_second_sweep(*a, **k):
        raise AssertionError("the plot swept again")

    monkeypatch.setattr(vgf_plot, "fine_sweep", no_second_sweep)
    drawn = []
    original = plots.vgf

    def keep(*a, **k):
        drawn.append(original(*a, **k))
        return drawn[-1]

    monkeypatch.setattr(plots, "vgf", keep)
    out, err, rc = _run("analyse", str(two_file), "--vd", "130", "--plot",
                        str(tmp_path / "v.png"), "--quiet")
    assert rc == 0, err
    assert (tmp_path / "v.png").stat().st_size > 0
    (fig,) = drawn
    for ax in fig.axes[:2]:
        vertical = {round(float(ln.get_xdata()[0]), 6) for ln in ax.lines
                    if len(ln.get_xdata()) == 2 and ln.get_xdata()[0] == ln.get_xdata()[1]}
        assert {130.0, round(1.15 * 130.0, 6)} <= vertical, vertical
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert "V_D 130.0 m/s" in texts and "required 149.5 m/s" in texts
    # the curves pass through the analysis's own speeds (its nodes drawn as dots)
    dots = [ln for ln in fig.axes[0].lines if ln.get_marker() == "."]
    assert dots and all(np.all(np.diff(ln.get_xdata()) > 0) for ln in dots)


def test_plot_shape_writes_the_critical_mode(two_file, tmp_path):
    """Issue 35 item 8: the critical mode's shape from the command line (--plot-modes is a
    count); refused before the work without a format matplotlib writes."""
    pytest.importorskip("matplotlib")
    out, err, rc = _run("analyse", str(two_file), "--plot-shape", str(tmp_path / "s.png"),
                        "--quiet")
    assert rc == 0, err
    assert f"wrote {tmp_path / 's.png'}" in out and (tmp_path / "s.png").stat().st_size > 1000
    out, err, rc = _run("analyse", str(two_file), "--plot-shape", str(tmp_path / "s.xyz"),
                        "--quiet")
    assert rc == 2 and "--plot-shape" in err and len(err.strip().splitlines()) == 1
