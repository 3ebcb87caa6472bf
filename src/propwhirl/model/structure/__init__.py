"""The structure: the beam wing and its mesh, the assembly of its generated element matrices,
and structures given by their normal modes (issue 38: the model's rooms by their physics)."""
