"""Symbolic derivations of propwhirl's equations of motion (SymPy; needed only by `make generate`).

One module per model; each defines ``derive() -> derivations.common.Derivation``.  The generator
(`python -m derivations.generate`) discovers them and writes one NumPy module each to
`generated/`.
"""
