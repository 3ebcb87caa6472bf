"""The ``certify`` command of the command line (:mod:`propwhirl.app.cli`): a whirl-flutter
clearance campaign (:mod:`propwhirl.studies.campaign`, the file format ``docs/campaign.md``).

    propwhirl certify CAMPAIGN.toml --out REPORT/ [--processes N | --scheduler ADDRESS]
                      [--resume] [--quiet]

Runs every case over its envelope, writes ``REPORT/campaign.json`` (the
:class:`~propwhirl.studies.campaign_result.CampaignResult`) and ``REPORT/campaign.csv`` (every number,
one line per case and altitude) and prints the summary table.  Exit code 0 when every case
clears, 1 when one does not, 2 for bad input (nothing is analysed).  While it runs, the
finished analyses are kept in ``REPORT/campaign.json.partial``; ``--resume`` continues from it.
"""
from __future__ import annotations

import argparse
from pathlib import Path

from propwhirl import fileio
from propwhirl.app import execution_options
from propwhirl.app.cli_common import echo
from propwhirl.validate import InputError

#: The files written in the --out folder.
JSON_NAME = "campaign.json"
CSV_NAME = "campaign.csv"


def _certify(args: argparse.Namespace) -> int:
    from propwhirl.io.campaign_files import load_campaign
    from propwhirl.studies.campaign import from_spec, run_campaign

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError(f"--out {args.out}: is a file, must be a folder (it gets "
                         f"{JSON_NAME} and {CSV_NAME})")
    options = execution_options.run_options(args)
    campaign = from_spec(load_campaign(args.campaign))   # every check before any analysis
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {args.out}: cannot make the folder: {fileio.reason(exc)}") from None
    json_path, csv_path = out / JSON_NAME, out / CSV_NAME
    cp = execution_options.checkpoint(args, json_path)
    result = run_campaign(campaign, **options, checkpoint=cp)
    result.save(json_path)
    result.to_csv(csv_path)
    execution_options.finish(cp)
    echo(result.format())
    print(f"wrote {json_path} and {csv_path}")
    execution_options.report_failures([r.error for r in result.rows], "analyses")
    return 0 if result.cleared else 1


def add_commands(sub) -> None:
    """Register ``certify`` on the CLI's subparsers."""
    p = sub.add_parser("certify", help="whirl-flutter clearance campaign: every case over its "
                       "envelope (exit code 0 all cleared, 1 not, 2 bad input)",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("campaign", metavar="CAMPAIGN", help="campaign file (TOML, docs/campaign.md)")
    p.add_argument("--out", required=True, metavar="DIR", help=f"report folder: {JSON_NAME} and "
                   f"{CSV_NAME} (made if missing)")
    execution_options.add(p)
    p.set_defaults(func=_certify)
