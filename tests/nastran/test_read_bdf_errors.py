"""NASTRAN bulk data in, refused (issue 36, items 3 and 7): everything a beam wing cannot
represent, and every broken deck — missing cards, unstated or mixed units, a hub grid not in
the model, duplicated ids, a truncated file — is one line naming the file, the card and its
id, and nothing is returned."""
from __future__ import annotations

import dataclasses

import pytest

from helpers import bdf_decks as d
from propwhirl import InputError
from propwhirl.cases import registry
from propwhirl.io.nastran_read import read_bdf


@pytest.fixture(scope="module")
def base():
    return registry.case_model("wingtip")


def refused(tmp_path, text: str, base, *, units="si", hubs=(101,)) -> str:
    path = tmp_path / "wing.bdf"
    path.write_text(text)
    with pytest.raises(InputError) as info:
        read_bdf(path, units=units, base=base, hubs=hubs)
    message = str(info.value)
    assert "\n" not in message, message
    assert message.startswith(str(path) + ": "), message
    return message


def swap(cards, name, cid, new):
    return d.replace_card(cards, name, cid, new)


def on_all(cards, name, change):
    return [change(c) if c[0] == name else c for c in cards]


R = d.standard("rigid")
F = d.standard("flexible")

#: (id, cards, expected fragments of the one line, keyword arguments of text())
CASES = [
    # ---------------------------------------------------------------- missing cards
    ("missing property", swap(R, "PBAR", 10, None), ["CBAR 1 refers to PBAR or PBARL 10",
                                                     "not in the file"], {}),
    ("missing material", swap(R, "MAT1", 20, None), ["PBAR 10 refers to MAT1 20",
                                                     "not in the file"], {}),
    ("missing grid", swap(R, "GRID", 3, None), ["refers to GRID 3", "not in the file"], {}),
    ("missing coordinate system", swap(R, "GRID", 2, d.grid(2, 0.0, 0.5, 0.0, "2", cp=9)),
     ["GRID 2 refers to coordinate system 9"], {}),
    ("property of the wrong type", on_all(R, "CBAR", lambda c: ["CBEAM"] + c[1:]),
     ["CBEAM 1 refers to PBAR 10: must be PBEAM or PBEAML"], {}),
    ("no clamp", swap(R, "SPC1", 1, ["SPC1", 1, "12345", 1]), ["no grid of the stick is "
                                                               "clamped"], {}),
    ("the case control's SPC set missing", swap(R, "SPC1", 1, None),
     ["the case control's SPC = 1 is not in the file"], {}),
    # ---------------------------------------------------------------- duplicated ids
    ("duplicated grid (same card)", R + [d.grid(3, d.STICK_X, 1.0, d.STICK_Z, "2")],
     ["GRID 3 is given twice"], {}),
    ("duplicated grid (other card)", R + [d.grid(3, d.STICK_X, 1.2, d.STICK_Z, "2")],
     ["GRID 3 is given twice"], {}),
    ("duplicated element", R + [["CBAR", 2, 10, 3, 4, 0.0, 0.0, 1.0]],
     ["CBAR 2 is given twice"], {}),
    ("duplicated property", R + [["PBAR", 10, 20, 0.02, 1e-6, 1e-6, 1e-6]],
     ["PBAR 10 is given twice"], {}),
    ("duplicated mass", R + [d.conm2(301, 102, 3.0)], ["CONM2 301 is given twice"], {}),
    ("duplicated material", R + [["MAT1", 20, d.E, d.G, None, d.RHO]],
     ["MAT1 20 is given twice"], {}),
    ("duplicated rigid element", R + [["RBE2", 201, 5, "123456", 101]],
     ["RBE2 201 is given twice"], {}),
    ("duplicated spring", F + [["CELAS2", 221, 5e4, 111, 5, 112, 5]],
     ["CELAS2 221 is given twice"], {}),
    ("duplicated solution setting", R + [["EIGRL", 1, None, None, 12]],
     ["EIGRL 1 is given twice"], {}),
    ("an element id shared by a CBAR and a CBEAM", R + [["CBEAM", 2, 10, 3, 4, 0.0, 0.0, 1.0]],
     ["CBAR 2 and CBEAM 2 share one id"], {}),
    ("an element id shared by a CBAR and a CELAS2", F + [["CELAS2", 1, 5e4, 111, 5, 112, 5]],
     ["CBAR 1 and CELAS2 1 share one id", "element ids must be unique"], {}),
    ("an element id shared by a CBAR and an RBE2",
     R + [d.grid(120, -0.5, 2.0, d.STICK_Z), ["RBE2", 1, 101, "123456", 120]],
     ["CBAR 1 and RBE2 1 share one id"], {}),
    ("an element id shared by a CBAR and a CONM2", R + [d.conm2(1, 102, 3.0)],
     ["CBAR 1 and CONM2 1 share one id"], {}),
    ("a property id shared by a PBAR and a PBEAM", R + [d.pbeam(10)],
     ["PBAR 10 and PBEAM 10 share one id"], {}),
    # ---------------------------------------------------------------- truncated, unread
    ("truncated: no ENDDATA", R, ["no ENDDATA", "truncated"], {"enddata": False}),
    ("a card propwhirl does not read", R + [["CQUAD4", 77, 1, 1, 2, 3, 4]], ["CQUAD4 77",
                                                                             "not read"], {}),
    ("a CBUSH mount", R + [["CBUSH", 78, 1, 101, 102]], ["CBUSH 78", "CELAS2"], {}),
    ("an MPC", R + [["MPC", 5, 101, 1, 1.0, 102, 1, -1.0]], ["MPC 5", "not read"], {}),
    # ---------------------------------------------------------------- the stick
    ("bent stick", swap(R, "GRID", 4, d.grid(4, d.STICK_X + 0.2, 1.5, d.STICK_Z, "2")),
     ["GRID 4 lies 0.2 m off the line from the root GRID 1 to the tip GRID 5", "a bent stick"],
     {}),
    ("stick with dihedral", swap(R, "GRID", 4, d.grid(4, d.STICK_X, 1.5, d.STICK_Z + 0.1, "2")),
     ["GRID 4 lies 0.1 m off (in z)", "dihedral"], {}),
    ("left wing", on_all(R, "GRID", lambda c: c[:4] + [d.L(-c[4].value)] + c[5:]),
     ["not outboard", "mirror"], {}),
    ("branch", R + [d.grid(6, d.STICK_X, 1.0, 1.0, "2"), ["CBAR", 5, 10, 3, 6, 0.0, 0.0, 1.0]],
     ["GRID 3 joins 3 beam elements", "second load path"], {}),
    ("two elements on one pair", R + [["CBAR", 5, 10, 3, 4, 0.0, 0.0, 1.0]],
     ["joins 3 beam elements"], {}),
    ("rigid element along the wing", R + [["RBE2", 250, 2, "123456", 3]],
     ["GRID 2 and GRID 3 of the stick are joined rigidly", "RBE2 250"], {}),
    ("beam offset", swap(R, "CBAR", 2, ["CBAR", 2, 10, 2, 3, 0.0, 0.0, 1.0, None, None, None,
                                        d.L(0.1), 0.0, 0.0]),
     ["CBAR 2: offset WA", "off its grids"], {}),
    ("pin flags", swap(R, "CBAR", 2, ["CBAR", 2, 10, 2, 3, 0.0, 0.0, 1.0, None, "4"]),
     ["CBAR 2: pin flags PA = 4"], {}),
    ("product of inertia", swap(R, "PBAR", 10, ["PBAR", 10, 20, 0.01, 2e-6, 8e-6, 3e-6, 5.0,
                                                None, *([None] * 8), None, None, 1e-7]),
     ["PBAR 10: I12", "principal axes"], {}),
    ("turned principal planes", on_all(R, "CBAR", lambda c: c[:5] + [1.0, 0.0, 1.0]),
     ["CBAR 1: its orientation vector puts plane 1 at 45 deg"], {}),
    ("support along the span", R + [["SPC1", 1, "3", 3]], ["GRID 3 (on the stick) holds "
                                                           "component(s) 3", "support"], {}),
    ("enforced displacement", R + [["SPC", 1, 3, "3", 0.01]], ["SPC 1 enforces 0.01 on GRID 3"],
     {}),
    ("mixed in-plane constraints", swap(R, "GRID", 3, d.grid(3, d.STICK_X, 1.0, d.STICK_Z,
                                                             "126")),
     ["GRID 3: its in-plane components"], {}),
    ("a PBARL shape not read", swap(R, "PBAR", 10, ["PBARL", 10, 20, "MSCBML0", "BOX", None,
                                                    None, None, None, 0.1, 0.1, 0.01, 0.01]),
     ["PBARL 10: TYPE BOX is not read"], {}),
    ("a CD frame turned", swap(R, "GRID", 3, ["GRID", 3, None, d.L(d.STICK_X), d.L(1.0),
                                             d.L(d.STICK_Z), 8, "2"])
     + [["CORD2R", 8, 0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0]],
     ["GRID 3: CD = 8 turns its displacement frame"], {}),
    ("no polar inertia", on_all(R, "MAT1", lambda c: ["MAT1", 20, d.E, d.G, None, 0.0]),
     ["PBAR 10 (on CBAR 1): no polar inertia"], {}),
    ("a grid joined to nothing", R + [d.grid(7, 0.0, 9.0, 0.0)], ["GRID 7 is joined to "
                                                                   "nothing"], {}),
    # ---------------------------------------------------------------- the propeller
    ("hub not in the model", R, ["hub GRID 999 (installation 1) is not in the file"],
     {"hubs": (999,)}),
    ("hub with two CONM2", R + [d.conm2(303, 101, 1.0)],
     ["hub GRID 101 (installation 1) carries 2 CONM2 (CONM2 301, CONM2 303)"], {}),
    ("mass off the shaft", swap(R, "GRID", 102, d.grid(102, d.NACELLE_X, 2.0, d.STICK_Z - 0.3)),
     ["CONM2 302 on GRID 102: its mass lies 0.3 m off (in z)"], {}),
    ("products of inertia of a mass", swap(R, "CONM2", 302, d.conm2(302, 102, 20.0, i21=0.1)),
     ["CONM2 302: products of inertia"], {}),
    ("roll inertia of a nacelle mass", swap(R, "CONM2", 302, d.conm2(302, 102, 20.0, i11=0.3)),
     ["CONM2 302: I11", "does not roll"], {}),
    ("a mass on the wing", R + [d.conm2(310, 3, 4.0)],
     ["CONM2 310 on wing GRID 3: a point mass on the wing outside every propeller"], {}),
    ("a nacelle without its hub", R + [d.grid(120, -0.5, 1.0, d.STICK_Z),
                                       d.conm2(320, 120, 5.0), ["RBE2", 260, 3, "123456", 120]],
     ["CONM2 320 on GRID 120 belongs to no propeller", "--hubs"], {}),
    ("one hinge only", swap(swap(F, "RBE2", 214, ["RBE2", 214, 113, "123456", 114]), "CELAS2",
                            222, None),
     ["hub GRID 101 (installation 1): its mount has the hinge RBE2 212"], {}),
    ("two pitch hinges", swap(swap(F, "RBE2", 214, ["RBE2", 214, 113, "12346", 114]), "CELAS2",
                              222, ["CELAS2", 222, 6e4, 113, 5, 114, 5, 0.04]),
     ["both hinges", "pitch"], {}),
    ("a hinge without its spring", swap(F, "CELAS2", 221, None),
     ["RBE2 212 leaves pitch (R_y) free between GRID 111 and GRID 112 but no CELAS2"], {}),
    ("a spring on no hinge", R + [["CELAS2", 290, 1e4, 101, 5, 102, 5]],
     ["CELAS2 290 is no hinge's spring"], {}),
    ("a mount damping out of range", swap(F, "CELAS2", 221, ["CELAS2", 221, 5e4, 111, 5, 112,
                                                              5, 2.5]),
     ["CELAS2 221: GE = 2.5 is outside the valid range [0, 2]"], {}),
    ("a grounded spring", R + [["CELAS2", 291, 1e4, 101, 5]], ["CELAS2 291 is grounded"], {}),
    ("a rigid element with free translations", swap(R, "RBE2", 201, ["RBE2", 201, 5, "456",
                                                                     101, 102]),
     ["RBE2 201 leaves component(s) 123 of GRID 101 free"], {}),
    ("a mass between the hinges", F + [d.conm2(330, 113, 2.0, x=0.0)],
     ["CONM2 330 on GRID 113 is part of hub GRID 101 (installation 1)'s mount", "between the "
      "hinges"], {}),
]


@pytest.mark.parametrize("cards, fragments, kw", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_refused_in_one_line_naming_the_card(tmp_path, base, cards, fragments, kw):
    kw = dict(kw)
    hubs = kw.pop("hubs", (101,))
    message = refused(tmp_path, d.text(cards, **kw), base, hubs=hubs)
    for fragment in fragments:
        assert fragment in message, (fragment, message)


def test_a_free_field_line_longer_than_nine_fields(tmp_path, base):
    """pyNastran would drop the fields beyond the ninth (a CONM2's inertia) unsaid."""
    text = d.text(R).replace("CONM2,302,102,,20.0,0.0,0.0,0.0,\n,0.0,", "CONM2,302,102,,20.0,"
                             "0.0,0.0,0.0,,0.0,")
    assert "CONM2,302,102,,20.0,0.0,0.0,0.0,,0.0,0.0,1.5" in text
    message = refused(tmp_path, text, base)
    assert "(CONM2 302): 14 free fields on one line, more than nine" in message


def test_units_unstated_or_unknown(tmp_path, base):
    text = d.text(R)
    assert "units not stated" in refused(tmp_path, text, base, units=None)
    assert "--units si|mm-t-s|in-lbf-s" in refused(tmp_path, text, base, units=None)
    assert "units = 'imperial' is invalid" in refused(tmp_path, text, base, units="imperial")


def test_mixed_units_are_refused_naming_the_card(tmp_path, base):
    """A deck in mm-t-s read as SI: the material's wave speed is no solid's."""
    message = refused(tmp_path, d.text(R, "mm-t-s"), base, units="si")
    assert "MAT1 20" in message and "mixed" in message
    # RHO = 0 (the mass all NSM: no wave speed to check): the rigidity is no wing's
    cards = d.beams(swap(R, "PBAR", 10, d.pbeam(nsi=0.5)))
    cards = on_all(cards, "MAT1", lambda c: ["MAT1", 20, d.Q(d.E, "modulus"),
                                             d.Q(d.G, "modulus"), None, 0.0])
    message = refused(tmp_path, d.text(cards, "mm-t-s"), base, units="si")
    assert "CBEAM 1" in message and "outside the valid range" in message
    assert "read in si units" in message and "not mixed" in message


def test_hubs_must_match_the_base(tmp_path, base):
    text = d.text(R)
    assert "0 hub grid(s) for the base model's 1 installation(s)" in refused(
        tmp_path, text, base, hubs=())
    two = registry.case_model("two-propeller")
    assert "hub GRID 101 is given twice" in refused(tmp_path, text, two, hubs=(101, 101))


def test_a_base_is_needed(tmp_path, base):
    path = tmp_path / "wing.bdf"
    path.write_text(d.text(R))
    with pytest.raises(InputError, match="holds the structure only: give the base model"):
        read_bdf(path, units="si", hubs=(101,))


def test_a_base_with_per_element_values_of_another_mesh(tmp_path, base):
    wing = dataclasses.replace(base.wing, elastic_axis=tuple([0.5] * base.wing.element_count))
    path = tmp_path / "wing.bdf"
    path.write_text(d.text(R))
    with pytest.raises(InputError, match="elastic_axis has 25 values.* the BDF's stick has 4"):
        read_bdf(path, units="si", base=base.with_(wing=wing), hubs=(101,), base_name="b.toml")


def test_not_a_text_file(tmp_path, base):
    path = tmp_path / "wing.bdf"
    path.write_bytes(b"\x00\x01\xff\xfe binary")
    with pytest.raises(InputError, match="not UTF-8"):
        read_bdf(path, units="si", base=base, hubs=(101,))
