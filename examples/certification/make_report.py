"""Make an example certification report: `propwhirl certify` on a campaign, then the page as a
reader sees it.

    python examples/certification/make_report.py CAMPAIGN.toml OUT_DIR     (or: make report)

writes into OUT_DIR the report (report.html), every number of it (campaign.json,
campaign.csv), a screenshot of the page's first screen in headless Chromium (screenshot.png)
and the PDF's pages rendered to PNG (pdf-page-1.png, ...).  The PDF itself is left out (its
pages are the PNGs; `propwhirl certify` prints it again).  Needs the plots and report extras and
the distribution's Chromium (make report installs them).  Exit code: certify's (0 cleared, 1
not cleared, 2 bad input).
"""
from __future__ import annotations

import sys
from pathlib import Path

from propwhirl.app import browser, cli

#: The browser window of the screenshot [pixels].
WINDOW = (1100, 1500)
#: The scale of the PDF's pages as PNG (1 = 72 dots per inch).
PAGE_SCALE = 0.8


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    campaign, out = argv[0], Path(argv[1])
    code = cli.main(["certify", campaign, "--out", str(out), "--pdf", "--quiet"])
    if code not in (0, 1):
        return code
    for old in out.glob("pdf-page-*.png"):
        old.unlink()
    d = browser.webdriver(*WINDOW)
    try:
        d.get((out / "report.html").resolve().as_uri())
        d.save_screenshot(str(out / "screenshot.png"))
    finally:
        d.quit()
    import pypdfium2 as pdfium

    pdf = pdfium.PdfDocument(str(out / "report.pdf"))
    try:
        for i in range(len(pdf)):
            pdf[i].render(scale=PAGE_SCALE).to_pil().save(
                out / f"pdf-page-{i + 1}.png", optimize=True)
        pages = len(pdf)
    finally:
        pdf.close()
    (out / "report.pdf").unlink()
    print(f"wrote {out}/report.html, screenshot.png and {pages} PDF pages as PNG")
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
