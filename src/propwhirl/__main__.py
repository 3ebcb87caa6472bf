"""`python -m propwhirl` — the command-line interface (see propwhirl.app.cli)."""
import sys

from propwhirl.app.cli import main

sys.exit(main())
