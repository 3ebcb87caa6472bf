"""The wing's aerodynamics: Theodorsen's function and the exact strip matrices of the p-k,
the doublet lattice (panels, AICs and their cache, Roger's fits, the modal Roger state space),
and what the aerodynamic methods refuse or warn about (issue 38: the model's rooms by their
physics)."""
