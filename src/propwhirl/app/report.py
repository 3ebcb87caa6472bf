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
  verdict (pass, or FAIL with its reason);
* per case: its transformation, its margin at every altitude, and at its least-margin altitude
  the V-g-f (V_D, the required speed and the damping requirement drawn) and the critical mode's
  shape.

Figures are SVG images inside the page (``data:`` URIs: the page is one file, nothing is
fetched; vector, so sharp at every zoom and vector in the printed PDF; each V-g-f's damping
axis on the band that decides, :func:`propwhirl.app.plots.campaign_plot.deciding_band`); no
table row is split across a printed page; every number has its unit in its column's heading
or beside it; every FAIL carries its reason, and the verdict which requirements decided it.
The page's markup is a template, ``templates/report.html`` (package data): blocks of the standard library's
:class:`string.Template` filled by :func:`render`, which passes every value through the one
escaping function :func:`e` (:func:`html.escape`, quotes too) unless it is a fragment
:func:`render` made itself (:class:`Html`) — so every string from the campaign or the model
file reaches the page escaped.  (Not jinja2: it is the code generator's extra, and ``propwhirl
certify`` writes the report with the runtime dependencies alone.)  Drawn from the
:class:`~propwhirl.studies.campaign_result.CampaignResult` alone (``campaign.json``), so a report
can be made again without analysing; the model's summary and mesh need the model.
"""
from __future__ import annotations

import base64
import datetime
import functools
import html
import importlib.resources
import re
import string
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
#: The report's title: what it judges.
TITLE = "flutter, whirl-flutter and divergence clearance report"
#: The page's markup: blocks of string.Template (templates/report.html, package data).
TEMPLATE = "templates/report.html"


class Html(str):
    """Markup that is already safe: a fragment :func:`render` made (its values escaped).
    Every other value put into the page goes through :func:`e`."""

    __slots__ = ()


def e(x: Any) -> Html:
    """`x` as escaped HTML text (quotes too), the page's one escaping function: a fragment
    :func:`render` made (:class:`Html`) is kept, anything else is ``html.escape(str(x))``."""
    return x if isinstance(x, Html) else Html(html.escape(str(x), quote=True))


@functools.cache
def _blocks() -> dict[str, string.Template]:
    """The blocks of :data:`TEMPLATE` by name (``<!-- block: NAME -->`` up to the next)."""
    text = importlib.resources.files("propwhirl.app").joinpath(TEMPLATE).read_text("utf-8")
    parts = re.split(r"^<!-- block: (\w+) -->\n", text, flags=re.M)
    return {name: string.Template(body.rstrip("\n")) for name, body in
            zip(parts[1::2], parts[2::2])}


def render(block: str, **values: Any) -> Html:
    """Block `block` of the page's template with every value escaped (:func:`e`)."""
    return Html(_blocks()[block].substitute({k: e(x) for k, x in values.items()}))


def join(parts: Sequence[Any], sep: str = "\n") -> Html:
    """The parts, each escaped (:func:`e`), joined."""
    return Html(sep.join(e(x) for x in parts))


def attrs(**values: Any) -> Html:
    """HTML attributes ``' name="value"'`` (values escaped; None and "" left out; a trailing
    underscore dropped: ``class_``; ``data_case`` is ``data-case``)."""
    return Html("".join(f' {k.rstrip("_").replace("_", "-")}="{e(x)}"'
                        for k, x in values.items() if x is not None and x != ""))


def sha256_file(path: str | Path, what: str = "file") -> str:
    """The SHA-256 of a file's bytes (hex): a regular file of at most
    :data:`propwhirl.fileio.MAX_READ_BYTES` bytes (:func:`propwhirl.fileio.sha256_file`),
    InputError naming the file (a `what`) otherwise."""
    return fileio.sha256_file(path, what)


def _num(x: float | None, fmt: str, unit: str = "") -> str:
    if x is None:
        return "–"
    return format(x, fmt) + (f" {unit}" if unit else "")


def _img(svg: bytes, alt: str) -> Html:
    """A figure as a vector image inside the page (SVG in a ``data:`` URI: sharp at every
    zoom, and vector in the printed PDF)."""
    return render("image", alt=alt,
                  src="data:image/svg+xml;base64," + base64.b64encode(svg).decode("ascii"))


def _figure(fig: Any) -> bytes:
    from propwhirl.app.plots.campaign_plot import svg_bytes  # lazy: figures

    try:
        return svg_bytes(fig)
    finally:
        fig.clear()


def _td(x: Any, cls: str = "") -> Html:
    """A table cell: `x` escaped (a fragment kept)."""
    return render("cell", tag="td", attrs=attrs(class_=cls), text=x)


def _th(x: Any) -> Html:
    return render("cell", tag="th", attrs=Html(""), text=x)


def _table(head: Sequence[str], rows: Sequence[Sequence[Html]], cls: str = "",
           row_attrs: Sequence[Html] | None = None) -> Html:
    """A table of cells (:func:`_td`, :func:`_th`); `head` plain text (no head when all
    empty)."""
    return render("table", attrs=attrs(class_=cls),
                  head=render("head", cells=join([_th(h) for h in head], "")) if any(head)
                  else Html(""),
                  rows=join([render("row", attrs=Html("") if row_attrs is None else row_attrs[i],
                                    cells=join(r, "")) for i, r in enumerate(rows)]))


def _critical(r: Any) -> str:
    if r.error:
        return "analysis failed: " + r.error
    if r.kind == "none":
        return "none up to " + _num(r.analysed_to, ".1f", "m/s")
    if r.event == "unstable-at-start":
        return (f"{r.kind} of {r.mode}: unstable already at the first analysed speed "
                f"({_num(r.critical_speed, '.2f', 'm/s')}), its damping negative there, so "
                "its onset lies below the analysed range (the speed grid's start: "
                "unstable-at-start)")
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


def _verdict(r: Any) -> Html:
    """A row's verdict cell: "pass", or "FAIL" with its reason beside it (every requirement it
    fails: :attr:`~propwhirl.studies.campaign_result.PointRow.reason`)."""
    if r.cleared:
        return _td("pass", "pass")
    return _td(render("verdict", reason=r.reason or "no reason recorded"), "fail")


#: The summary table's columns: (heading with its unit, the cell of a row).
SUMMARY_COLUMNS = (
    ("case", lambda r: _td(r.case)),
    ("altitude [m]", lambda r: _td(_num(r.altitude_m, ".0f"), "num")),
    ("V_D (TAS) [m/s]", lambda r: _td(_num(r.V_D, ".2f"), "num")),
    ("rule", lambda r: _td(r.rule or "–")),
    ("V_required [m/s]", lambda r: _td(_num(r.V_required, ".2f"), "num")),
    ("V_crit [m/s]", lambda r: _td(_num(r.critical_speed, ".2f"), "num")),
    ("margin [m/s]", lambda r: _td(_num(r.margin_m_per_s, "+.2f"), "num")),
    ("margin [%]", lambda r: _td(_num(r.margin_percent, "+.2f"), "num")),
    ("least g = 2ζ to V_req [-]", lambda r: _td(_num(r.least_g, ".4f"), "num")),
    ("dζ/dV at V_req [s/m]", lambda r: _td(_num(r.dzeta_dV_at_required, "+.2e"), "num")),
    ("critical instability", lambda r: _td(_critical(r))),
    ("verdict (the requirement that fails)", _verdict),
)


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
    docstring): the blocks of :data:`TEMPLATE` filled by :func:`render`, which escapes every
    value.

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
    date = date or datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    summaries = result.cases()
    page = render(
        "page", name=result.name, title=TITLE,
        subtitle=Html("Aeroelastic clearance — flutter, propeller whirl flutter and "
                      "divergence — of <code>propwhirl certify</code>."),
        verdict_class="pass" if result.cleared else "fail",
        verdict="CLEARED" if result.cleared else "NOT CLEARED",
        decided=_decided(result),
        campaign=_campaign_table(result, campaign_file, model_file, date, summaries),
        model=_model_section(result, model, figures),
        summary=_table([h for h, _ in SUMMARY_COLUMNS],
                       [[cell(r) for _, cell in SUMMARY_COLUMNS] for r in result.rows],
                       "summary",
                       [attrs(class_=f"point {'pass' if r.cleared else 'fail'}",
                              data_case=r.case, data_altitude=repr(r.altitude_m))
                        for r in result.rows]),
        cases=join([_case_section(result, i, s, figures)
                    for i, s in enumerate(summaries, start=1)]))
    return page + "\n"


def _decided(result: Any) -> Html:
    """Which requirement decided the verdict: every requirement the failing points fail, with
    their number (nothing when the campaign clears)."""
    found = result.decided_by()
    if not found:
        return Html("")
    return render("decided", total=len(result.rows), items=join(
        [render("decided_item", what=what, count=n) for what, n in found], ""))


def _campaign_table(result: Any, campaign_file: Any, model_file: Any, date: str,
                    summaries: Sequence[Any]) -> Html:
    """The campaign's table: its files and hashes, envelope, regulation, requirements, ..."""
    g = ("none (damping reported, not judged)" if result.min_damping_g is None else
         result.damping_text or f"g = 2ζ ≥ {result.min_damping_g:g} [-] of the total damping "
         "of every oscillatory mode of interest up to V_D (a result file before the reading "
         "was recorded)")
    files: list[tuple[str, Any]] = []
    for label, path in (("campaign file", campaign_file), ("model file", model_file)):
        if path is not None:
            files.append((label, render("cell", tag="code", attrs=Html(""), text=path)))
            files.append((f"{label} SHA-256", render("cell", tag="span",
                                                     attrs=attrs(class_="hash"),
                                                     text=sha256_file(path, label))))
    required = f"{result.factor:g} × V_D (true airspeed)" + (
        "; failure cases (25.629(b)(2)): the greater of V_D (M_D) and the 1.15 V_C / "
        "M_C + 0.05 line, each row's rule" if any(r.rule.startswith("25.629(b)(2)")
                                                 for r in result.rows) else "")
    rows = [("campaign", result.name), ("model", result.model_name), *files,
            ("envelope", _envelope(result.rows)), ("regulation", result.regulation),
            ("required speed", required), ("damping requirement", g),
            ("convention", result.convention),
            ("cases cleared", f"{sum(s.cleared for s in summaries)} of {len(summaries)}"),
            ("analyses", str(result.analyses)),
            ("software", f"propwhirl {propwhirl.__version__}"), ("date", date)]
    return _table(("", ""), [(_th(k), _td(x)) for k, x in rows], "campaign")


def _model_section(result: Any, model: Any, figures: bool) -> Html:
    """The model (:mod:`propwhirl.app.report_model`): its summary, its propellers' mounts, its
    wing's EI, GJ and mass along the span and its mesh (figures), its in-vacuo modes; or a
    note without the model."""
    if model is None:
        return render("note", text="The model was not given to the report: see the model file "
                      "above.")
    from propwhirl.app import report_model as rm  # lazy: analyses (the CLI loads no model)

    parts = [_table(("quantity", "value"), [(_td(k), _td(x)) for k, x in rm.model_summary(model)],
                    "model")]
    rows = rm.propeller_table(model)
    if rows:
        parts.append(render("heading", text="Propellers and their mounts"))
        parts.append(render("note", text="Masses on each shaft (rotor first) and their sum "
                            "M_P; inertias about the pitch and yaw pivots; the mount's stiffness "
                            "and the uncoupled frequencies f = √(K / I) / 2π; its structural "
                            "damping as the model file gives it (g = 2ζ, or ζ)."))
        parts.append(_table(rm.PROPELLER_HEAD, [[_td(x) for x in r] for r in rows],
                            "propellers"))
    mesh = _mesh(model)
    wing = rm.wing_properties(model)
    if figures and (mesh is not None or wing is not None):
        from propwhirl.app.plots import campaign_plot as cp  # lazy: figures

        if wing is not None:
            parts.append(render("figure", heading="Stiffness and mass along the span",
                                image=_img(_figure(cp.wing_properties_plot(
                                    wing["y"], wing["m"], wing["EI"], wing["GJ"],
                                    mesh[1] if mesh else [])),
                                    f"EI, GJ and mass of {result.model_name}")))
        if mesh is not None:
            parts.append(_img(_figure(cp.mesh_plot(*mesh, title="mesh")),
                              f"mesh of {result.model_name}"))
    head, modes = rm.in_vacuo_modes(model)
    parts.append(render("heading", text=f"In-vacuo modes (the first {len(modes)})"))
    parts.append(render("note", text="V = 0, rotors not turning, no aerodynamics: each mode's "
                        "frequency and the shares of its kinetic energy (bending, torsion of the "
                        "wing; pitch, yaw of the propellers)."))
    parts.append(_table(head, [[_td(r[0]), *(_td(x, "num") for x in r[1:])] for r in modes],
                        "modes"))
    return join(parts)


def _case_section(result: Any, i: int, s: Any, figures: bool) -> Html:
    """Case `i` (its summary `s`): its transformation, least margin, margins at every altitude
    and, at its least-margin altitude, the V-g-f and the critical mode."""
    r = s.worst
    margin = ("no counted instability up to " + _num(r.analysed_to, ".2f", "m/s")
              if r.critical_speed is None else
              f"V_crit = {r.critical_speed:.2f} m/s, required {r.V_required:.2f} m/s"
              + (f" ({r.rule})" if r.rule else "") + ": margin "
              f"{r.margin_m_per_s:+.2f} m/s ({r.margin_percent:+.2f} %)")
    margins = _table(("altitude [m]", "V_required [m/s]", "V_crit [m/s]", "margin [m/s]",
                      "margin [%]", "least g to V_D [-]", "verdict (the requirement that fails)"),
                     [(_td(_num(x.altitude_m, ".0f"), "num"),
                       _td(_num(x.V_required, ".2f"), "num"),
                       _td(_num(x.critical_speed, ".2f"), "num"),
                       _td(_num(x.margin_m_per_s, "+.2f"), "num"),
                       _td(_num(x.margin_percent, "+.2f"), "num"),
                       _td(_num(x.least_g_to_V_D, ".4f"), "num"),
                       _verdict(x)) for x in result.rows if x.case == s.case],
                     "margins")
    return render("case", number=i, case=s.case, verdict_class="pass" if s.cleared else "fail",
                  verdict="cleared" if s.cleared else "NOT cleared", description=r.description,
                  altitude=f"{r.altitude_m:g}", margin=margin, critical=_critical(r),
                  reason=f"; not cleared: {r.reason}" if r.reason else "", margins=margins,
                  figures=_case_figures(r, s, result.min_damping_g, figures))


def _case_figures(r: Any, s: Any, min_damping_g: float | None, figures: bool) -> Html:
    """The V-g-f and the critical mode of row `r` (a note where there are none)."""
    if not figures:
        return render("note", text="Figures left out: install the plots extra (pip install "
                      "propwhirl[plots]) and write the report again.")
    if r.plot is None:
        return render("note", text="No figures: " + (
            "the analysis failed." if r.error else
            "the result file was written without them (propwhirl.campaign/1)."))
    from propwhirl.app.plots import campaign_plot as cp  # lazy: figures

    out = [render("figure", heading=f"V-g-f at {r.altitude_m:g} m",
                  image=_img(_figure(cp.point_vgf(r, min_damping_g)),
                             f"V-g-f of {s.case} at {r.altitude_m:g} m"))]
    shape = cp.point_mode_shape(r)
    if shape is not None:
        out.append(render("figure", heading=f"Critical mode at {r.altitude_m:g} m",
                          image=_img(_figure(shape), f"critical mode of {s.case} at "
                                     f"{r.altitude_m:g} m")))
    return join(out)


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
