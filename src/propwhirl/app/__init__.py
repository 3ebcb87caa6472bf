"""The applications: command line, the main job, plots."""
