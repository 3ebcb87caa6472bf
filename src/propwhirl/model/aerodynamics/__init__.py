"""The wing's aerodynamics: Theodorsen's function, the doublet lattice (panels, AICs and their
cache, Roger's fits) and what the aerodynamic methods refuse or warn about (issue 38: the
model's rooms by their physics; their assembly with a structure is model/'s: the p-k's
:mod:`propwhirl.model.frequency_domain`, the modal Roger state space
:mod:`propwhirl.model.dlm_modal`)."""
