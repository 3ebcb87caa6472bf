"""The ``certify`` command of the command line (:mod:`propwhirl.app.cli`): a whirl-flutter
clearance campaign (:mod:`propwhirl.studies.campaign`, the file format ``docs/campaign.md``).

    propwhirl certify CAMPAIGN.toml --out REPORT/ [--processes N | --scheduler ADDRESS]
                      [--resume] [--quiet] [--pdf | --no-pdf | --no-report]

Runs every case over its envelope, writes ``REPORT/campaign.json`` (the
:class:`~propwhirl.studies.campaign_result.CampaignResult`), ``REPORT/campaign.csv`` (every number,
one line per case and altitude), ``REPORT/report.html`` (the report, :mod:`propwhirl.app.report`)
and ``REPORT/report.pdf`` (printed by headless Chromium: by default when one is found,
``--pdf`` requires it, ``--no-pdf`` leaves it out; ``--no-report`` writes neither; a print that
fails is a note on stderr, the exit code stays the verdict's) and prints the summary table.  Exit code 0 when every case
clears, 1 when one does not, 2 for bad input (nothing is analysed).  While it runs, the
finished analyses are kept in ``REPORT/campaign.json.partial``; ``--resume`` continues from it.
"""
from __future__ import annotations

#: What ``propwhirl certify --help`` says first (plain text: no docstring markup).
DESCRIPTION = ("Run a flutter, whirl-flutter and divergence clearance campaign (CAMPAIGN, a "
               "TOML file: docs/campaign.md) over its flight envelope and write into --out "
               "campaign.json, campaign.csv (every number), report.html and report.pdf (the "
               "report). Exit code 0 when every case clears, 1 when one does not, 2 for bad "
               "input (nothing analysed).")

import argparse
from pathlib import Path

from propwhirl import fileio
from propwhirl.app import browser, execution_options
from propwhirl.app.cli_common import check_runs, echo, print_notes
from propwhirl.app.report import HTML_NAME, PDF_NAME, write_report
from propwhirl.validate import InputError

#: The files written in the --out folder.
JSON_NAME = "campaign.json"
CSV_NAME = "campaign.csv"


def _ask_the_model(campaign: str) -> None:
    """The campaign's model asked, before the campaign is read, whether it runs a campaign
    (the model contract, :func:`~propwhirl.app.cli_common.check_runs`): its reason in one
    line.  Anything that keeps the model from being read here (a bad campaign file, no such
    model) is left to :func:`~propwhirl.io.campaign_files.load_campaign`, which says it."""
    import tomllib

    from propwhirl import io  # lazy: model files
    from propwhirl.io.modal_files import is_modal_file  # lazy: model files

    try:
        text = fileio.read_text(campaign, "campaign file", empty_ok=True,
                                limit=fileio.MAX_TOML_BYTES)
        key = tomllib.loads(text).get("model")
        if not isinstance(key, str):
            return
        path = Path(key) if Path(key).is_absolute() else Path(campaign).parent / key
        model = io.load_modal_model(path) if is_modal_file(path) else io.load_model(path)
    except (InputError, tomllib.TOMLDecodeError, OSError, ValueError):
        return
    check_runs(model, "certify", campaign)


def _certify(args: argparse.Namespace) -> int:
    from propwhirl.io.campaign_files import load_campaign  # lazy: campaign files
    from propwhirl.studies.campaign import from_spec, run_campaign  # lazy: studies

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError(f"--out {args.out}: is a file, must be a folder (it gets "
                         f"{JSON_NAME} and {CSV_NAME})")
    options = execution_options.run_options(args)
    if args.pdf is True and browser.find_chromium() is None:
        raise InputError(f"--pdf: no Chromium found to print {PDF_NAME}: {browser.INSTALL_HINT}"
                         " (or give --no-pdf)")
    _ask_the_model(args.campaign)
    spec = load_campaign(args.campaign)
    json_path, csv_path = out / JSON_NAME, out / CSV_NAME
    _check_outputs(args, out, spec.model_path)
    campaign = from_spec(spec)                           # every check before any analysis
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {args.out}: cannot make the folder: {fileio.reason(exc)}") from None
    cp = execution_options.checkpoint(args, json_path)
    result = run_campaign(campaign, **options, checkpoint=cp)
    result.save(json_path)
    result.to_csv(csv_path)
    execution_options.finish(cp)
    notes: list[str] = []
    written = [] if args.pdf == "none" else write_report(
        result, out, campaign_file=args.campaign, model_file=spec.model_path,
        model=campaign.model, pdf=args.pdf, notes=notes)
    echo(result.format())
    print_notes(notes)
    print(f"wrote {', '.join(map(str, [json_path, csv_path, *written]))}")
    execution_options.report_failures([r.error for r in result.rows], "analyses")
    return 0 if result.cleared else 1


def _check_outputs(args: argparse.Namespace, out: Path, model_path: str) -> None:
    """Before any analysis: every file certify writes in `out` — campaign.json, its
    partial-results file, campaign.csv and (unless --no-report) report.html and report.pdf —
    is a regular file or a new path (not a device, a FIFO or a socket:
    :func:`propwhirl.fileio.check_output`) and none is the campaign file or its model file
    (:func:`propwhirl.fileio.check_apart`: resolved, symbolic links followed)."""
    names = [JSON_NAME, JSON_NAME + execution_options.PARTIAL_SUFFIX, CSV_NAME]
    if args.pdf != "none":
        names += [HTML_NAME, PDF_NAME]
    outputs = [(f"--out {args.out}:", out / name) for name in names]
    for label, path in outputs:
        fileio.check_output(path, label.rstrip(":"))
    fileio.check_apart(outputs, [(f"the campaign file CAMPAIGN {args.campaign}", args.campaign),
                                 (f"the model file of the campaign (model = {model_path!r})",
                                  model_path)])


def add_commands(sub) -> None:
    """Register ``certify`` on the CLI's subparsers."""
    p = sub.add_parser("certify", help="whirl-flutter clearance campaign: every case over its "
                       "envelope (exit code 0 all cleared, 1 not, 2 bad input)",
                       description=DESCRIPTION)
    p.add_argument("campaign", metavar="CAMPAIGN", help="campaign file (TOML, docs/campaign.md)")
    p.add_argument("--out", required=True, metavar="DIR", help=f"report folder: {JSON_NAME}, "
                   f"{CSV_NAME}, {HTML_NAME} and {PDF_NAME} (made if missing)")
    pdf = p.add_mutually_exclusive_group()
    pdf.add_argument("--pdf", dest="pdf", action="store_true", default=None,
                     help=f"print {PDF_NAME} with headless Chromium (an error when none is "
                     "found; default: printed when Chromium is found)")
    pdf.add_argument("--no-pdf", dest="pdf", action="store_false",
                     help=f"write no {PDF_NAME}")
    pdf.add_argument("--no-report", dest="pdf", action="store_const", const="none",
                     help=f"write neither {HTML_NAME} nor {PDF_NAME} (only the numbers)")
    execution_options.add(p)
    p.set_defaults(func=_certify)
