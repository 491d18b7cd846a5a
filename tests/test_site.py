"""The documentation site (``make docs`` -> ``build/site/``) in a real browser: headless Chromium.

Runs when the site exists (``make docs`` runs it itself; ``make test`` after ``make docs``). The site is
served from a local HTTP server on 127.0.0.1; every page is opened once and must have no console
errors, no failed requests, no request leaving the server and no image that fails to load. A chapter
page must show rendered math (MathJax, served by the site), the ledger's verdict filter must show
exactly the rows of the verdict clicked, and the search page must find "Mahony". Screenshots of the
home page and chapter 01 go to ``build/site-screenshots/``.

The browser is Debian's ``chromium`` (``make docs`` installs it when missing), driven by Playwright's
Python client; ``NAVLIB_CHROMIUM`` names another binary.
"""
from __future__ import annotations

import functools
import http.server
import os
import shutil
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "build" / "site"
SHOTS = ROOT / "build" / "site-screenshots"

pytestmark = pytest.mark.skipif(not (SITE / "index.html").is_file(), reason="no build/site: run `make docs`")


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


@pytest.fixture(scope="module")
def server():
    srv = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_Quiet, directory=str(SITE)))
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{srv.server_port}/"
    srv.shutdown()


@pytest.fixture(scope="module")
def browser():
    executable = os.environ.get("NAVLIB_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")
    assert executable, "no chromium on PATH: install Debian's chromium package (make docs does) or set NAVLIB_CHROMIUM"
    from playwright.sync_api import sync_playwright
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=executable, args=["--no-sandbox", "--disable-gpu"])
        yield b
        b.close()


class Watched:
    """A page that records console errors, failed requests and requests that leave the site."""

    def __init__(self, browser, base: str):
        self.base = base
        self.page = browser.new_page(viewport={"width": 1280, "height": 1400})
        self.problems: list[str] = []
        self.page.on("console", lambda m: m.type == "error" and self.problems.append(f"console: {m.text}"))
        self.page.on("pageerror", lambda e: self.problems.append(f"script error: {e}"))
        self.page.on("requestfailed", lambda r: self.problems.append(f"failed: {r.url}"))
        self.page.on("response", lambda r: r.status >= 400 and self.problems.append(f"HTTP {r.status}: {r.url}"))
        self.page.on("request", lambda r: not r.url.startswith((base, "data:", "blob:"))
                     and self.problems.append(f"external request: {r.url}"))

    def open(self, path: str) -> list[str]:
        self.problems.clear()
        self.page.goto(self.base + path, wait_until="load")
        # math typeset and web fonts loaded (each a promise that settles at once on a page without them)
        self.page.evaluate("async () => { if (window.MathJax && MathJax.startup) await MathJax.startup.promise;"
                           " await document.fonts.ready; }")
        broken = self.page.eval_on_selector_all(
            "img", "imgs => imgs.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'))")
        return self.problems + [f"image not loaded: {src}" for src in broken]


def pages() -> list[str]:
    return sorted(p.relative_to(SITE).as_posix() for p in SITE.rglob("*.html")
                  if not p.relative_to(SITE).as_posix().startswith(("_static/", "_sources/", "_extra/")))


@pytest.fixture(scope="module")
def visited(browser, server) -> dict[str, dict]:
    """Every page opened once: its problems and how much math it typeset; screenshots of two pages."""
    page, seen = Watched(browser, server), {}
    SHOTS.mkdir(parents=True, exist_ok=True)
    for path in pages():
        problems = page.open(path)
        seen[path] = {"problems": problems, "display_math": page.page.locator("mjx-container[display='true']").count(),
                      "math": page.page.locator("mjx-container").count()}
        if path in ("index.html", "chapters/01_north_finding.html"):
            page.page.screenshot(path=str(SHOTS / ("home.png" if path == "index.html" else "chapter-01.png")))
    return seen


def test_every_page_loads_cleanly_offline(visited):
    bad = {path: v["problems"] for path, v in visited.items() if v["problems"]}
    assert len(visited) >= 10, f"only {len(visited)} pages"
    assert not bad, f"{len(bad)} of {len(visited)} pages with problems: {dict(list(bad.items())[:5])}"


def test_chapter_math_is_rendered_and_screenshots_are_saved(visited):
    chapter = visited["chapters/01_north_finding.html"]
    assert chapter["display_math"] > 0, "no display equation typeset"
    assert chapter["math"] > 10, "inline math not typeset"
    assert (SHOTS / "home.png").stat().st_size > 10_000 and (SHOTS / "chapter-01.png").stat().st_size > 10_000


def test_ledger_filter_shows_the_rows_of_one_verdict(browser, server):
    page = Watched(browser, server)
    assert page.open("ledger.html") == []
    rows = page.page.locator("#ledger tbody tr")
    total = rows.count()
    assert total > 100 and page.page.locator("#ledger-count").inner_text() == str(total)
    for verdict in ("refuted", "not checkable here"):
        expected = page.page.locator(f"#ledger tbody tr[data-verdict='{verdict}']").count()
        page.page.click(f"button[data-filter='verdict'][data-value='{verdict}']")
        assert 0 < expected < total
        assert page.page.locator("#ledger tbody tr:visible").count() == expected
        assert page.page.locator("#ledger-count").inner_text() == str(expected)
    page.page.click("button[data-filter='verdict'][data-value='']")
    assert page.page.locator("#ledger tbody tr:visible").count() == total


def test_cjk_characters_are_in_the_sites_font():
    """Every CJK character a page shows is in the subset font the site serves (docs/_static/fonts)."""
    import re

    from fontTools.ttLib import TTFont
    cmap = TTFont(SITE / "_static" / "fonts" / "NotoSansCJKsc-navlib-subset.woff").getBestCmap()
    shown = {ch for page in SITE.rglob("*.html")
             for ch in re.findall(r"[\u3000-\u303f\u3400-\u9fff\uff00-\uffef]", page.read_text(encoding="utf-8"))}
    missing = sorted(ch for ch in shown if ord(ch) not in cmap)
    assert shown and not missing, f"CJK characters without a glyph (regenerate the subset): {''.join(missing)}"


def test_search_finds_mahony(browser, server):
    page = Watched(browser, server)
    assert page.open("search.html?q=Mahony") == []
    page.page.wait_for_selector("#search-results li", timeout=30_000)
    hits = page.page.locator("#search-results li")
    assert hits.count() > 0
    assert any("mahony" in hits.nth(i).inner_text().lower() for i in range(min(hits.count(), 20)))
