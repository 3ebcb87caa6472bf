"""The certification report of `propwhirl certify` (issue 24, item 3), read as a person reads it:
the HTML page opened in the distribution's headless Chromium (driven by selenium) — every figure
loads, every (case, altitude) row of the summary table is there, a screenshot is saved — and the
PDF's pages rendered to PNG (pypdfium2).  Skipped, naming what is missing and how to install it,
only where no browser is found.  Without a browser: the page escapes every user string, gives
every number its unit, names the files with their SHA-256 and propwhirl's version, and is
drawn from a version-1 result file too."""
from __future__ import annotations

import hashlib
import html.parser
import json
import re
from pathlib import Path

import numpy as np
import pytest

from propwhirl import __version__
from propwhirl.app import browser, cli
from propwhirl.app import report as R
from propwhirl.app import report_model as RM
from propwhirl.studies import campaign as C

CAMPAIGN = """
format = "propwhirl-campaign"
format_version = 1
name = "report test <b>campaign</b>"
model = "{model}"
[regulation]
name = "cs25"
min_damping_g = 0.0001
damping = {{ applies_to = "total", source = "a <i>test</i> reading" }}
[envelope]
airspeed = "TAS"
V_D_m_per_s = 40.0
altitudes_m = [0.0, 3000.0]
[[cases]]
name = "nominal"
[[cases]]
name = 'mount at 50 % <script>alert(1)</script> & "q"'
mount_stiffness = 0.5
"""
CASES = ("nominal", 'mount at 50 % <script>alert(1)</script> & "q"')
ALTITUDES = (0.0, 3000.0)


def _browser_or_skip() -> None:
    try:
        import pypdfium2  # noqa: F401
        import selenium  # noqa: F401
    except ImportError as exc:
        pytest.skip(f"the report's browser test needs {exc.name}: pip install -e '.[report]' "
                    "(make test installs it)")
    if browser.find_chromium() is None or browser.find_chromedriver() is None:
        pytest.skip("no headless browser: " + browser.INSTALL_HINT + " (make test does it where "
                    "it runs as root)")


@pytest.fixture(scope="module")
def certified(small_file, tmp_path_factory) -> Path:
    """The report folder of a small campaign (2 cases x 2 altitudes) run by `propwhirl
    certify`, with its PDF where a browser is found."""
    folder = tmp_path_factory.mktemp("certify")
    path = folder / "c.toml"
    path.write_text(CAMPAIGN.format(model=Path(small_file).as_posix()))
    pdf = "--pdf" if browser.find_chromium() else "--no-pdf"
    assert cli.main(["certify", str(path), "--out", str(folder / "out"), "--quiet", pdf]) in (0, 1)
    return folder / "out"


def test_the_report_in_a_browser(certified, tmp_path):
    _browser_or_skip()
    result = C.CampaignResult.load(certified / "campaign.json")
    d = browser.webdriver(1100, 900)
    try:
        d.get((certified / "report.html").resolve().as_uri())
        images = d.execute_script(
            "return [...document.images].map(i => [i.complete, i.naturalWidth, i.alt])")
        rows = d.execute_script(
            "return [...document.querySelectorAll('table.summary tbody tr')].map("
            "r => [r.dataset.case, r.dataset.altitude, r.cells.length, r.innerText])")
        title = d.title
        height = d.execute_script("return document.body.scrollHeight")
        d.set_window_size(1100, min(int(height) + 50, 8000))
        shot = tmp_path / "report.png"
        assert d.save_screenshot(str(shot))
    finally:
        d.quit()
    # every figure loads: the wing's EI, GJ and mass, the mesh, and per case its V-g-f and
    # critical mode
    with_shape = sum(1 for s in result.cases() if s.worst.plot and s.worst.plot.shape)
    assert len(images) == 2 + len(result.cases()) + with_shape   # EI/GJ/m, the mesh
    assert all(ok and width > 0 for ok, width, _ in images), images
    assert "<b>campaign</b>" in title          # shown as text, not markup
    assert "flutter, whirl-flutter and divergence" in title     # what is judged
    # every (case, altitude) row, in the campaign's order, with its verdict
    assert [(c, float(a)) for c, a, _, _ in rows] == [(c, a) for c in CASES for a in ALTITUDES]
    assert all(n == len(R.SUMMARY_COLUMNS) for _, _, n, _ in rows)
    for (_, _, _, text), r in zip(rows, result.rows):
        assert ("pass" if r.cleared else "FAIL") in text and f"{r.V_required:.2f}" in text
    _not_blank(shot, min_height=1000)


def test_the_pdf_pages_render(certified, tmp_path):
    _browser_or_skip()
    import pypdfium2 as pdfium

    pdf = pdfium.PdfDocument(str(certified / "report.pdf"))
    try:
        pages = len(pdf)
        # the campaign, model and summary, then each case on its own page (or more)
        assert pages >= 1 + len(CASES)
        for i in range(pages):
            png = tmp_path / f"page-{i + 1}.png"
            pdf[i].render(scale=0.5).to_pil().save(png)
            _not_blank(png, min_height=300)
    finally:
        pdf.close()


def _not_blank(png: Path, min_height: int) -> None:
    """A PNG of at least `min_height` pixels with ink on it: more than 0.5 % of its pixels
    not white."""
    from matplotlib import image

    a = image.imread(png)
    assert a.shape[0] >= min_height
    ink = (a[..., :3] < 0.9).any(axis=-1).mean()
    assert ink > 0.005, f"{png.name}: {100 * ink:.2f} % ink"


# ------------------------------------------------------------------------------ no browser
class _Page(html.parser.HTMLParser):
    """The tables of a page: per table its head cells and its rows of (class, text) cells;
    every <script> tag and every image source."""

    def __init__(self) -> None:
        super().__init__()
        self.tables: list[dict] = []
        self.scripts = 0
        self.images: list[str] = []
        self._cell: list | None = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "script":
            self.scripts += 1
        elif tag == "img":
            self.images.append(a.get("src", ""))
        elif tag == "table":
            self.tables.append({"class": a.get("class", ""), "head": [], "rows": []})
        elif tag == "tr" and self.tables:
            self.tables[-1]["rows"].append([])
        elif tag in ("td", "th") and self.tables:
            self._cell = [tag, a.get("class", ""), ""]

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[2] += data

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self.tables[-1]["rows"][-1].append(tuple(self._cell))
            self._cell = None


@pytest.fixture(scope="module")
def result(certified) -> C.CampaignResult:
    return C.CampaignResult.load(certified / "campaign.json")


def test_every_user_string_is_escaped_and_every_number_has_its_unit(certified, result):
    text = (certified / "report.html").read_text()
    page = _Page()
    page.feed(text)
    assert page.scripts == 0 and "<script>alert" not in text and "<b>campaign" not in text
    assert "&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;q&quot;" in text
    summary = next(t for t in page.tables if t["class"] == "summary")
    head = [c[2] for c in summary["rows"][0]]
    body = summary["rows"][1:]
    assert len(body) == len(result.rows) == len(CASES) * len(ALTITUDES)
    numeric = 0
    for row in body:
        for (tag, cls, cell), h in zip(row, head):
            if cls == "num" and cell != "–":
                numeric += 1
                float(cell)                          # a number, its unit in the heading
                assert "[" in h and h.endswith("]"), h
    assert numeric >= 3 * len(body)
    for t in page.tables:                            # the per-case margin tables too
        if t["class"] == "margins":
            assert all("[" in c[2] for c in t["rows"][0][:-1])
    assert all(src.startswith("data:image/svg+xml;base64,") for src in page.images)


def test_the_files_hashes_and_the_version_are_named(certified, small_file):
    text = (certified / "report.html").read_text()
    digest = hashlib.sha256(Path(small_file).read_bytes()).hexdigest()
    campaign = hashlib.sha256((certified.parent / "c.toml").read_bytes()).hexdigest()
    assert digest in text and campaign in text
    assert f"propwhirl {__version__}" in text
    assert "1.15 × V_D" in text and "g = 2ζ ≥ 0.0001" in text
    assert "of the total damping (structural damping included)" in text
    assert "(a &lt;i&gt;test&lt;/i&gt; reading)" in text    # the file's source, escaped
    assert "V_D 40 m/s TAS at 0, 3000 m" in text


def test_a_version_1_result_file_still_makes_a_report(certified, tmp_path):
    doc = json.loads((certified / "campaign.json").read_text())
    assert doc["format"] == "propwhirl.campaign/2"
    doc["format"] = "propwhirl.campaign/1"
    for row in doc["rows"]:
        del row["plot"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(doc))
    r = C.CampaignResult.load(old)
    assert all(x.plot is None for x in r.rows)
    page = R.report_html(r, date="2026-01-01")
    assert page.count("propwhirl.campaign/1") == len(CASES) and "<img" not in page


def test_the_figures_data_is_saved_and_read_back(result):
    for r in result.rows:
        p = r.plot
        assert p is not None and p.zeta.shape == p.frequency_hz.shape == (p.V.size,
                                                                            len(p.modes))
        assert np.isfinite(p.zeta).all() and p.oscillatory.any()
        if r.critical_speed is not None:
            assert p.shape is not None and abs(p.shape["V"] - r.critical_speed) < 1e-6
            peak = max(np.abs(np.r_[p.shape["h"], p.shape["alpha"]]).max(),
                       max(max(abs(t), abs(q)) for _, _, t, q in p.shape["propellers"]))
            assert peak == pytest.approx(1.0)        # normalised to its largest entry
    assert C.PointPlot.from_dict(result.rows[0].plot.to_dict()) == result.rows[0].plot


def test_pdf_without_a_browser_is_refused_before_any_analysis(small_file, tmp_path,
                                                              monkeypatch, capsys):
    monkeypatch.setattr(browser, "find_chromium", lambda: None)
    monkeypatch.setattr(C, "evaluate_point", lambda t: pytest.fail("an analysis ran"))
    path = tmp_path / "c.toml"
    path.write_text(CAMPAIGN.format(model=Path(small_file).as_posix()))
    assert cli.main(["certify", str(path), "--out", str(tmp_path / "r"), "--pdf"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--pdf" in err and "apt-get install" in err


def test_the_vgf_curve_is_hermite_and_straight_near_a_branch_point():
    from propwhirl.app.plots.campaign_plot import hermite

    V = np.array([0.0, 1.0, 3.0, 4.0])
    y, dy = V**3 - V, 3 * V**2 - 1                    # a cubic is drawn exactly
    x, c = hermite(V, y, dy, np.ones(4, bool), n=9)
    assert np.allclose(c, x**3 - x)
    dy_singular = dy.copy()
    dy_singular[2] = 1e6                                # f -> 0 with an infinite slope
    x, c = hermite(V, y, dy_singular, np.ones(4, bool), n=9)
    step = (x >= 1.0) & (x <= 3.0)
    assert np.allclose(c[step], np.interp(x[step], V, y))
    x, c = hermite(V, y, dy, np.array([True, True, False, True]), n=9)
    assert np.isnan(c).sum() == 2 and np.isfinite(c).sum() == 9   # no line through a gap


def test_a_failing_print_is_one_line_naming_the_browser(tmp_path, monkeypatch):
    page = tmp_path / "p.html"
    page.write_text("<p>x</p>")
    monkeypatch.setenv("PROPWHIRL_CHROMIUM", "/bin/false")
    assert browser.find_chromium() == "/bin/false"
    with pytest.raises(R.v.InputError) as err:
        browser.print_pdf(page, tmp_path / "p.pdf")
    assert len(str(err.value).splitlines()) == 1 and "/bin/false" in str(err.value)
    assert not (tmp_path / "p.pdf").exists()
    monkeypatch.setenv("PROPWHIRL_CHROMIUM", str(tmp_path / "none"))
    assert browser.find_chromium() is None
    with pytest.raises(R.v.InputError, match="apt-get install -y chromium"):
        browser.print_pdf(page, tmp_path / "p.pdf")


def test_a_failing_print_leaves_the_page_and_a_note(result, tmp_path, monkeypatch):
    monkeypatch.setenv("PROPWHIRL_CHROMIUM", "/bin/false")
    notes: list[str] = []
    written = R.write_report(result, tmp_path, pdf=None, figures=False, notes=notes)
    assert written == [tmp_path / "report.html"] and not (tmp_path / "report.pdf").exists()
    assert len(notes) == 1 and "report.pdf not written" in notes[0] and "/bin/false" in notes[0]
    with pytest.raises(R.v.InputError):
        R.write_report(result, tmp_path, pdf=True, figures=False)


# ----------------------------------------------------------- issue 33, items 1 and 3
from propwhirl.validate import InputError  # noqa: E402

EXAMPLE_RESULT = (Path(__file__).resolve().parents[2] / "examples" / "certification" / "wingtip"
                  / "campaign.json")


@pytest.fixture(scope="module")
def example_result() -> C.CampaignResult:
    """The committed example's result (no campaign run)."""
    return C.CampaignResult.load(EXAMPLE_RESULT)


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_the_hash_of_a_device_is_refused_before_it_is_opened(example_result, monkeypatch,
                                                             device):
    """Item 3: the report's SHA-256 of campaign_file='/dev/zero' grew past 4 GB."""
    from helpers.files import never_opened

    never_opened(monkeypatch, device)
    with pytest.raises(InputError) as e:
        R.report_html(example_result, campaign_file=device, figures=False)
    assert str(e.value) == (f"cannot read campaign file {device!r}: it is a character device, "
                            "not a regular file (propwhirl reads regular files only)")


@pytest.mark.parametrize("name", [R.HTML_NAME, R.PDF_NAME])
def test_the_report_is_not_written_over_the_model_file(example_result, tmp_path, monkeypatch,
                                                       name):
    """Item 1: the report written onto the model (or campaign) file it names and hashes."""
    model = tmp_path / name
    model.write_text("[wing]\n")
    monkeypatch.setattr(R, "report_html", lambda *a, **k: pytest.fail("the report was drawn"))
    with pytest.raises(InputError) as e:
        R.write_report(example_result, tmp_path, model_file=model, pdf=False)
    label = "report" if name == R.HTML_NAME else "PDF report"
    assert str(e.value) == (f"{label} {model} is the model file {model}: give another path")
    with pytest.raises(InputError, match="is the campaign file"):
        R.write_report(example_result, tmp_path, campaign_file=tmp_path / "." / name, pdf=False)
    assert model.read_text() == "[wing]\n"


# ------------------------------------------------------- issue 38 item 7: the page's template
def test_every_value_of_the_template_is_escaped_once():
    """The page is string.Template blocks filled by render(): a value is escaped exactly once
    (a fragment render made is kept), a `$` in a value is text, every block's names filled."""
    cell = R.render("cell", tag="td", attrs=R.attrs(class_='a"b'), text="<x> & $name")
    assert cell == '<td class="a&quot;b">&lt;x&gt; &amp; $name</td>'
    row = R.render("row", attrs=R.Html(""), cells=R.join([cell, "<y>"], ""))
    assert row == f"<tr>{cell}&lt;y&gt;</tr>"          # the fragment kept, the text escaped
    assert R.e(R.e("<")) == "&lt;"                     # escaped once, not twice
    with pytest.raises(KeyError):
        R.render("cell", tag="td", attrs=R.Html(""))   # a name left unfilled is an error
    blocks = R._blocks()
    assert {"page", "case", "figure", "image", "note", "table", "head", "row", "cell"} <= set(
        blocks)


def test_the_template_is_package_data():
    import tomllib

    pyproject = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml")
                              .read_text())
    assert "app/templates/*.html" in pyproject["tool"]["setuptools"]["package-data"]["propwhirl"]


# ------------------------------------------- issue 35 item 1: a verdict with its reason
FAILING = """
format = "propwhirl-campaign"
format_version = 1
name = "fails"
model = "{model}"
[regulation]
name = "cs25"
min_damping_g = 0.03
damping = {{ applies_to = "total", source = "MIL-A-8870C 3.1.1" }}
[envelope]
airspeed = "TAS"
V_D_m_per_s = 130.0
altitudes_m = [0.0, 3000.0]
[[cases]]
name = "nominal"
"""


@pytest.fixture(scope="module")
def failing(small_file, tmp_path_factory) -> Path:
    """A campaign that fails: 1.15 V_D above the wing's divergence at sea level, and a
    damping requirement of g >= 0.03 (total) the model does not meet."""
    folder = tmp_path_factory.mktemp("failing")
    path = folder / "c.toml"
    path.write_text(FAILING.format(model=Path(small_file).as_posix()))
    assert cli.main(["certify", str(path), "--out", str(folder / "out"), "--quiet",
                     "--no-pdf"]) == 1
    return folder / "out"


def test_every_fail_carries_its_reason_and_the_summary_says_what_decided(failing):
    result = C.CampaignResult.load(failing / "campaign.json")
    text = (failing / "report.html").read_text()
    page = _Page()
    page.feed(text)
    fails = [(t["class"], c[2]) for t in page.tables for row in t["rows"] for c in row
             if c[1] == "fail"]
    assert len(fails) >= 2 * len(result.rows)          # the summary's and the case's tables
    for table, cell in fails:
        assert cell.startswith("FAIL") and len(cell) > len("FAIL") + 10, (table, cell)
        assert "damping: total g = " in cell or "speed: " in cell, cell
    # which requirement decided, with how many points fail it
    decided = dict(result.decided_by())
    assert decided["the damping requirement"] == len(result.rows)
    speed = sum("speed" in r.failed for r in result.rows)
    assert speed >= 1 and decided["no instability up to the required speed"] == speed
    assert re.search(r"<li><b>the damping requirement</b>: 2 points</li>", text)
    assert "Decided by (of the 2 points analysed" in text
    last = result.format().splitlines()[-1]
    assert "NOT CLEARED (failed: " in last and "the damping requirement: 2 of 2 points" in last
    assert f"no instability up to the required speed: {speed} of 2 points" in last


# ------------------------------------------------- issue 35 item 3: figures a reader can read
def test_the_figures_are_vector_in_the_page_and_in_the_pdf(certified):
    """Every figure of the page is SVG; the printed PDF holds no raster image below 200 dpi
    (its figures are vector paths and text)."""
    _browser_or_skip()
    import pypdfium2 as pdfium
    import pypdfium2.raw as pdfium_c

    page = _Page()
    page.feed((certified / "report.html").read_text())
    assert page.images and all(s.startswith("data:image/svg+xml;base64,") for s in page.images)
    pdf = pdfium.PdfDocument(str(certified / "report.pdf"))
    try:
        paths = 0
        for i in range(len(pdf)):
            for obj in pdf[i].get_objects(max_depth=8):
                if obj.type == pdfium_c.FPDF_PAGEOBJ_IMAGE:
                    m = obj.get_metadata()
                    assert min(m.horizontal_dpi, m.vertical_dpi) >= 200, (i, m)
                paths += obj.type == pdfium_c.FPDF_PAGEOBJ_PATH
        assert paths > 500 * len(CASES)                  # the figures' curves, as paths
    finally:
        pdf.close()


def test_no_table_row_is_split_across_pdf_pages(result, tmp_path):
    """A summary of 60 rows, each with a reason of 3 to 12 lines, printed: the first and last
    words of a row's cells are on the same page; the header repeats on each page; on
    the printed width the summary table fits the page."""
    _browser_or_skip()
    import dataclasses

    import pypdfium2 as pdfium

    row = result.rows[0]
    rows = tuple(dataclasses.replace(
        row, case=f"row {i:03d}", cleared=False, kind="flutter", event="onset",
        mode=f"top{i:03d} a mode whose name takes a few lines bot{i:03d}",
        reason=f"begin{i:03d} " + "a reason long enough to take several lines of its cell in "
        "the printed table; " * (1 + i % 4) + f"end{i:03d}") for i in range(60))
    big = dataclasses.replace(result, rows=rows)
    R.write_report(big, tmp_path, pdf=True, figures=False, date="2026-01-01")
    pdf = pdfium.PdfDocument(str(tmp_path / "report.pdf"))
    try:
        texts = [pdf[i].get_textpage().get_text_range() for i in range(len(pdf))]
    finally:
        pdf.close()
    compact = [re.sub(r"\s+", "", t) for t in texts]    # (pdfium splits Chromium's runs)
    compact = compact[:next(p for p, t in enumerate(compact) if "Case1:" in t)]  # summary
    pages_with_rows = 0
    for i in range(60):       # the first and last words of its cells, on one page
        pages = {word: [p for p, t in enumerate(compact) if word in t] for word in (
            f"row{i:03d}", f"top{i:03d}", f"bot{i:03d}", f"begin{i:03d}", f"end{i:03d}")}
        assert all(len(p) == 1 and p == pages[f"row{i:03d}"] for p in pages.values()), (
            i, pages)
    for t in compact:
        if "row0" in t:
            pages_with_rows += 1
            assert "V_required" in t                     # the header on every page
    assert pages_with_rows >= 2                          # the table does span pages
    d = browser.webdriver(800, 900)
    try:
        d.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "print"})
        d.set_window_size(703 + 16, 900)                 # A4 less 2 x 12 mm, at 96 px/inch
        d.get((tmp_path / "report.html").resolve().as_uri())
        right, body = d.execute_script(
            "return [document.querySelector('table.summary').getBoundingClientRect().right,"
            " document.body.getBoundingClientRect().right]")
    finally:
        d.quit()
    assert right <= body + 0.5, (right, body)


def test_the_damping_axis_is_the_band_that_decides():
    """Six whirl modes near zeta = 0.01 and one wing mode at 0.2: the axis ends at 0.05 (not
    0.23), the wing mode is marked where it leaves (a triangle on the top edge), the
    requirement's line lies inside the band."""
    from propwhirl.app.plots.campaign_plot import BAND_TOP, deciding_band

    V = np.linspace(5.0, 150.0, 30)
    zeta = np.column_stack([0.01 + 0.0001 * k - 1e-4 * V for k in range(6)]
                           + [np.full(V.size, 0.2)])
    lo, hi = deciding_band(V, zeta, 120.0, 0.03)
    assert hi == pytest.approx(BAND_TOP) and lo == pytest.approx(-0.05)
    assert lo < 0.0 < 0.015 < hi                        # zero and the requirement inside
    assert deciding_band(V, zeta, 120.0, 0.06)[1] == pytest.approx(0.09)   # 3 x zeta_req
    high = np.column_stack([zeta[:, -1], 0.1 + 0.0 * V])     # the least damped tops out at 0.1
    assert deciding_band(V, high, 120.0, None)[1] == pytest.approx(0.115)


def test_a_curve_above_the_band_is_marked(result):
    """The campaign's V-g-f draws on the band that decides; a curve that starts above it gets
    a triangle at its first speed on the top edge."""
    from propwhirl.app.plots import campaign_plot as cp

    row = result.rows[0]
    fig = cp.point_vgf(row, 0.0001)
    try:
        ax = fig.axes[0]
        lo, hi = ax.get_ylim()
        osc = np.asarray(row.plot.oscillatory)
        z = np.where(osc, row.plot.zeta, np.nan)
        assert (lo, hi) == pytest.approx(cp.deciding_band(row.plot.V, z, row.V_required,
                                                          0.0001))
        above = [k for k in range(z.shape[1]) if np.isfinite(z[:, k]).any()
                 and z[np.flatnonzero(np.isfinite(z[:, k]))[0], k] > hi]
        tops = [ln for ln in ax.lines if ln.get_marker() == "^"
                and np.allclose(ln.get_ydata(), hi)]
        assert len(tops) >= len(above)
    finally:
        fig.clear()


# ------------------------------------------------ issue 35 item 4: what was analysed
def test_the_model_section_holds_the_structural_data(certified, small_file):
    """The mounts (masses, inertias, stiffness, frequencies, damping), the wing's EI, GJ and
    mass along the span (a figure), the in-vacuo modes (as `propwhirl modes` prints them),
    the aerodynamics, the method and the mesh: each against the model itself."""
    from propwhirl.analysis.vibration import label_modes
    from propwhirl.io import load_model

    model = load_model(small_file)
    text = (certified / "report.html").read_text()
    page = _Page()
    page.feed(text)
    tables = {t["class"]: t for t in page.tables}
    props = tables["propellers"]["rows"]
    assert [c[2] for c in props[0]] == list(RM.PROPELLER_HEAD)
    p = model.propellers[0].propeller
    cells = dict(zip(RM.PROPELLER_HEAD, (c[2] for c in props[1])))
    Kt, Kp = p.stiffness()
    inertia = p.pivot_inertia()
    assert cells["K_θ, K_ψ [N m/rad]"] == f"{Kt:.4g}, {Kp:.4g}"
    f = np.sqrt(Kt / inertia["I_theta_P"]) / (2 * np.pi)
    assert cells["f_θ, f_ψ [Hz]"].startswith(f"{f:.3f}")
    if p.f_theta is not None:
        assert f == pytest.approx(p.f_theta, rel=1e-9)      # the file's frequency, back
    assert cells["mount damping"] == f"g = {p.damping_theta:g}, {p.damping_psi:g}"
    assert cells["masses [kg]"].endswith(f"= {inertia['M_P']:g}")
    modes = tables["modes"]["rows"][1:]
    expected = label_modes(model)[:len(modes)]
    assert len(modes) == RM.IN_VACUO_COUNT
    assert [(c[0][2], c[1][2]) for c in modes] == [(n, f"{fr:.3f}") for n, fr in expected]
    for row in modes:                                     # shares of one mode sum to 100 %
        assert sum(float(c[2]) for c in row[2:]) == pytest.approx(100.0, abs=2.5)
    summary = dict((c[0][2], c[1][2]) for c in tables["model"]["rows"][1:])
    assert "strip theory" in summary["wing aerodynamics"]
    assert summary["analysis method"].startswith("analyse(method='auto') → ")
    assert "EI, GJ and mass of" in text and "mesh of" in text


def test_unstable_at_start_is_explained(result):
    import dataclasses

    row = dataclasses.replace(result.rows[0], kind="flutter", event="unstable-at-start",
                              mode="backward 1", critical_speed=5.0)
    assert R._critical(row).startswith("flutter of backward 1: unstable already at the first "
                                       "analysed speed (5.00 m/s), its damping negative there")
