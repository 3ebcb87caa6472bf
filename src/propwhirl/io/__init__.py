"""Files: model files (TOML) and result files (JSON, CSV)."""
from propwhirl.io.files import (dumps, load_model, loads, model_fields, read_vgf_csv, save_model,
                                write_vgf_csv)

__all__ = ["dumps", "load_model", "loads", "model_fields", "read_vgf_csv", "save_model",
           "write_vgf_csv"]
