"""The structure: the beam wing, its spanwise mesh and the assembly of its generated element
matrices (issue 38: the model's rooms by their physics; a structure given by its normal modes
is :mod:`propwhirl.model.modal_structure`)."""
