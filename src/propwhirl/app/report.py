"""The certification report of a campaign (issue 24): one self-contained HTML page (and, printed
by headless Chromium, a PDF of it: :mod:`propwhirl.app.browser`).

The page (:func:`report_html`) holds, in order:

* the campaign: its name, the verdict, the campaign file and the model file with their SHA-256
  hashes, the regulation and its speed factor, the damping requirement, the convention, the
  number of analyses, propwhirl's version and the date;
* the model: its summary (name, semi-span, elements, each propeller's station, operation, rpm
  and rotation) and its mesh (a figure);
* the summary table: one row per (case, altitude) — V_D, the required speed, V_crit, the margin
  in m/s and %, the least g, dζ/dV at the required speed, the critical instability and the
  verdict (pass / FAIL);
* per case: its transformation, its margin at every altitude, and at its least-margin altitude
  the V-g-f (V_D, the required speed and the damping requirement drawn) and the critical mode's
  shape.

Figures are PNG images inside the page (``data:`` URIs: the page is one file, nothing is
fetched); every number has its unit in its column's heading or beside it; every string from
the campaign or the model file is escaped (:func:`html.escape`).  Drawn from the
:class:`~propwhirl.studies.campaign_result.CampaignResult` alone (``campaign.json``), so a report
can be made again without analysing; the model's summary and mesh need the model.
"""
from __future__ import annotations

import base64
import datetime
import html
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import propwhirl
from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.app import browser
from propwhirl.studies.campaign_result import CampaignResult

#: The report's file names in the output folder.
HTML_NAME = "report.html"
PDF_NAME = "report.pdf"
#: Resolution of the embedded figures [dots per inch].
FIGURE_DPI = 72

_CSS = """
body { font-family: "DejaVu Sans", Arial, sans-serif; font-size: 10.5pt; color: #111;
       max-width: 1000px; margin: 1.5em auto; padding: 0 1em; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; } h2 { font-size: 1.3em; margin-top: 1.6em;
border-bottom: 1px solid #999; } h3 { font-size: 1.1em; }
table { border-collapse: collapse; margin: 0.6em 0; } th, td { border: 1px solid #bbb;
padding: 2px 6px; } th { background: #eee; text-align: left; } td.num { text-align: right;
font-variant-numeric: tabular-nums; white-space: nowrap; }
table.summary { font-size: 9pt; }
td.pass, span.pass, p.pass { color: #0a6d1d; font-weight: bold; }
td.fail, span.fail, p.fail { color: #b00000; font-weight: bold; }
tr.fail td { background: #fdecec; }
.verdict { font-size: 1.3em; padding: 0.3em 0.6em; border: 2px solid; display: inline-block; }
code, .hash { font-family: "DejaVu Sans Mono", monospace; font-size: 0.9em;
word-break: break-all; }
img { max-width: 100%; height: auto; display: block; margin: 0.5em 0; }
section.case { page-break-before: always; break-before: page; }
.note { color: #444; font-size: 0.9em; }
figure { margin: 0; break-inside: avoid; page-break-inside: avoid; }
@page { size: A4; margin: 12mm; }
@media print { figure img { max-height: 100mm; width: auto; max-width: 100%; }
               body { max-width: none; margin: 0; } }
"""


def sha256_file(path: str | Path, what: str = "file") -> str:
    """The SHA-256 of a file's bytes (hex): a regular file of at most
    :data:`propwhirl.fileio.MAX_READ_BYTES` bytes (:func:`propwhirl.fileio.sha256_file`),
    InputError naming the file (a `what`) otherwise."""
    return fileio.sha256_file(path, what)


def e(x: Any) -> str:
    """`x` as escaped HTML text (quotes too)."""
    return html.escape(str(x), quote=True)


def _num(x: float | None, fmt: str, unit: str = "") -> str:
    if x is None:
        return "–"
    return format(x, fmt) + (f" {unit}" if unit else "")


def _img(png: bytes, alt: str) -> str:
    return (f'<img alt="{e(alt)}" src="data:image/png;base64,'
            f'{base64.b64encode(png).decode("ascii")}">')


def _figure(fig: Any) -> bytes:
    from propwhirl.app.plots.campaign_plot import png_bytes  # lazy: figures

    try:
        return png_bytes(fig, FIGURE_DPI)
    finally:
        fig.clear()


def _table(head: Sequence[str], rows: Sequence[Sequence[str]], cls: str = "",
           row_attrs: Sequence[str] | None = None) -> str:
    """A table of already-escaped cells; `head` plain text (escaped here)."""
    out = [f'<table class="{cls}">' if cls else "<table>"]
    if any(head):
        out.append("<thead><tr>" + "".join(f"<th>{e(h)}</th>" for h in head) + "</tr></thead>")
    out.append("<tbody>")
    for i, r in enumerate(rows):
        attrs = "" if row_attrs is None else " " + row_attrs[i]
        out.append(f"<tr{attrs}>" + "".join(r) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def _td(x: str, cls: str = "") -> str:
    return f'<td class="{cls}">{x}</td>' if cls else f"<td>{x}</td>"


def _critical(r: Any) -> str:
    if r.error:
        return "analysis failed: " + r.error
    if r.kind == "none":
        return "none up to " + _num(r.analysed_to, ".1f", "m/s")
    out = f"{r.kind} {r.event} of {r.mode}"
    if r.kind == "flutter" and r.frequency_hz is not None:
        out += f" at {r.frequency_hz:.2f} Hz"
    if r.whirl:
        out += f", {r.whirl} whirl"
    return out


def _envelope(rows: Sequence[Any]) -> str:
    """'V_D 100 m/s EAS at 0, 2438.4, 5000 m' (each altitude's V_D when they differ; M_D-limited
    points named)."""
    points: dict[float, Any] = {}
    for r in rows:
        points.setdefault(r.altitude_m, r)
    alts = ", ".join(f"{h:g}" for h in points)
    given = {(r.V_D_given, r.airspeed) for r in points.values()}
    if len(given) == 1:
        (vd, air), = given
        text = f"V_D {vd:g} m/s {air} at {alts} m"
    else:
        text = "V_D " + ", ".join(f"{r.V_D_given:g} m/s {r.airspeed} at {h:g} m"
                                  for h, r in points.items())
    limited = [f"{h:g}" for h, r in points.items() if r.mach_limited]
    return text + (f"; limited by M_D at {', '.join(limited)} m" if limited else "")


#: The summary table's columns: (heading with its unit, the cell of a row).
SUMMARY_COLUMNS = (
    ("case", lambda r: _td(e(r.case))),
    ("altitude [m]", lambda r: _td(_num(r.altitude_m, ".0f"), "num")),
    ("V_D (TAS) [m/s]", lambda r: _td(_num(r.V_D, ".2f"), "num")),
    ("rule", lambda r: _td(e(r.rule or "–"))),
    ("V_required [m/s]", lambda r: _td(_num(r.V_required, ".2f"), "num")),
    ("V_crit [m/s]", lambda r: _td(_num(r.critical_speed, ".2f"), "num")),
    ("margin [m/s]", lambda r: _td(_num(r.margin_m_per_s, "+.2f"), "num")),
    ("margin [%]", lambda r: _td(_num(r.margin_percent, "+.2f"), "num")),
    ("least g = 2ζ to V_req [-]", lambda r: _td(_num(r.least_g, ".4f"), "num")),
    ("dζ/dV at V_req [s/m]", lambda r: _td(_num(r.dzeta_dV_at_required, "+.2e"), "num")),
    ("critical instability", lambda r: _td(e(_critical(r)))),
    ("verdict", lambda r: _td("pass" if r.cleared else "FAIL", "pass" if r.cleared else "fail")),
)


def model_summary(model: Any) -> list[tuple[str, str]]:
    """(quantity with unit, value) pairs describing a propeller-wing model (escaped later)."""
    out = [("name", str(getattr(model, "name", "")))]
    wing = getattr(model, "wing", None)
    if wing is not None:
        for label, attr, fmt in (("semi-span [m]", "semi_span", ".4g"),
                                 ("elements", "element_count", "d"), ("nodes", "n_nodes", "d"),
                                 ("aerodynamics", "aero", "s")):
            x = getattr(wing, attr, None)
            if x is not None:
                out.append((label, format(x, fmt)))
    props = getattr(model, "propellers", ()) or ()
    out.append(("propellers", str(len(props))))
    for i, inst in enumerate(props, start=1):
        p = getattr(inst, "propeller", inst)
        y = getattr(inst, "y", None)
        bits = [] if y is None else [f"y = {float(y):.4g} m"]
        op = getattr(p, "operation", None)
        if op:
            bits.append(str(op))
        rpm = getattr(p, "rpm", None)
        if rpm is not None:
            bits.append(f"{float(rpm):.0f} rpm")
        rot = getattr(p, "rotation", None)
        if rot is not None:
            bits.append("counter-clockwise from the front" if int(rot) > 0 else
                        "clockwise from the front")
        out.append((f"propeller {i}", ", ".join(bits)))
    return out


def _mesh(model: Any) -> tuple[list[float], list[tuple[int, float | None]]] | None:
    wing = getattr(model, "wing", None)
    node_y = getattr(wing, "node_y", None)
    if node_y is None:
        return None
    props = [(i, None if getattr(inst, "y", None) is None else float(inst.y))
             for i, inst in enumerate(getattr(model, "propellers", ()) or (), start=1)]
    return [float(y) for y in node_y], props


def _check_arguments(result: Any, campaign_file: Any, model_file: Any, date: Any) -> None:
    """The report's arguments of the right types, else a one-line InputError naming one."""
    if not isinstance(result, CampaignResult):
        raise v.fail("result", result, "invalid: must be a CampaignResult (run_campaign's, or "
                     f"CampaignResult.load(path)), got {type(result).__name__}")
    for name, path in (("campaign_file", campaign_file), ("model_file", model_file)):
        if path is not None:
            v.file_path(name, path, f"the {name.replace('_', ' ')} (or None)")
    if date is not None and not isinstance(date, str):
        raise v.fail("date", date, f"invalid: must be a str or None, got {type(date).__name__}")


def report_html(result: Any, *, campaign_file: str | Path | None = None,
                model_file: str | Path | None = None, model: Any = None,
                date: str | None = None, figures: bool = True) -> str:
    """The report page of a :class:`~propwhirl.studies.campaign_result.CampaignResult` (module
    docstring).

    campaign_file, model_file: the files (named and hashed); model: the campaign's model (its
    summary and mesh; without it the section says so); date: the report's date (default
    today, UTC); figures: False leaves the figures out (the page says so; without matplotlib,
    the ``plots`` extra, they are left out too)."""
    _check_arguments(result, campaign_file, model_file, date)
    if figures:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            figures = False
    no_figures = ('<p class="note">Figures left out: install the plots extra (pip install '
                  'propwhirl[plots]) and write the report again.</p>')
    if figures:
        from propwhirl.app.plots import campaign_plot as cp  # lazy: figures
    date = date or datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    verdict = "CLEARED" if result.cleared else "NOT CLEARED"
    vcls = "pass" if result.cleared else "fail"
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             f"<title>{e(result.name)}: whirl-flutter clearance report</title>",
             f"<style>{_CSS}</style></head><body>",
             f"<h1>{e(result.name)}</h1>",
             "<p>Whirl-flutter clearance report of <code>propwhirl certify</code>.</p>",
             f'<p class="verdict {vcls}" id="verdict">{verdict}</p>']
    summaries = result.cases()
    n_ok = sum(s.cleared for s in summaries)
    g = ("none (damping reported, not judged)" if result.min_damping_g is None else
         f"g = 2ζ ≥ {result.min_damping_g:g} [-] for every oscillatory mode up to V_D")
    files = []
    for label, path in (("campaign file", campaign_file), ("model file", model_file)):
        if path is not None:
            files.append((label, f"<code>{e(path)}</code>"))
            files.append((f"{label} SHA-256",
                          f'<span class="hash">{sha256_file(path, label)}</span>'))
    rows = [("campaign", e(result.name)), ("model", e(result.model_name)), *files,
            ("envelope", e(_envelope(result.rows))),
            ("regulation", e(result.regulation)),
            ("required speed", f"{result.factor:g} × V_D (true airspeed)" + (
                "; failure cases (25.629(b)(2)): the greater of V_D (M_D) and the 1.15 V_C / "
                "M_C + 0.05 line, each row's rule" if any(r.rule.startswith("25.629(b)(2)")
                                                         for r in result.rows) else "")),
            ("damping requirement", e(g)), ("convention", e(result.convention)),
            ("cases cleared", f"{n_ok} of {len(summaries)}"),
            ("analyses", str(result.analyses)),
            ("software", f"propwhirl {e(propwhirl.__version__)}"), ("date", e(date))]
    parts += ["<h2>Campaign</h2>", _table(("", ""), [(f"<th>{k}</th>", _td(x)) for k, x in rows],
                                          "campaign")]
    parts.append("<h2>Model</h2>")
    if model is None:
        parts.append('<p class="note">The model was not given to the report: see the model '
                     "file above.</p>")
    else:
        parts.append(_table(("quantity", "value"),
                            [(_td(e(k)), _td(e(x))) for k, x in model_summary(model)], "model"))
        mesh = _mesh(model)
        if figures and mesh is not None:
            parts.append(_img(_figure(cp.mesh_plot(*mesh, title="mesh")),
                              f"mesh of {result.model_name}"))
    parts.append("<h2>Summary</h2>")
    parts.append('<p class="note">Every case at every altitude. Speeds are true airspeeds; '
                 "margin = V_crit − V_required and 100 (V_crit / V_required − 1); least g: of the "
                 "oscillatory modes up to the required speed. Every number of this report, and "
                 "every altitude's: campaign.json and campaign.csv beside it.</p>")
    parts.append(_table([h for h, _ in SUMMARY_COLUMNS],
                        [[cell(r) for _, cell in SUMMARY_COLUMNS] for r in result.rows],
                        "summary",
                        [f'class="point {"pass" if r.cleared else "fail"}" data-case="{e(r.case)}" '
                         f'data-altitude="{r.altitude_m!r}"' for r in result.rows]))
    for i, s in enumerate(summaries, start=1):
        r = s.worst
        rows_c = [x for x in result.rows if x.case == s.case]
        parts.append(f'<section class="case" id="case-{i}"><h2>Case {i}: {e(s.case)} — '
                     f'<span class="{"pass" if s.cleared else "fail"}">'
                     f'{"cleared" if s.cleared else "NOT cleared"}</span></h2>')
        parts.append(f"<p>Transformation: {e(r.description)}.</p>")
        margin = ("no counted instability up to " + _num(r.analysed_to, ".2f", "m/s")
                  if r.critical_speed is None else
                  f"V_crit = {r.critical_speed:.2f} m/s, required {r.V_required:.2f} m/s"
                  + (f" ({r.rule})" if r.rule else "") + ": margin "
                  f"{r.margin_m_per_s:+.2f} m/s ({r.margin_percent:+.2f} %)")
        parts.append(f"<p>Least margin at {r.altitude_m:g} m: {e(margin)}; critical: "
                     f"{e(_critical(r))}" + (f"; not cleared: {e(r.reason)}" if r.reason else "")
                     + ".</p>")
        parts.append(_table(("altitude [m]", "V_required [m/s]", "V_crit [m/s]", "margin [m/s]",
                             "margin [%]", "least g to V_D [-]", "verdict"),
                            [(_td(_num(x.altitude_m, ".0f"), "num"),
                              _td(_num(x.V_required, ".2f"), "num"),
                              _td(_num(x.critical_speed, ".2f"), "num"),
                              _td(_num(x.margin_m_per_s, "+.2f"), "num"),
                              _td(_num(x.margin_percent, "+.2f"), "num"),
                              _td(_num(x.least_g_to_V_D, ".4f"), "num"),
                              _td("pass" if x.cleared else "FAIL",
                                  "pass" if x.cleared else "fail")) for x in rows_c], "margins"))
        if not figures:
            parts.append(no_figures)
        elif r.plot is None:
            parts.append('<p class="note">No figures: ' + ("the analysis failed." if r.error else
                         "the result file was written without them (propwhirl.campaign/1).")
                         + "</p>")
        else:
            parts.append(f"<figure><h3>V-g-f at {r.altitude_m:g} m</h3>")
            parts.append(_img(_figure(cp.point_vgf(r, result.min_damping_g)),
                              f"V-g-f of {s.case} at {r.altitude_m:g} m") + "</figure>")
            shape = cp.point_mode_shape(r)
            if shape is not None:
                parts.append(f"<figure><h3>Critical mode at {r.altitude_m:g} m</h3>")
                parts.append(_img(_figure(shape), f"critical mode of {s.case} at "
                                  f"{r.altitude_m:g} m") + "</figure>")
        parts.append("</section>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def write_report(result: Any, folder: str | Path, *, campaign_file: str | Path | None = None,
                 model_file: str | Path | None = None, model: Any = None,
                 pdf: bool | None = None, date: str | None = None, figures: bool = True,
                 notes: list[str] | None = None) -> list[Path]:
    """Write ``report.html`` into `folder` and, with `pdf` True (or None and a Chromium found:
    :func:`propwhirl.app.browser.find_chromium`), ``report.pdf`` printed from it; returns the
    paths written.  A print that fails is a note appended to `notes` (the HTML is written;
    without `notes` the InputError is raised).  Before anything is hashed or drawn, neither
    report file may be the campaign file or the model file (InputError,
    :func:`propwhirl.fileio.check_apart`: resolved, symbolic links followed), nor a device, a
    FIFO or a socket (:func:`propwhirl.fileio.check_output`)."""
    _check_arguments(result, campaign_file, model_file, date)
    folder = Path(v.file_path("folder", folder, "the report's folder"))
    outputs = [("report", folder / HTML_NAME), ("PDF report", folder / PDF_NAME)]
    for what, path in outputs:
        fileio.check_output(path, what)
    fileio.check_apart(outputs, [(f"the campaign file {campaign_file}", campaign_file),
                                 (f"the model file {model_file}", model_file)])
    page = report_html(result, campaign_file=campaign_file, model_file=model_file, model=model,
                       date=date, figures=figures)
    out = [fileio.write_text(folder / HTML_NAME, page, what="report")]
    if pdf or (pdf is None and browser.find_chromium() is not None):
        try:
            out.append(browser.print_pdf(out[0], folder / PDF_NAME))
        except v.InputError as exc:
            if notes is None:
                raise
            notes.append(f"{PDF_NAME} not written: {exc} ({HTML_NAME} is written)")
    return out
