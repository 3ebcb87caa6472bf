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
