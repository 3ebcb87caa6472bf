"""Design studies: parametric sweeps of the critical speed."""
