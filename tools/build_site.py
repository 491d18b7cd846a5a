#!/usr/bin/env python3
"""Build the documentation site into ``build/site/`` (``make docs``).

Assembles ``build/site-src/`` and runs Sphinx on it with ``docs/conf.py``:

* ``index.md`` — what navlib is (``docs/home.md``), the claims by verdict per paper, each paper's verdict
  matrix with thumbnails (``tools/ledger.py``, from the results files), the two commands, how to cite
  (``CITATION.cff``);
* ``chapters/`` — the executed notebooks that ``make reproduce`` wrote to ``build/`` (not executed
  again), code cells collapsible, names such as ``nf.resolve`` in the text linked to the API reference;
* ``ledger.md`` — every check of every notebook with its claim's verdict, filterable by paper and verdict;
* ``api/`` — one page per public module (autodoc over the numpydoc docstrings), an index by group (core,
  filters, paper companions);
* ``course`` — the course page for teachers (``docs/course.md``, with the run times of the last runs);
* ``conventions``, ``claims`` (``docs/``), ``own-data``, ``robustness`` (README sections: one source),
  ``benchmarks`` (README section and the last ``build/bench.json`` when present).

MathJax 3 is copied from ``docs/node_modules`` (``docs/package.json``, installed with ``npm ci``) into
the site: nothing is loaded from outside it. ``tests/test_site.py`` opens every page in headless Chromium.
"""

from __future__ import annotations

import argparse
import ast
import html
import importlib
import json
import pkgutil
import posixpath
import re
import shutil
import sys
import time
from collections import Counter
from pathlib import Path

import nbformat
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import ledger  # noqa: E402

README_PAGES = {"own-data": "Your own data", "robustness": "Robustness: what each filter does with bad data"}
WIDGET_MIME = "application/vnd.jupyter.widget-view+json"
VERDICT_CSS = {v: f"verdict-{i}" for i, v in enumerate(ledger.COLUMNS)} | {ledger.EXTENSION: "verdict-ext"}


REPO_FILES = "https://github.com/navlib-repro/navlib/blob/main/"


def absolute_links(markdown: str, base: str = "", anchors: str = "") -> str:
    """Markdown links to repository files (relative to ``base``, a folder of the repository) made absolute; with
    ``anchors`` (a file of the repository), links to its sections (``#...``) too."""

    def repl(m):
        return f"]({REPO_FILES}{posixpath.normpath(f'{base}/{m.group(1)}' if base else m.group(1))})"

    markdown = re.sub(r"\]\((?!https?:|#|mailto:)([^)\s]+)\)", repl, markdown)
    if not anchors:
        return markdown
    here = {slug(h) for h in re.findall(r"^#+ (.*)$", markdown, re.M)}
    return re.sub(
        r"\]\(#([^)\s]+)\)", lambda m: m.group(0) if m.group(1) in here else f"]({REPO_FILES}{anchors}#{m.group(1)})", markdown
    )


def slug(heading: str) -> str:
    """The anchor of a Markdown heading (GitHub's and myst's rule: lower case, punctuation dropped, spaces to -)."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def readme_section(title: str) -> str:
    """The README section under ``## title`` (up to the next ``## ``), links to repository files made absolute."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    start = text.index(f"\n## {title}\n")
    end = text.find("\n## ", start + 1)
    return absolute_links(text[start + 1 : end if end > 0 else None], anchors="README.md")


# ----------------------------------------------------------------------------------------------- chapters
def aliases(nb) -> dict[str, str]:
    """Names the notebook's code binds to navlib modules: ``nf`` -> ``navlib.papers.north_finding``."""
    out = {"navlib": "navlib"}
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        src = "\n".join(line for line in cell.source.splitlines() if not line.lstrip().startswith(("%", "!")))
        try:
            tree = ast.parse(src)
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("navlib"):
                for a in node.names:
                    out[a.asname or a.name] = f"{node.module}.{a.name}"
            elif isinstance(node, ast.Import):
                out.update({a.asname or a.name: a.name for a in node.names if a.name.startswith("navlib")})
    return out


def public_target(dotted: str) -> str | None:
    """``dotted`` if it names a public navlib module or a name in its module's ``__all__``."""
    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            module = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        rest = parts[k:]
        if not rest:
            return dotted
        if len(rest) == 1 and rest[0] in getattr(module, "__all__", ()):
            return dotted
        return None
    return None


CODE_NAME = re.compile(r"`([A-Za-z_][\w]*(?:\.[A-Za-z_]\w*)+)(\(\))?`")


def link_names(markdown: str, names: dict[str, str]) -> str:
    """`` `nf.resolve` `` -> a MyST cross-reference to ``navlib.papers.north_finding.resolve``."""

    def repl(m):
        head, _, tail = m.group(1).partition(".")
        if head not in names:
            return m.group(0)
        target = public_target(f"{names[head]}.{tail}")
        return f"{{py:obj}}`{m.group(1)}{m.group(2) or ''} <{target}>`" if target else m.group(0)

    return CODE_NAME.sub(repl, markdown)


BINDER = "https://mybinder.org/v2/gh/navlib-repro/navlib/HEAD?labpath=notebooks%2F"
CAPTION = re.compile(r"^\*(Figure[^*]+)\*", re.M)


def plain(markdown: str) -> str:
    """Markdown and TeX marks removed: text for an image's alt attribute."""
    return re.sub(r"[*_`$\\]|\{[^}]*\}|\[([^]]*)\]\([^)]*\)", lambda m: m.group(1) or "", markdown).strip()


def markdown_of(cell) -> list[str]:
    """A cell's Markdown: its source (a text cell) or its Markdown outputs (a code cell, e.g. ``repro.caption``)."""
    if cell.cell_type == "markdown":
        return [cell.source]
    return ["".join(o["data"]["text/markdown"]) for o in cell.get("outputs", []) if "text/markdown" in o.get("data", {})]


def figure_alt(cells: list, i: int) -> str:
    """Alt text of the figure code cell ``i`` draws: its caption (``*Figure ...*``, printed by the cell or by the
    next cell, or written in the next text cell), else the cell's first comment or title."""
    for text in markdown_of(cells[i]) + (markdown_of(cells[i + 1]) if i + 1 < len(cells) else []):
        m = CAPTION.search(text)
        if m:
            return plain(m.group(1))
    title = re.search(r"set_title\(\s*f?[\"']([^\"']+)|suptitle\(\s*f?[\"']([^\"']+)|^# (.+)$", cells[i].source, re.M)
    return plain("Figure: " + next(g for g in title.groups() if g)) if title else "Figure: see the text around it"


def anchor(kind: str, name: str) -> str:
    """The HTML id of a check, claim or figure (``check-P000-FIG4-BANDS-all``): letters, digits, - and _ only."""
    return f"{kind}-" + re.sub(r"[^A-Za-z0-9_-]", "-", name)


CHECK_ROW = re.compile(r"<th>([A-Z][A-Z0-9]*[-/][^<\s]*)</th>")
SAVEFIG = re.compile(r"savefig\(\s*\w+\s*,\s*f?[\"']([^\"']+)[\"']")


def link_check_rows(table_html: str, seen: set[str], checks: set[str]) -> str:
    """A chapter's check table with each of the notebook's ``checks`` linked to its ledger row (and the first row of
    a check given the anchor the ledger links back to)."""

    def repl(m):
        name = m.group(1)
        if name not in checks:
            return m.group(0)
        ident = "" if name in seen else f" id='{anchor('check', name)}'"
        seen.add(name)
        return f"<th{ident}><a href='../ledger.html#{anchor('check', name)}'>{name}</a></th>"

    return CHECK_ROW.sub(repl, table_html)


def figure_links(name: str, claims: list[str]) -> str:
    """Under a chapter figure: its anchor and the ledger rows of the claims it shows."""
    links = ", ".join(f"<a href='../ledger.html#{anchor('claim', c)}'>{c}</a>" for c in claims)
    return f"<p class='ledger-links' id='{anchor('fig', name)}'>{'Ledger: ' + links if links else ''}</p>"


def launch_links(stem: str) -> str:
    """Links under a chapter's title: run it in Binder (JupyterLab, the repository's binder/ environment) or download it."""
    return (
        f"<p class='launch-links'><a href='{BINDER}{stem}.ipynb'>Run this chapter in Binder</a>"
        f"<a href='../_sources/chapters/{stem}.ipynb' download>Download the notebook (.ipynb)</a></p>"
    )


ERRATUM = re.compile(r"^> \*\*(Erratum [^*]+?)\.?\*\*(.*?)(?=\n(?!>)|\Z)", re.M | re.S)


def inline_math_html(text: str) -> str:
    """``$x$`` as the HTML Sphinx writes for inline maths (MathJax typesets it inside raw HTML too)."""
    return re.sub(
        r"\$([^$]+)\$", lambda m: f"<span class='math notranslate nohighlight'>\\({html.escape(m.group(1))}\\)</span>", text
    )


def fold_errata(markdown: str) -> str:
    """Each erratum box (a quote opening with **Erratum ...**) folded under its title: the reproduction details
    stay complete, one click away."""

    def repl(m):
        body = re.sub(r"^> ?", "", m.group(2), flags=re.M).strip()
        return f"<details class='erratum'><summary>{inline_math_html(m.group(1))}</summary>\n\n{body}\n\n</details>"

    return ERRATUM.sub(repl, markdown)


def stage_notebook(src: Path, dest: Path, claims_by_figure: dict[str, list[str]], checks: set[str]) -> None:
    """Copy an executed notebook for the site: code collapsible, widget views dropped, API names linked, figures
    given their caption as alt text and linked to the ledger rows of their claims, check tables linked to the
    ledger, launch and download links under the title."""
    nb = nbformat.read(src, as_version=4)
    names = aliases(nb)
    cells, seen = [], set()
    for i, cell in enumerate(nb.cells):
        cells.append(cell)
        if cell.cell_type != "code":
            continue
        for out in cell.get("outputs", []):
            if "text/html" in out.get("data", {}):
                out["data"]["text/html"] = link_check_rows("".join(out["data"]["text/html"]), seen, checks)
        if any("image/png" in o.get("data", {}) for o in cell.get("outputs", [])):
            cell.metadata.setdefault("mystnb", {})["image"] = {"alt": figure_alt(nb.cells, i)}
            for name in SAVEFIG.findall(cell.source):
                cells.append(nbformat.v4.new_markdown_cell(figure_links(name, claims_by_figure.get(name, []))))
    nb.cells = cells
    title = next(c for c in nb.cells if c.cell_type == "markdown")
    title.source = re.sub(r"^(# .*)$", lambda m: f"{m.group(1)}\n\n{launch_links(src.stem)}", title.source, count=1, flags=re.M)
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            cell.source = fold_errata(absolute_links(link_names(cell.source, names), base="notebooks"))
        elif cell.cell_type == "code":
            tags = cell.metadata.setdefault("tags", [])
            if "hide-input" not in tags and "# your code here" not in cell.source:  # an exercise's stub stays shown
                tags.append("hide-input")
            kept = []
            for out in cell.get("outputs", []):
                if WIDGET_MIME in out.get("data", {}):
                    continue  # live controls need a kernel (their text fallback is a repr); the static figure stays
                kept.append(out)
            cell.outputs = kept
    nb.metadata.pop("widgets", None)
    nbformat.write(nb, dest)


# ------------------------------------------------------------------------------------------------- ledger
def fmt(x, unit: str = "") -> str:
    if x is None:
        return ""
    s = f"{x:.6g}" if isinstance(x, (int, float)) else str(x)
    return f"{s} {unit}".strip()


def counts_table(leds: list[ledger.PaperLedger]) -> str:
    head = "".join(f"<th>{h}</th>" for h in ("paper", "claims", *ledger.COLUMNS, "checks passed"))
    rows, total = [], Counter()
    for led in leds:
        total.update(led.counts)
        short = f"{led.stem[:2]} {led.title.split(' — ')[0]}"  # "01 Tan & Xie"
        cells = [
            f"<a href='chapters/{led.stem}.html' title='{html.escape(led.title)}'>{html.escape(short)}</a>",
            str(len(led.rows)),
            *(str(led.counts.get(v, 0)) for v in ledger.COLUMNS),
            f"{led.checks_passed}/{led.checks_total}",
        ]
        rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    cells = [
        "<b>all papers</b>",
        str(sum(len(led.rows) for led in leds)),
        *(str(total.get(v, 0)) for v in ledger.COLUMNS),
        f"{sum(led.checks_passed for led in leds)}/{sum(led.checks_total for led in leds)}",
    ]
    rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    return scroll_x(f"<table class='counts'><thead><tr>{head}</tr></thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>")


def scroll_x(table: str) -> str:
    """An HTML table in a box that scrolls sideways when the table is wider than the column (a phone)."""
    return f"<div class='scroll-x'>{table}</div>"


def verdict_span(verdict: str) -> str:
    return f"<span class='verdict {VERDICT_CSS[verdict]}'>{html.escape(verdict)}</span>"


def claims_matrix(led: ledger.PaperLedger, rows_of: str = "rows") -> str:
    """Every claim of a paper (or, with ``rows_of="extensions"``, the project's own quantities around it): paper
    item, paper value, ours, verdict (with its reason) and thumbnail."""
    rows = []
    for r in getattr(led, rows_of):
        thumb = (
            f"<a href='chapters/{r.stem}.html#{anchor('fig', Path(r.figure).stem)}'><img src='{r.figure}' width='110' "
            f"alt='{html.escape(r.claim)}: figure in the chapter'></a>"
            if r.figure
            else ""
        )
        why = ledger.verdict_text(r)[len(r.verdict) :].lstrip(": ")
        cells = [
            html.escape(r.item),
            f"<code>{html.escape(r.claim)}</code><br><small>{html.escape(r.quantity)}</small>",
            html.escape(r.paper),
            html.escape(r.ours),
            verdict_span(r.verdict) + (f"<br><small>{html.escape(why)}</small>" if why else ""),
            thumb,
        ]
        rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
        if r.real is not None:  # the claim's second verdict, on a committed real recording
            real = r.real
            why = ledger.verdict_text(real)[len(real.verdict) :].lstrip(": ")
            cells = [
                "↳ real data",
                f"<small>{html.escape(real.stem)}</small>",
                html.escape(real.paper),
                html.escape(real.ours),
                verdict_span(real.verdict) + (f"<br><small>{html.escape(why)}</small>" if why else ""),
                f"<img src='{real.figure}' width='110' alt='{html.escape(r.claim)} on real data'>" if real.figure else "",
            ]
            rows.append("<tr class='real-data'>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    head = "".join(f"<th>{h}</th>" for h in ("paper item", "claim", "paper", "ours", "verdict", "figure"))
    return scroll_x(f"<table class='matrix'><thead><tr>{head}</tr></thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>")


def ledger_rows(led: ledger.PaperLedger, stem: str, res: dict | None) -> list[str]:
    """One row per check of the paper's notebook ``stem`` (with its claim's verdict), one per claim without checks
    whose verdict it records (the first notebook also takes the claims without any verdict)."""
    by_check = {n: r for r in (*led.rows, *led.extensions) for n in r.checks}
    rows, claimed = [], set()
    for c in (res or {}).get("checks", []):
        claim = by_check.get(c["name"])
        verdict = claim.verdict if claim else "no claim"
        unit = c.get("unit") or ""
        if c.get("expected") is not None:
            target = f"{fmt(c['expected'], unit)} ± {fmt(c.get('tol'))}"
        else:
            lo, hi = c.get("lower"), c.get("upper")
            target = (
                "outside " if c.get("outside") else ""
            ) + f"[{fmt(lo) if lo is not None else '−∞'}, {fmt(hi) if hi is not None else '∞'}] {unit}".strip()
        first = claim is not None and claim.claim not in claimed
        claimed.add(claim.claim if claim else "")
        back = f"chapters/{stem}.html#{anchor('check', c['name'])}"
        cells = [
            html.escape(led.stem[:2]),
            f"<a href='{back}'><code>{html.escape(c['name'])}</code></a>",
            html.escape(c.get("paper_value") or ""),
            html.escape(fmt(c.get("value"), unit)),
            html.escape(target),
            "pass" if c.get("passed") else "<b>FAIL</b>",
            (f"<span id='{anchor('claim', claim.claim)}'></span>" if first else "")
            + (verdict_span(verdict) if claim else "<small>(check beyond the catalogue)</small>"),
            html.escape(c.get("source", "")),
        ]
        rows.append(
            f"<tr data-paper='{led.stem[:2]}' data-verdict='{html.escape(verdict)}' id='{anchor('check', c['name'])}'>"
            + "".join(f"<td>{x}</td>" for x in cells)
            + "</tr>"
        )
    for r in led.rows:
        if not r.checks and (r.stem or led.stem) == stem:
            cells = [
                html.escape(led.stem[:2]),
                f"<code id='{anchor('claim', r.claim)}'>{html.escape(r.claim)}</code> <small>(claim, no check)</small>",
                html.escape(r.paper),
                html.escape(r.ours),
                "",
                "",
                verdict_span(r.verdict),
                html.escape(ledger.verdict_text(r)[len(r.verdict) :].lstrip(": ")),  # why not checkable, and the reason
            ]
            rows.append(
                f"<tr data-paper='{led.stem[:2]}' data-verdict='{html.escape(r.verdict)}'>"
                + "".join(f"<td>{x}</td>" for x in cells)
                + "</tr>"
            )
    return rows


def ledger_page(leds: list[ledger.PaperLedger], build: Path) -> str:
    rows = [row for led in leds for stem in led.stems for row in ledger_rows(led, stem, ledger.results(build, stem))]
    papers = "".join(f"<button data-filter='paper' data-value='{led.stem[:2]}'>{html.escape(led.stem)}</button>" for led in leds)
    verdicts = "".join(
        f"<button data-filter='verdict' data-value='{html.escape(v)}'>{html.escape(v)}</button>"
        for v in (*ledger.COLUMNS, "no claim")
    )
    head = "".join(
        f"<th>{h}</th>" for h in ("nb", "check", "paper value", "ours", "target or bound", "result", "claim verdict", "source")
    )
    return "\n".join(
        [
            "# The ledger: every check",
            "",
            "A *claim* is a statement of a paper; a *check* is one computed comparison in a notebook (its value "
            "computed by navlib from simulated or committed data). Each row is a check with the verdict of the claim "
            "it supports; claims that rest on no check (not checkable here) have a row of their own. How verdicts "
            "are given: [the claims catalogue](claims.md).",
            "",
            "<div class='ledger-filters'>",
            f"<p>Paper: <button data-filter='paper' data-value='' class='active'>all</button>{papers}</p>",
            f"<p>Verdict: <button data-filter='verdict' data-value='' class='active'>all</button>{verdicts}</p>",
            "<p><span id='ledger-count'></span> rows shown</p>",
            "</div>",
            "",
            f"<div class='scroll-x'><table id='ledger' class='ledger'><thead><tr>{head}</tr></thead><tbody>",
            *rows,
            "</tbody></table></div>",
            "",
        ]
    )


# --------------------------------------------------------------------------------------------------- home
def citation() -> str:
    import yaml

    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    lines = [
        f"{cff['authors'][0]['name']} ({cff['date-released'][:4]}). *{cff['title']}*, version {cff['version']}. "
        f"<{cff['repository-code']}>",
        "",
        "and the paper whose method you use:",
        "",
    ]
    for ref in cff.get("references", []):
        who = ", ".join(f"{a['family-names']} {a['given-names'][0]}." for a in ref["authors"])
        year = f" ({ref['year']})" if "year" in ref else ""
        doi = f" doi:{ref['doi']}" if "doi" in ref else ""
        lines.append(f"* {who}{year}. {ref['title']}. *{ref['journal']}*.{doi} ({ref['notes'].split('.')[0]})")
    return "\n".join(lines)


def home_page(leds: list[ledger.PaperLedger], chapters: list[str]) -> str:
    matrices = []
    for led in leds:
        counts = ", ".join(f"{led.counts[v]} {v}" for v in ledger.COLUMNS if led.counts.get(v))
        labels = [s[:2] + (chr(ord("a") + i) if i else "") for i, s in enumerate(led.stems)]  # 05, 05b, ...
        links = ", ".join(f"<a href='chapters/{s}.html'>chapter {label}</a>" for s, label in zip(led.stems, labels, strict=True))
        matrices += [
            f"<details><summary><b>{html.escape(led.title)}</b> — {len(led.rows)} claims: "
            f"{html.escape(counts)} ({links})</summary>",
            claims_matrix(led),
            "</details>",
            "",
        ]
        if led.extensions:
            matrices += [
                f"<details><summary>{html.escape(led.stem[:2])}: {len(led.extensions)} extensions (the project's "
                "own quantities, no paper verdict)</summary>",
                claims_matrix(led, "extensions"),
                "</details>",
                "",
            ]
    return "\n".join(
        [
            (ROOT / "docs" / "home.md").read_text(encoding="utf-8").rstrip(),
            "",
            "**Teaching with these chapters?** [The course page](course.md) gives an order, 45- and 90-minute lesson "
            "plans, parameters to hand out and the run times.",
            "",
            "## The papers' claims and their verdicts",
            "",
            "Claims by verdict (counted from the results of the last `make reproduce`; the full list of checks is in "
            "[the ledger](ledger.md)):",
            "",
            counts_table(leds),
            "",
            "Each paper's verdict matrix (open a paper):",
            "",
            *matrices,
            "## Two commands",
            "",
            "```bash",
            "git clone https://github.com/navlib-repro/navlib.git && cd navlib",
            "make reproduce   # set up .venv, execute every notebook, write build/ (figures, results, this site's input)",
            "make test        # unit and property tests, and every notebook (reused from make reproduce when up to date)",
            "```",
            "",
            "`make docs` builds this site from the executed notebooks into `build/site/`.",
            "",
            "## How to cite",
            "",
            citation(),
            "",
            "```{toctree}",
            ":caption: Chapters",
            ":maxdepth: 1",
            ":hidden:",
            "",
            *[f"chapters/{c}" for c in chapters],
            "```",
            "",
            "```{toctree}",
            ":caption: Reference",
            ":maxdepth: 1",
            ":hidden:",
            "",
            "course",
            "ledger",
            "claims",
            "conventions",
            "own-data",
            "robustness",
            "benchmarks",
            "api/index",
            "```",
            "",
        ]
    )


# ---------------------------------------------------------------------------------------------------- API
def public_modules() -> dict[str, list[str]]:
    import navlib

    groups = {"Core": [], "Filters": [], "Paper companions": []}
    for info in pkgutil.walk_packages(navlib.__path__, "navlib."):
        if any(part.startswith("_") for part in info.name.split(".")) or info.ispkg and info.name != "navlib.papers":
            continue
        group = (
            "Filters"
            if info.name.startswith("navlib.filters.")
            else "Paper companions"
            if info.name.startswith("navlib.papers")
            else "Core"
        )
        groups[group].append(info.name)
    return {g: sorted(m) for g, m in groups.items()}


def api_pages(dest: Path) -> None:
    """One page per public module (autodoc over its numpydoc docstrings), listed by group on the index."""
    index = [
        "# API reference",
        "",
        "Every public name of navlib, one page per module, from its docstrings (shapes and units in each). The "
        "paper companions (`navlib.papers.*`) give the paper's equations with their numbers.",
        "",
    ]
    pages = []
    for group, modules in public_modules().items():
        index += [f"## {group}", ""]
        for module in modules:
            pages.append(module)
            summary = (importlib.import_module(module).__doc__ or "").strip().splitlines()[0]
            index.append(f"* [`{module}`]({module}.md): {summary}")
            (dest / f"{module}.md").write_text(
                f"# `{module}`\n\n```{{eval-rst}}\n.. automodule:: {module}\n```\n", encoding="utf-8"
            )
        index.append("")
    index += ["```{toctree}", ":hidden:", "", *pages, "```", ""]
    (dest / "index.md").write_text("\n".join(index), encoding="utf-8")


def course_page(build: Path) -> str:
    """``docs/course.md`` with the run times of the last ``make reproduce`` (``build/summary.json``) and of the
    teaching-mode runs of ``tests/test_teaching.py`` (``build/teaching/``) filled in."""
    summary = json.loads((build / "summary.json").read_text(encoding="utf-8"))
    rows = [
        "Full runs, from the last `make reproduce` (numba's compilation on a first run is counted apart; "
        "later runs load the compiled code from the cache):",
        "",
        "| chapter | full run | of which compiling | peak memory |",
        "| --- | --- | --- | --- |",
    ]
    rows += [
        f"| {stem} | {r['seconds']:.0f} s | {r.get('compile_seconds', 0):.0f} s | {r.get('peak_mb', 0):.0f} MB |"
        for stem, r in sorted(summary.items())
    ]
    runs = (
        sorted(
            (json.loads(p.read_text(encoding="utf-8")) for p in (build / "teaching").glob("*.json")), key=lambda r: r["notebook"]
        )
        if (build / "teaching").is_dir()
        else []
    )
    rows += [
        "",
        "Teaching + fast mode with a parameter changed, from each run's last execution "
        "(`make test` runs it when out of date; tests/test_teaching.py):",
        "",
    ]
    if runs:
        rows += ["| chapter | change | run | checks held |", "| --- | --- | --- | --- |"]
        rows += [
            f"| {r['notebook']} | {', '.join(f'`{k} = {v}`' for k, v in r['parameters'].items())} | "
            f"{r['seconds']:.0f} s | {r['checks_held']} |"
            for r in runs
        ]
    else:
        rows.append("*No teaching-mode runs recorded in this build: `make test` records them.*")
    text = (ROOT / "docs" / "course.md").read_text(encoding="utf-8")
    return text.replace("@RUN_TIMES@", "\n".join(rows))


def benchmarks_page(build: Path, out_dir: Path) -> str:
    parts = [readme_section("Benchmarks").replace("## Benchmarks", "# Benchmarks", 1), ""]
    bench = build / "bench.json"
    if bench.is_file():
        data = json.loads(bench.read_text(encoding="utf-8"))
        m = data.get("machine", {})
        parts += [
            "## The last `make bench` on this machine",
            "",
            f"Python {m.get('python', '?')}, {m.get('cpus', '?')} CPUs, {m.get('platform', '?')}"
            + (" (quick run)" if data.get("quick") else "")
            + ".",
            "",
            "| case | implementation | throughput | goal | note |",
            "|---|---|---|---|---|",
        ]
        for r in data.get("results", []):
            goal = "" if r.get("goal") is None else f"{r['goal']:.4g} {r['unit']}"
            parts.append(
                f"| {r['case']} | {r['implementation']} | {r['throughput']:.4g} {r['unit']} | {goal} | {r.get('note', '')} |"
            )
    else:
        parts += ["*No `build/bench.json` yet: run `make bench`.*"]
    growth = build / "bench-growth.json"
    if growth.is_file():
        parts += [
            "",
            "## Cost growth",
            "",
            "Time of each kernel against its size, each size in a fresh interpreter "
            "(`bench/cases_growth.py`); the dashed line has slope 1 (linear in the work).",
            "",
            f"```{{image}} {growth_figure(json.loads(growth.read_text(encoding='utf-8')), out_dir)}",
            ":alt: Run time against problem size for each main kernel, on log-log axes, with a slope-1 line",
            "```",
        ]
    return "\n".join(parts) + "\n"


def growth_figure(curves: dict, out_dir: Path) -> str:
    """The growth curves of ``make bench`` as a log-log figure in the site's sources; returns its file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.2), layout="constrained")
    for name, c in curves.items():
        ax.loglog(c["sizes"], c["seconds"], "o-", ms=3, label=f"{name} (N^{c['exponent']:.2f})")
    n = np.array([1e3, 1e7])
    ax.loglog(n, 1e-7 * n, "k--", lw=0.8, label="slope 1")
    ax.set(xlabel="samples (or trials) N", ylabel="time (s)", title="Cost growth of the main kernels")
    ax.legend(fontsize=7)
    fig.savefig(out_dir / "growth.png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    return "growth.png"


# ------------------------------------------------------------------------------------------------- build
def stage(build: Path, src: Path) -> list[str]:
    """Write the site's sources into ``src``; return the chapter names."""
    notebooks = sorted(p for p in build.glob("[0-9][0-9]_*.ipynb"))
    if not notebooks or not (build / "summary.json").is_file():
        raise SystemExit(f"no executed notebooks in {build}: run `make reproduce` first")
    shutil.rmtree(src, ignore_errors=True)
    for d in ("chapters", "api", "_extra"):
        (src / d).mkdir(parents=True)
    shutil.copytree(ROOT / "docs" / "_static", src / "_static")  # styles, scripts, favicon, CJK font
    chapters = []
    leds = [led for led in ledger.ledgers(build) if led.stem in {nb.stem for nb in notebooks}]
    for nb in notebooks:
        claims_by_figure: dict[str, list[str]] = {}
        for led in leds:
            for r in led.rows:
                if r.figure and r.stem == nb.stem:
                    claims_by_figure.setdefault(Path(r.figure).stem, []).append(r.claim)
        in_ledger = any(nb.stem in led.stems for led in leds)  # chapters of a paper; 00 and 06 have none
        checks = {c["name"] for c in (ledger.results(build, nb.stem) or {}).get("checks", [])} if in_ledger else set()
        stage_notebook(nb, src / "chapters" / nb.name, claims_by_figure, checks)
        chapters.append(nb.stem)
        if (build / nb.stem / "figures").is_dir():  # thumbnails of the home page and the ledger
            shutil.copytree(build / nb.stem / "figures", src / "_extra" / nb.stem / "figures")
    for led in leds:
        for p in led.problems:
            print(f"warning: {led.stem}: {p}", file=sys.stderr)
    (src / "index.md").write_text(home_page(leds, chapters), encoding="utf-8")
    (src / "ledger.md").write_text(ledger_page(leds, build), encoding="utf-8")
    for name in ("conventions", "claims"):
        shutil.copy(ROOT / "docs" / f"{name}.md", src / f"{name}.md")
    (src / "course.md").write_text(course_page(build), encoding="utf-8")
    for page, title in README_PAGES.items():
        (src / f"{page}.md").write_text(readme_section(title).replace("## ", "# ", 1), encoding="utf-8")
    (src / "benchmarks.md").write_text(benchmarks_page(build, src), encoding="utf-8")
    api_pages(src / "api")
    mathjax = ROOT / "docs" / "node_modules" / "mathjax" / "es5"
    if not mathjax.is_dir():
        raise SystemExit("no docs/node_modules/mathjax: run `npm ci --prefix docs` (make docs does)")
    # the one combined component the site loads (tex-mml-chtml.js) and what it loads on demand
    other_builds = [p.name for p in mathjax.glob("*.js") if p.name != "tex-mml-chtml.js"]
    shutil.copytree(mathjax, src / "_static" / "mathjax", ignore=lambda d, names: other_builds if Path(d) == mathjax else [])
    shutil.copy(ROOT / "docs" / "conf.py", src / "conf.py")
    return chapters


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", type=Path, default=ROOT / "build", help="where make reproduce wrote its outputs")
    ap.add_argument("--out", type=Path, default=None, help="the site (default: <build>/site)")
    args = ap.parse_args(argv)
    build = args.build.resolve()
    out = (args.out or build / "site").resolve()
    src = build / "site-src"
    start = time.perf_counter()
    chapters = stage(build, src)
    from sphinx.cmd.build import build_main

    shutil.rmtree(out, ignore_errors=True)
    warnings = build / "site-warnings.txt"
    rc = build_main(["-b", "html", "-q", "-j", "2", "-W", "--keep-going", "-w", str(warnings), str(src), str(out)])
    print(f"site: {out / 'index.html'} ({len(chapters)} chapters, {time.perf_counter() - start:.1f} s)")
    return rc


if __name__ == "__main__":
    sys.exit(main())
