"""What each reproduced number is compared with (issue 11, item 8 and friction 9): the thesis's
own value, or an independent literature value; marked in the table and the JSON."""
import json

from propwhirl import documents
from propwhirl.reproduce import harness as reproduce

REFS = {r.id: r for r in reproduce.load_references()}
LITERATURE = "t7.3/divergence_speed"


def _records():
    """Three records without computing anything: a literature check, a thesis check, an id
    not computed."""
    return [reproduce.compare(REFS[LITERATURE], 37.149),
            reproduce.compare(REFS["t7.2/first_torsion"], None),
            reproduce.compare(REFS["t4.1/beta25/CZ_theta"], -0.3283)]


def test_the_literature_checked_ids_are_those_the_reference_file_marks():
    marked = {r.id for r in REFS.values() if r.check == "literature"}
    assert marked == {LITERATURE}
    recs = {r.id: r for r in (reproduce.compare(ref, None) for ref in REFS.values())}
    assert {i for i, r in recs.items() if r.literature_checked} == marked
    lit = recs[LITERATURE]
    assert (lit.reference, lit.target, lit.thesis) == ("literature", 37.15, 38.37)
    assert "closed-form" in lit.reference_note
    # t4.1 prints a literature value too, but is held to the thesis's: not literature-checked
    assert REFS["t4.1/beta25/CZ_theta"].literature is not None
    assert recs["t4.1/beta25/CZ_theta"].reference == "thesis"


def test_the_table_says_what_each_difference_is_against():
    table = reproduce.format_table(_records())
    lines = table.splitlines()
    assert "compared with" in lines[0]
    row = {ln.split()[0]: ln for ln in lines[2:5]}
    assert "  literature 37.15 " in row[LITERATURE] and " 38.37 " in row[LITERATURE]
    assert "  thesis " in row["t4.1/beta25/CZ_theta"] and "  thesis " in row["t7.2/first_torsion"]
    note = next(ln for ln in lines if ln.startswith(f"  {LITERATURE}: "))
    assert "literature 37.15 m/s (Table 7.3), not the thesis's 38.37" in note
    assert "closed-form strip-theory divergence speed" in note
    assert "marked literature (1 id)" in table
    assert table.splitlines()[-1].endswith(documents.cite("validation"))
    assert "docs/validation.md" not in table.replace(str(documents.path("validation")), "")


def test_the_json_says_what_each_difference_is_against():
    data = json.loads(reproduce.to_json(_records()))["records"]
    by_id = {d["id"]: d for d in data}
    assert by_id[LITERATURE]["literature_checked"] is True
    assert by_id[LITERATURE]["reference"] == "literature"
    assert by_id[LITERATURE]["reference_value"] == 37.15
    assert by_id[LITERATURE]["rel_error"] == (37.149 - 37.15) / 37.15
    cz = by_id["t4.1/beta25/CZ_theta"]
    assert (cz["literature_checked"], cz["reference"], cz["reference_value"]) == (False, "thesis", -0.328)
    assert list(by_id[LITERATURE]) == list(reproduce.JSON_FIELDS)
