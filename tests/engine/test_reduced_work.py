"""The work of the reduced wingtip analysis, bounded (issue 26, item 2; the profile and the
eigen-solution equivalents in docs/performance.md, "The reduced analysis's overhead"): its
cost is per node — an eigen-solution of the 50-state reduced matrix, two links, the clusters
followed through branch points — so the nodes and eigen-solutions are what a change must not
grow.  Counted, never timed."""
from __future__ import annotations

from propwhirl.analysis import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing


def test_reduced_wingtip_analysis_work():
    a = analyse(wingtip_propeller_wing(), method="reduced")
    sw = a.sweep.stats
    assert sw["reduced_states"] == 50
    assert sw["nodes"] <= 14 and sw["eig"] <= 14            # 8 first speeds, 4 refined, 2
    assert sw["state_matrix_calls"] <= 4                    # one batch per refinement round
    assert a.criticals.stats["corrected"] == 3              # one full-order correction each
    assert a.criticals.stats["evaluations"] <= 15


def test_reduced_wingtip_cluster_work(monkeypatch):
    """The clusters tried as a set and those whose roots are followed over the sub-steps
    (before: 47 trials, 17 followed; 8 of them refused by a real part changing sign with no
    branch point, which the sub-steps' roots show without following them)."""
    import propwhirl.engine.clusters as clusters

    count = {"trials": 0, "followed": 0}

    def counter(name, f):
        def counted(*args, **kwargs):
            count[name] += 1
            return f(*args, **kwargs)
        return counted

    monkeypatch.setattr(clusters, "_try_cluster", counter("trials", clusters._try_cluster))
    monkeypatch.setattr(clusters, "_follow_substeps",
                        counter("followed", clusters._follow_substeps))
    analyse(wingtip_propeller_wing(), method="reduced")
    assert count["trials"] <= 47
    assert count["followed"] <= 9


def test_no_cluster_trial_twice_in_a_step(monkeypatch):
    """The X-57-like model (reduced): a row set reached again from another seed of the same
    step is not tried again (before: 13 of 79 trials were repeats)."""
    from pathlib import Path

    import propwhirl.engine.clusters as clusters
    from propwhirl.io import load_model

    seen = []
    original = clusters._try_cluster

    def recorded(a, b, rows, cols, *args, **kwargs):
        seen.append((a.V, b.V, tuple(rows.tolist()), tuple(cols.tolist())))
        return original(a, b, rows, cols, *args, **kwargs)

    monkeypatch.setattr(clusters, "_try_cluster", recorded)
    model = load_model(Path(__file__).resolve().parents[2] / "examples" / "x57_like.toml")
    analyse(model, method="reduced")
    assert len(seen) == len(set(seen)) and len(seen) <= 66
