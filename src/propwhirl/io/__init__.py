"""Files: model files (TOML, :mod:`.model_files` with the schema of :mod:`.schema`), modal-model
files (modes as .npz beside a TOML description, :mod:`.modal_files`), NASTRAN bulk data in and
out (:mod:`.nastran_read` — needs the ``nastran`` extra in an environment of its own —,
:mod:`.nastran_write`), NASTRAN modes in (an OP2, :mod:`.nastran_op2`: the same extra) and
result files (V-g-f CSV, :mod:`.results`)."""
from propwhirl.io.modal_files import load_modal_model, save_modal_model, write_modes
from propwhirl.io.model_files import dumps, load_model, loads, save_model
from propwhirl.io.nastran_op2 import read_op2
from propwhirl.io.nastran_read import read_bdf
from propwhirl.io.nastran_write import write_bdf
from propwhirl.io.results import VGF_COLUMNS, read_vgf_csv, write_vgf_csv
from propwhirl.io.schema import FORMAT, FORMAT_VERSION, UNIT_SUFFIXES, model_fields  # noqa: F401

__all__ = ["dumps", "load_modal_model", "load_model", "loads", "model_fields", "read_bdf",
           "read_op2", "read_vgf_csv", "save_modal_model", "save_model", "write_bdf",
           "write_modes", "write_vgf_csv"]
