"""`python -m propwhirl` — the command-line interface (see propwhirl.app.cli)."""
import os
import sys

try:
    from propwhirl.app.cli import EXIT_INTERRUPTED, main
except KeyboardInterrupt:     # Ctrl-C while the command line loads: the same one line as later
    print("propwhirl: interrupted", file=sys.stderr, flush=True)
    os._exit(130)

code = main()
if code == EXIT_INTERRUPTED:
    # Ctrl-C, handled by main (one line, no partial output). When the interrupt landed inside
    # the import machinery (the models load while the command line is built), CPython marks it
    # unhandled and would end the process by SIGINT instead of the code main returned (seen:
    # one run in five); leave with the code itself, the streams flushed.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
sys.exit(code)
