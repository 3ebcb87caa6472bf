"""The reproduction of the thesis's numbers (ids and tolerances from thesis_values.toml)."""
from propwhirl.reproduce.harness import (Record, Reference, compare, format_table, load_references,
                                         register, registered_cases, run, to_json)

__all__ = ["Record", "Reference", "compare", "format_table", "load_references", "register",
           "registered_cases", "run", "to_json"]
