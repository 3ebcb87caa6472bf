"""The doublet-lattice tables are an object the analysis owns (issue 33, item 8): no module of
the doublet-lattice path keeps tables (AICs, fits) at module level; ``analyse`` reads and fills
the ``DlmTables`` it is given (or its own), and two analyses with different tables in one
process do not see each other's entries."""
import dataclasses
import importlib
import pickle

import numpy as np
import pytest

from propwhirl.model.aerodynamics import dlm
from propwhirl.validate import InputError

#: the modules of the doublet-lattice path (tables, fits, the state space, the p-k)
MODULES = ("propwhirl.model.aerodynamics.dlm", "propwhirl.model.aerodynamics.dlm_rfa",
           "propwhirl.model.aerodynamics.dlm_cache", "propwhirl.model.aerodynamics.dlm_mesh",
           "propwhirl.model.aerodynamics.theodorsen", "propwhirl.model.aerodynamics.validity",
           "propwhirl.model.dlm_modal", "propwhirl.model.frequency_domain",
           "propwhirl.analysis.modal_dlm", "propwhirl.analysis.pk")


@pytest.mark.parametrize("name", MODULES)
def test_no_module_level_mutable_table_state(name):
    """No dict, list or set (an OrderedDict LRU of tables, a dict of fits) and no
    functools cache among the module's globals: a module-level cache would be state shared
    behind the analyses' backs (main had ``dlm._CACHE``, an OrderedDict)."""
    module = importlib.import_module(name)
    state = sorted(k for k, x in vars(module).items() if not k.startswith("__") and (
        isinstance(x, (dict, list, set, bytearray))
        or (callable(x) and hasattr(x, "cache_info") and getattr(x, "__module__", "") == name)))
    assert state == []


def patil_dlm():
    from propwhirl.cases.ch07_patil import patil_model
    m = patil_model(10)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=2,
                                            dlm_spanwise_panels=8))


SPEEDS = np.arange(20.0, 36.0, 4.0)


@pytest.mark.parametrize("method", ["auto", "pk"])
def test_two_analyses_with_their_own_tables_share_nothing(monkeypatch, method):
    """The same wing analysed twice in one process, each with its own tables: the second
    computes every AIC again (it does not see the first's), leaves the first's tables as
    they were, and gives the same events; a third with the first's tables computes none."""
    pytest.importorskip("panelaero")
    from propwhirl.analysis import analyse
    from propwhirl.model.aerodynamics import dlm_cache

    monkeypatch.delenv(dlm_cache.CACHE_ENV, raising=False)
    m = patil_dlm()
    first, second = dlm.DlmTables(), dlm.DlmTables()
    a = analyse(m, SPEEDS, method=method, dlm_tables=first)
    n = first.aero(m.wing).evaluations
    assert n > 0 and len(second) == 0
    b = analyse(m, SPEEDS, method=method, dlm_tables=second)
    assert second.aero(m.wing) is not first.aero(m.wing)
    assert second.aero(m.wing).evaluations == n
    assert first.aero(m.wing).evaluations == n
    assert [(e.kind, e.event, e.V) for e in a.events] == [(e.kind, e.event, e.V) for e in b.events]
    c = analyse(m, SPEEDS, method=method, dlm_tables=first)
    assert first.aero(m.wing).evaluations == n                     # all read from the tables
    assert [(e.kind, e.event, e.V) for e in c.events] == [(e.kind, e.event, e.V) for e in a.events]


def test_the_assembly_holds_the_tables_it_is_given():
    m = patil_dlm()
    tables = dlm.DlmTables()
    assert m.assembly(dlm_tables=tables).dlm_tables is tables
    assert m.assembly(dlm_tables=tables).with_switches(wing_aero=False).dlm_tables is tables
    own = m.assembly().dlm_tables
    assert isinstance(own, dlm.DlmTables) and own is not tables
    strips = m.with_(wing=dataclasses.replace(m.wing, aero="strip"))
    assert strips.assembly(dlm_tables=tables).dlm_tables is None


def test_tables_keep_the_last_geometries_and_travel_empty():
    """At most ``size`` geometries (least recently used dropped); pickled (a study's tables
    sent to a worker process) they arrive empty, with their size."""
    from propwhirl.model.structure.wing import Wing
    wings = [Wing(semi_span=2.0 + i, mass_per_length=1.0, EI=1e4, GJ=1e4,
                  radius_of_gyration=0.25, n_elements=4, aero="dlm", dlm_chordwise_panels=2,
                  dlm_spanwise_panels=3) for i in range(3)]
    tables = dlm.DlmTables(size=2)
    a0 = tables.aero(wings[0])
    assert tables.aero(wings[0]) is a0 and len(tables) == 1
    tables.aero(wings[1])
    tables.aero(wings[0])                                     # the most recent again
    tables.aero(wings[2])                                     # drops wings[1]
    assert wings[0] in tables and wings[2] in tables and wings[1] not in tables
    back = pickle.loads(pickle.dumps(tables))
    assert isinstance(back, dlm.DlmTables) and len(back) == 0 and back.size == 2


@pytest.mark.parametrize("bad", ["tables", 3, {}])
def test_bad_tables_are_one_line_errors(bad):
    from propwhirl.analysis import analyse
    with pytest.raises(InputError, match=r"^dlm_tables = .* is invalid: must be None or a "
                                         r"propwhirl.model.aerodynamics.dlm.DlmTables$"):
        analyse(patil_dlm(), SPEEDS, dlm_tables=bad)
    with pytest.raises(InputError, match=r"^size = 0 is invalid"):
        dlm.DlmTables(size=0)


def test_a_big_fill_on_processes_gives_the_same_table(monkeypatch):
    """DlmAerodynamics.fill on two worker processes (issue 37 item 2: the thresholds lowered
    to this small wing) computes every missing node once, counts it, reports each, and gives
    the table nodes bit for bit as computed in this process."""
    pytest.importorskip("panelaero")
    from propwhirl.model.aerodynamics import dlm_cache
    from propwhirl.model.structure.wing import Wing

    monkeypatch.delenv(dlm_cache.CACHE_ENV, raising=False)
    monkeypatch.setattr(dlm, "PARALLEL_AICS", 2)
    monkeypatch.setattr(dlm, "PARALLEL_PANELS", 1)
    w = Wing(semi_span=3.0, mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25,
             n_elements=4, aero="dlm", dlm_chordwise_panels=2, dlm_spanwise_panels=4)
    nodes = [(0.3, 1), (0.3, 5), (0.35, 9), (0.0, 0)]
    par, seq = dlm.DlmAerodynamics(w), dlm.DlmAerodynamics(w)
    par.column_node(0.3, 5)                               # already there: not again
    seen = []
    assert par.fill(nodes, lambda d, t: seen.append((d, t)), processes=2) == 3
    assert seen == [(0, 3), (1, 3), (2, 3), (3, 3)] and par.evaluations == 4
    for mach, ik in nodes:
        assert np.array_equal(par.column_node(mach, ik), seq.column_node(mach, ik))
    assert par.evaluations == 4


def test_tables_processes():
    assert dlm.DlmTables(processes=1).processes == 1
    assert 1 <= dlm.DlmTables().processes <= 2
    assert pickle.loads(pickle.dumps(dlm.DlmTables(processes=1))).processes == 1


def test_the_steady_part_once_per_mach_gives_panelaeros_aic():
    """DlmAerodynamics.aic keeps the steady (VLM) part of its Mach column (issue 37 item 2: 8 %
    of a DLM analysis was that part computed again at every k), since the kernel on the
    half-wing's rows (tests/model/test_dlm_kernel.py) PanelAero's calc_Qjj folded to the
    symmetric half-wing to round-off (1e-12 of max |Q|; was bit for bit with PanelAero's whole
    kernel), at k = 0 and not, across Machs."""
    pytest.importorskip("panelaero")
    from panelaero import DLM
    from propwhirl.model.structure.wing import Wing

    w = Wing(semi_span=3.0, mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25,
             n_elements=4, aero="dlm", dlm_chordwise_panels=3, dlm_spanwise_panels=5)
    aero = dlm.DlmAerodynamics(w)
    n = aero.mesh.n
    for mach, k in ((0.0, 0.0), (0.3, 0.0), (0.3, 0.4), (0.3, 1.2), (0.65, 0.05), (0.3, 0.7)):
        with np.errstate(all="ignore"):                   # PanelAero's own, called raw
            Q = DLM.calc_Qjj(aero.grid, mach, k / aero.b_ref)
        ref = Q[n:, n:] + Q[n:, :n]
        assert np.abs(aero.aic(mach, k) - ref).max() <= 1e-12 * np.abs(ref).max()