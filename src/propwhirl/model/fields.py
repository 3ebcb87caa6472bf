"""Model-file metadata carried by the fields of the model dataclasses.

Every field of a model dataclass declares, with ``metadata=spec(...)``, how a model file holds
it: the key (with its SI unit suffix, e.g. ``EI_N_m2``), the unit, a one-line description and,
when the field has a Python default, what kind of default it is::

    EI: Spanwise = field(metadata=spec("EI_N_m2", "N m^2", "bending rigidity", form="spanwise"))
    elastic_axis: Spanwise = field(default=0.5, metadata=spec(
        "elastic_axis_chord", "chord", "elastic-axis position", form="spanwise",
        default="physical"))

:mod:`propwhirl.io.schema` turns these declarations into the reader, the writer, their error
messages and ``docs/model-file.md``; the default *values* stay those of the dataclasses.  This
module only declares and imports nothing of propwhirl, so the model packages can use it
without depending on :mod:`propwhirl.io`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, Mapping

#: Key of the :class:`FieldSpec` in a dataclass field's ``metadata``.
META_KEY = "propwhirl.model_file"

#: How a value is written.  Forms left as ``None`` in :func:`spec` follow from the field's type
#: hint: bool → "boolean", int → "integer", float → "number", str or Literal → "string",
#: a dataclass → "table", tuple[dataclass, ...] → "tables".
Form = Literal[
    "number", "integer", "string", "boolean",
    "spanwise",          # a number or one number per wing element (never a function)
    "number_or_string",  # a number or one of the Literal strings of the type hint
    "numbers",           # a fixed-length list of numbers (`length`)
    "split",             # a tuple of numbers written as separate keys (`key`, `unit` are tuples)
    "table",             # a nested dataclass: a sub-table
    "tables",            # a tuple of dataclasses: a list of tables
    "flat",              # a nested dataclass whose keys sit in the enclosing table
    "mapping",           # a dict with the fixed entries `entries`
    "distribution",      # a number (`number_key`) or a radial table (name, eta, `value_key`)
    "derivatives",       # an aerodynamic derivative source: a table chosen by its `source` key
    "reference",         # a Propeller, written as the key of a [propellers.KEY] table
    "installations",     # the installed propellers of a wing: a list of tables
    "unsaved",           # not in the file: only the Python default can be saved (`doc` says why)
    "derived",           # not in the file: computed by the class from the other fields
]

#: What a Python default stands for (issue 9 audits the "physical" ones):
#: "physical" — a value of the aircraft or the air (a position, a stiffness, an angle, ...);
#: "setting"  — a modelling or numerical choice, a switch or a label;
#: "none"     — ``None`` (or empty): not given, the field's description says what then holds.
DefaultKind = Literal["physical", "setting", "none"]


@dataclass(frozen=True)
class Entry:
    """One fixed entry of a "mapping" field: Python name, file key, unit, description."""

    name: str
    key: str
    unit: str = ""
    doc: str = ""


@dataclass(frozen=True)
class FieldSpec:
    """How one dataclass field appears in a model file (see :func:`spec`)."""

    key: str | tuple[str, ...] | None
    unit: str | tuple[str, ...] = ""
    doc: str = ""
    default: DefaultKind | None = None
    form: Form | None = None
    section: str | None = None
    length: int | None = None
    number_key: str | None = None
    value_key: str | None = None
    entries: tuple[Entry, ...] = ()
    file_required: bool = False
    file_default: Any = None


def spec(key: str | tuple[str, ...] | None, unit: str | tuple[str, ...] = "", doc: str = "", *,
         default: DefaultKind | None = None, form: Form | None = None, section: str | None = None,
         length: int | None = None, number_key: str | None = None, value_key: str | None = None,
         entries: tuple[Entry, ...] = (), file_required: bool = False,
         file_default: Any = None) -> Mapping[str, FieldSpec]:
    """Metadata for ``dataclasses.field(metadata=...)`` declaring a model-file field.

    Parameters
    ----------
    key : the key in the model file, SI unit suffix included (``"semi_span_m"``); a tuple of
        keys for form "split"; None for fields that are not saved (forms "unsaved", "derived").
    unit : SI unit as written in the documentation (``"N m^2"``, ``"chord"`` for fractions of
        the local chord, ``""`` dimensionless); must agree with the key's suffix.
    doc : one line for the documentation and error messages.
    default : kind of the dataclass default ("physical", "setting" or "none"); required for
        a field with a default, forbidden for one without (checked by propwhirl.io.schema).
    form : how the value is written (see :data:`Form`); None: from the type hint.
    section : sub-table of the enclosing table that holds the key (``"switches"``).
    length : number of entries of a "numbers" list.
    number_key, value_key : "distribution": key of the number alternative and of the values
        column of the table.
    entries : "mapping": the allowed entries.
    file_required : the file must give the field although the dataclass has a default.
    file_default : value used when the file omits a field that the dataclass requires.
    """
    return {META_KEY: FieldSpec(key, unit, doc, default, form, section, length, number_key,
                                value_key, tuple(entries), file_required, file_default)}
