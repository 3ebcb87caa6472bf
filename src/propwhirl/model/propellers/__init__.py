"""The flexibly mounted propeller: its inertia, mounts and operation, the Houbolt–Reed
aerodynamic derivatives and their exact blade derivatives, the physics of one installed
propeller's block (issue 38: the model's rooms by their physics)."""
