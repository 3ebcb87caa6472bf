"""Headless Chromium for the campaign report (:mod:`propwhirl.app.report`): printing the HTML
page to PDF (``propwhirl certify``'s ``report.pdf``) and opening it as a reader would (the
report's browser test, through selenium: the ``report`` extra).

The browser is the distribution's (Debian: ``apt-get install chromium chromium-driver``; the
set-up in the README); no browser is downloaded.  It is found as ``$PROPWHIRL_CHROMIUM`` or
``chromium`` / ``chromium-browser`` / ``google-chrome`` on the PATH (:func:`find_chromium`),
and started headless with no sandbox, no GPU, no network services and a fresh profile in a
temporary folder (:data:`FLAGS`), so it runs as root, in containers and offline.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from propwhirl import fileio
from propwhirl import validate as v

#: The command-line flags every headless Chromium gets (plus a fresh ``--user-data-dir``).
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-dev-shm-usage", "--hide-scrollbars")
#: The names of the browser's executable tried on the PATH.
NAMES = ("chromium", "chromium-browser", "google-chrome")
#: How to install the browser (said where it is missing).
INSTALL_HINT = ("install Chromium from your distribution, e.g. as root on Debian/Ubuntu: "
                "apt-get install -y chromium chromium-driver (or set PROPWHIRL_CHROMIUM to a "
                "Chromium executable)")
#: Seconds a PDF print may take before it is abandoned.
PRINT_TIMEOUT_S = 120.0


def find_chromium() -> str | None:
    """The Chromium executable: ``$PROPWHIRL_CHROMIUM`` when set (it must exist), else the
    first of :data:`NAMES` on the PATH; None when there is none."""
    env = os.environ.get("PROPWHIRL_CHROMIUM")
    if env:
        return env if Path(env).is_file() and os.access(env, os.X_OK) else None
    for name in NAMES:
        found = shutil.which(name)
        if found:
            return found
    return None


def find_chromedriver() -> str | None:
    """The chromedriver executable beside the distribution's Chromium (``chromium-driver``),
    ``$PROPWHIRL_CHROMEDRIVER`` when set; None when there is none."""
    env = os.environ.get("PROPWHIRL_CHROMEDRIVER")
    if env:
        return env if Path(env).is_file() and os.access(env, os.X_OK) else None
    return shutil.which("chromedriver")


def print_pdf(html: str | Path, pdf: str | Path, chromium: str | None = None) -> Path:
    """Print the page `html` (a file) to `pdf` with headless Chromium (A4, backgrounds, no
    header or footer); the PDF written atomically.  InputError when no browser is found or
    the print fails (naming the browser's last line of output)."""
    exe = chromium or find_chromium()
    if exe is None:
        raise v.InputError(f"cannot print {pdf}: no Chromium found: {INSTALL_HINT}")
    src = Path(html).resolve()
    with tempfile.TemporaryDirectory(prefix="propwhirl-chromium-") as tmp:
        out = Path(tmp) / "page.pdf"
        cmd = [exe, *FLAGS, f"--user-data-dir={Path(tmp) / 'profile'}", "--no-pdf-header-footer",
               f"--print-to-pdf={out}", src.as_uri()]
        try:
            done = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                                  timeout=PRINT_TIMEOUT_S, check=False)
        except (OSError, subprocess.TimeoutExpired) as exc:
            raise v.InputError(f"cannot print {pdf} with {exe}: {exc}") from None
        if not out.is_file() or out.stat().st_size == 0:
            last = (done.stderr.strip().splitlines() or ["no output"])[-1]
            raise v.InputError(f"cannot print {pdf} with {exe} (exit code {done.returncode}): "
                               f"{last}")
        data = out.read_bytes()
    return fileio.write_bytes(pdf, data, what="PDF report")


def webdriver(width: int = 1200, height: int = 900):
    """A selenium WebDriver of the distribution's headless Chromium (:data:`FLAGS`, a fresh
    profile), a window of `width` × `height` pixels.  InputError naming what is missing (the
    ``report`` extra, Chromium, chromedriver).  The caller quits it (``driver.quit()``)."""
    try:
        from selenium import webdriver as wd
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        raise v.InputError("opening the report in a browser needs selenium: pip install "
                           "propwhirl[report]") from None
    exe, driver = find_chromium(), find_chromedriver()
    if exe is None or driver is None:
        missing = "Chromium" if exe is None else "chromedriver"
        raise v.InputError(f"no {missing} found: {INSTALL_HINT}")
    opts = wd.ChromeOptions()
    opts.binary_location = exe
    profile = tempfile.mkdtemp(prefix="propwhirl-chromium-")
    for flag in (*FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}"):
        opts.add_argument(flag)
    d = wd.Chrome(options=opts, service=Service(executable_path=driver))
    quit_ = d.quit

    def quit_and_clean() -> None:
        try:
            quit_()
        finally:
            shutil.rmtree(profile, ignore_errors=True)

    d.quit = quit_and_clean
    return d
