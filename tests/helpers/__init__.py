"""Shared test helpers: independent oracles and fixtures (not part of the package)."""
