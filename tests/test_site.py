"""The documentation site (``make docs`` -> ``build/site/``) in a real browser: headless Chromium.

Runs when the site exists (``make docs`` runs it itself; ``make test`` after ``make docs``). The site is
served from a local HTTP server on 127.0.0.1; every page is opened once and must have no console
errors, no failed requests, no request leaving the server and no image that fails to load. At 1280 and 390
px (a phone) every page must show what a reader expects (``tests/site_checks.js``): no MathJax error, no
literal ``$`` or ``\\(`` in the text, no unformatted ``{placeholder}``, nothing wider than the screen or
cut (wide tables and equations scroll inside their own box), real alt text on every image. Every link
inside the site resolves (file and anchor), and the build had no Sphinx warning. A chapter page must show
rendered math (MathJax, served by the site), the ledger's verdict filter must show exactly the rows of the
verdict clicked, and the search page must find "Mahony". Screenshots of every page at both widths go to
``build/site-screenshots/``.

The browser is Debian's ``chromium`` (``make docs`` installs it when missing), driven by Playwright's
Python client; ``NAVLIB_CHROMIUM`` names another binary.
"""

from __future__ import annotations

import functools
import html.parser
import http.server
import os
import posixpath
import shutil
import threading
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "build" / "site"
SHOTS = ROOT / "build" / "site-screenshots"
CHECKS = (Path(__file__).parent / "site_checks.js").read_text(encoding="utf-8")
WIDTHS = (1280, 390)

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
    srv.server_close()


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
        # net::ERR_ABORTED is a request the test's own next navigation cut (Chromium fetches the favicon after
        # "load"); a file that is missing answers 404, caught below, and an image that fails shows as not loaded.
        self.page.on(
            "requestfailed",
            lambda r: r.failure != "net::ERR_ABORTED" and self.problems.append(f"failed: {r.url} ({r.failure})"),
        )
        self.page.on("response", lambda r: r.status >= 400 and self.problems.append(f"HTTP {r.status}: {r.url}"))
        self.page.on(
            "request",
            lambda r: not r.url.startswith((base, "data:", "blob:")) and self.problems.append(f"external request: {r.url}"),
        )

    def open(self, path: str) -> list[str]:
        self.start(path)
        return self.finish()

    def start(self, path: str) -> None:
        """Navigate to ``path`` and return once the new document is committed: Chromium loads it meanwhile."""
        self.problems.clear()
        self.page.goto(self.base + path, wait_until="commit")

    def finish(self) -> list[str]:
        """Wait for the page started last to load, typeset and show its images; its problems."""
        self.page.wait_for_load_state("load")
        # math typeset and web fonts loaded (each a promise that settles at once on a page without them)
        self.page.evaluate(
            "async () => { if (window.MathJax && MathJax.startup) await MathJax.startup.promise; await document.fonts.ready; }"
        )
        broken = self.page.eval_on_selector_all(
            "img", "imgs => imgs.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'))"
        )
        return self.problems + [f"image not loaded: {src}" for src in broken]


def pages() -> list[str]:
    return sorted(
        p.relative_to(SITE).as_posix()
        for p in SITE.rglob("*.html")
        if not p.relative_to(SITE).as_posix().startswith(("_static/", "_sources/", "_extra/"))
    )


@pytest.fixture(scope="module")
def visited(browser, server) -> dict[tuple[str, int], dict]:
    """Every page opened once per width: its load problems, what tests/site_checks.js finds, how much math it
    typeset; a screenshot of each.

    One tab per width (each in its own browser context, so its own renderer process), in step: while one tab's page
    is checked, the other's loads and typesets, so the two widths overlap where a core is free.
    """
    seen = {}
    SHOTS.mkdir(parents=True, exist_ok=True)
    tabs = {width: Watched(browser, server) for width in WIDTHS}
    for width, tab in tabs.items():
        tab.page.set_viewport_size({"width": width, "height": 1400 if width > 600 else 844})
    shown: dict[int, str] = {}  # the page each tab is loading
    for path in [*pages(), None]:
        for width, tab in tabs.items():
            if width in shown:
                loaded = shown.pop(width)
                seen[loaded, width] = look(tab, loaded, width)
            if path is not None:
                tab.start(path)
                shown[width] = path
    return seen


def look(tab: Watched, path: str, width: int) -> dict:
    """What ``tab``, started on ``path``, shows once loaded (its screenshot saved)."""
    problems = tab.finish()
    found = {
        "problems": problems,
        **tab.page.evaluate(CHECKS),
        "display_math": tab.page.locator("mjx-container[display='true']").count(),
        "math": tab.page.locator("mjx-container").count(),
    }
    tab.page.screenshot(path=str(SHOTS / f"{path.replace('/', '-').removesuffix('.html')}-{width}.png"))
    return found


def failing(visited, key: str) -> dict:
    return {f"{path} @ {width} px": v[key][:5] for (path, width), v in visited.items() if v[key]}


def test_every_page_loads_cleanly_offline(visited):
    bad = failing(visited, "problems")
    assert len(visited) >= 20, f"only {len(visited)} page views"
    assert not bad, f"{len(bad)} page views with problems: {dict(list(bad.items())[:5])}"


@pytest.mark.parametrize("defect", ["mathErrors", "literalTex", "placeholders", "pageWidth", "overflowing", "badAlt"])
def test_no_page_shows_a_defect(visited, defect):
    """MathJax errors, TeX left as text, unformatted placeholders, a page wider than the screen, content cut
    or wider than the column, images without real alt text: none on any page at any width."""
    bad = failing(visited, defect)
    assert not bad, f"{defect} on {len(bad)} page views: {dict(list(bad.items())[:4])}"


def test_chapter_math_is_rendered_and_screenshots_are_saved(visited):
    for chapter in (p for p, w in visited if p.startswith("chapters/0") and w == WIDTHS[0]):
        shown = visited[chapter, WIDTHS[0]]["display_math"]
        assert shown > 0 or chapter.startswith("chapters/06"), f"{chapter}: no display equation"
    assert visited["chapters/01_north_finding.html", WIDTHS[0]]["math"] > 10, "inline math not typeset"
    for shot in ("index-1280.png", "chapters-01_north_finding-390.png"):
        assert (SHOTS / shot).stat().st_size > 10_000


def test_the_checks_find_what_a_reader_would_see(browser, server):
    """tests/site_checks.js on a page made broken on purpose: a \\tag inside split (MathJax's error), dollars left
    as text, an unformatted f-string field, an over-wide table and an image whose alt text is its path."""
    page = Watched(browser, server)
    page.page.set_viewport_size({"width": 390, "height": 844})
    page.page.set_content(
        f"<html><head><script src='{server}_static/mathjax/tex-mml-chtml.js'></script></head><body>"
        "<main><div class='math'>\\[\\begin{split}a = b \\tag{1}\\end{split}\\]</div>"
        "<div style='display: flex; flex-direction: row-reverse; overflow-x: auto'>"
        f"<pre style='flex: none; overflow: visible'>{'left-cut ' * 80}</pre></div>"
        "<p>the bias $b$ after {N_TRIALS_LAT // N_TRIALS} trials</p>"
        f"<table><tr><td style='white-space: nowrap'>{'wide cell ' * 80}</td></tr></table>"
        "<img src='data:image/gif;base64,R0lGODlhAQABAAAAACw=' alt='../_images/abc.png'></main></body></html>"
    )
    page.page.evaluate("async () => { await MathJax.startup.promise; }")
    found = page.page.evaluate(CHECKS)
    assert found["mathErrors"] and "split" in found["mathErrors"][0]
    assert found["literalTex"] and found["placeholders"] == ["{N_TRIALS_LAT // N_TRIALS}"]
    assert found["pageWidth"] and found["badAlt"]
    assert any("left of its box" in o for o in found["overflowing"]) and any("wider than" in o for o in found["overflowing"])


class _Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.hrefs, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(a["id"])
        for key in ("href", "src"):
            if a.get(key) and not (tag == "link" and key == "href" and "stylesheet" not in (a.get("rel") or "")):
                self.hrefs.append(a[key])


def test_every_link_inside_the_site_resolves():
    """Every relative link and source of every page names a file of the site, and its anchor exists there."""
    parsed = {}

    def read(page: Path) -> _Links:
        if page not in parsed:
            parsed[page] = _Links()
            parsed[page].feed(page.read_text(encoding="utf-8"))
        return parsed[page]

    broken = []
    for page in SITE.rglob("*.html"):
        if page.relative_to(SITE).parts[0] in ("_static", "_sources"):
            continue
        for href in read(page).hrefs:
            url = urlsplit(href)
            if url.scheme or url.netloc or href.startswith(("mailto:", "javascript:", "data:")):
                continue
            target = page if not url.path else (page.parent / unquote(url.path))
            target = Path(posixpath.normpath(target))
            if target.is_dir():
                target = target / "index.html"
            if not target.is_file():
                broken.append(f"{page.relative_to(SITE)}: {href}")
            elif url.fragment and target.suffix == ".html" and unquote(url.fragment) not in read(target).ids:
                broken.append(f"{page.relative_to(SITE)}: {href} (no such anchor)")
    assert not broken, f"{len(broken)} broken links: {broken[:8]}"


def test_the_site_built_without_warnings():
    """tools/build_site.py runs Sphinx with -W and writes what it warned about to build/site-warnings.txt."""
    warnings = ROOT / "build" / "site-warnings.txt"
    assert warnings.is_file(), "no build/site-warnings.txt: build the site with tools/build_site.py"
    text = warnings.read_text(encoding="utf-8").strip()
    assert not text, f"Sphinx warnings:\n{text[:2000]}"


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
    shown = {
        ch
        for page in SITE.rglob("*.html")
        for ch in re.findall(r"[\u3000-\u303f\u3400-\u9fff\uff00-\uffef]", page.read_text(encoding="utf-8"))
    }
    missing = sorted(ch for ch in shown if ord(ch) not in cmap)
    assert shown and not missing, f"CJK characters without a glyph (regenerate the subset): {''.join(missing)}"


def test_search_finds_mahony(browser, server):
    page = Watched(browser, server)
    assert page.open("search.html?q=Mahony") == []
    page.page.wait_for_selector("#search-results li", timeout=30_000)
    hits = page.page.locator("#search-results li")
    assert hits.count() > 0
    assert any("mahony" in hits.nth(i).inner_text().lower() for i in range(min(hits.count(), 20)))
