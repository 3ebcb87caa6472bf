"""`propwhirl analyse --method`: the dense reference and the reduced analysis from the CLI."""
import numpy as np

from propwhirl import io as pio
from propwhirl.app.cli import main
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing


def test_reduced_and_dense_from_the_command_line(tmp_path, capsys):
    path = tmp_path / "wingtip.toml"
    pio.save_model(wingtip_propeller_wing(), path)
    out = {}
    for method in ("dense", "reduced"):
        assert main(["analyse", str(path), "--method", method, "--speeds", "100", "350", "50",
                     "--json", str(tmp_path / f"{method}.json")]) == 0
        out[method] = capsys.readouterr().out
    import re
    m = re.search(r"method: reduced \((\d+) of 204 states", out["reduced"])
    assert m and int(m.group(1)) < 204
    assert "method: reduced" not in out["dense"]
    from propwhirl.analysis.stability import load
    d, r = load(tmp_path / "dense.json"), load(tmp_path / "reduced.json")
    assert [e.label for e in d.events] == [e.label for e in r.events]
    np.testing.assert_allclose([e.V for e in r.events], [e.V for e in d.events], rtol=5e-4)


def test_an_unknown_method_is_a_one_line_error(tmp_path, capsys):
    path = tmp_path / "wingtip.toml"
    pio.save_model(wingtip_propeller_wing(), path)
    try:
        main(["analyse", str(path), "--method", "sparse"])
    except SystemExit as exc:
        assert exc.code == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'sparse'" in err


def test_the_pk_method_from_the_command_line(tmp_path, capsys):
    """--method pk: the exact-Theodorsen p-k flutter speeds, within 1 % of the finite-state ones
    on the wingtip model (docs/validation.md)."""
    path = tmp_path / "wingtip.toml"
    pio.save_model(wingtip_propeller_wing(), path)
    assert main(["analyse", str(path), "--method", "pk", "--speeds", "100", "350", "10",
                 "--json", str(tmp_path / "pk.json")]) == 0
    from propwhirl.analysis.stability import load
    pk = load(tmp_path / "pk.json")
    flutter = [e.V for e in pk.events if e.kind == "flutter" and e.event == "onset"]
    assert flutter and abs(min(flutter) - 159.39) / 159.39 < 0.01


def test_the_default_analysis_of_a_dlm_wing_from_the_command_line(small_dlm_file, capsys):
    """`propwhirl analyse` of a doublet-lattice wing (the modal Roger state space, its crossings
    the p-k's) prints its method line and exits 0 (it ended in a KeyError after the summary)."""
    assert main(["analyse", str(small_dlm_file), "--speeds", "100", "290", "10", "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "critical:" in out
    assert "method: reduced (the Roger state space on " in out
    assert "its crossings converged by the p-k method on Q(k)" in out
