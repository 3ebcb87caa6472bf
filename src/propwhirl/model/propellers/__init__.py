"""The flexibly mounted propeller: its inertia, mounts and operation, the Houbolt–Reed
aerodynamic derivatives and their exact blade derivatives (issue 38: the model's rooms by their
physics; an installed propeller's block on the wing is
:mod:`propwhirl.model.propeller_blocks`)."""
