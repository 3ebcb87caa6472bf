"""``python -m propwhirl.io > docs/model-file.md``: print the model-file documentation."""
import sys

from propwhirl.io.schema import markdown

sys.stdout.write(markdown())
