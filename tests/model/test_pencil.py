"""model.pencil: the full-order pencil from a sparsity pattern built once equals
BlockSystem.pencil to the last bit (indices and values), at every speed; a reduced model builds
the pattern and the constant part once and assembles no pencil from triplets."""
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.blocks import BlockSystem
from propwhirl.model.pencil import SparsePencil
from propwhirl.model.reduction import reduce


def _identical(A, B) -> bool:
    return (A.shape == B.shape and A.indptr.dtype == B.indptr.dtype
            and A.indptr.tobytes() == B.indptr.tobytes()
            and A.indices.tobytes() == B.indices.tobytes() and A.data.tobytes() == B.data.tobytes())


def _variants():
    m = wingtip_propeller_wing()
    return {"wingtip": m,
            "no propeller aerodynamics": wingtip_propeller_wing(propeller_aero=False),
            "no wing aerodynamics": m.with_(wing_aero=False),
            "in-plane bending": replace(m, wing=replace(m.wing, EI_chordwise=200.0 * m.wing.EI))}


@pytest.mark.parametrize("name", list(_variants()))
def test_the_pattern_gives_the_pencil_of_the_blocks_bit_for_bit(name):
    a = _variants()[name].assembly()
    pencil = SparsePencil.of(a.second_order_blocks(np.array([1.0])))
    assert pencil.stable
    V = np.array([1.0, 60.0, 143.15, 250.0, 320.9])
    b = a.second_order_blocks(V)
    for t in range(V.size):
        for mine, theirs in zip(pencil.at(b, t), b.pencil(t)):
            assert _identical(mine, theirs), (name, V[t])


def test_a_position_without_a_nonzero_entry_is_left_out_as_the_triplets_leave_it():
    """Propeller aerodynamics off: positions of its blocks that are zero at every speed are not
    stored (as SciPy's conversion of the triplets, which drops zero values, does not)."""
    a = wingtip_propeller_wing(propeller_aero=False).assembly()
    pencil = SparsePencil.of(a.second_order_blocks(np.array([1.0])))
    F, _ = pencil.at(a.second_order_blocks(np.array([200.0])))
    assert F.nnz < pencil.F.indices.size
    assert np.all(F.data != 0)


def test_a_reduced_model_assembles_its_pencils_from_the_pattern(monkeypatch):
    """One pattern and one constant part per reduced model; no pencil from triplets."""
    calls = {"constant": 0, "pencil": 0}
    constant, pencil = BlockSystem.pencil_constant, BlockSystem.pencil

    def counted(name, f):
        def wrapped(*a, **k):
            calls[name] += 1
            return f(*a, **k)
        return wrapped

    monkeypatch.setattr(BlockSystem, "pencil_constant", counted("constant", constant))
    monkeypatch.setattr(BlockSystem, "pencil", counted("pencil", pencil))
    R = reduce(wingtip_propeller_wing(), np.arange(1.0, 351.0, 10.0))
    for V in (100.0, 150.0, 200.0, 250.0):
        F, E = R.pencil(V)
        assert F.shape == E.shape == (R.lift.shape[0],) * 2
    assert calls == {"constant": 1, "pencil": 0}
