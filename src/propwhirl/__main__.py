"""`python -m propwhirl` — the command-line interface (see propwhirl.cli)."""
import sys

from propwhirl.cli import main

sys.exit(main())
