#!/usr/bin/env python3
"""Regenerate the README's results section, its quoted numbers and figure gallery from build/.

Reads ``build/<notebook>/results.json`` (written by the notebooks through ``navlib.repro``) and
``data/claims.csv`` (through ``tools/ledger.py``), and rewrites

* the block between the ``results`` markers of README.md: claims by verdict per paper and each
  notebook's checks passed, the coverage (claims whose verdict rests on a computation), then per
  paper a matrix of its claims (paper item, paper value, ours, verdict, thumbnail), each between
  ``<!-- ledger:<notebook> -->`` markers;
* every number quoted in the README's prose as
  ``<!-- value <notebook> <check name> <format> -->1.14<!-- /value -->``: the text between the markers
  is the check's value formatted with the Python format spec (``x100:.0f`` multiplies by 100 first),
  so a number in prose can never drift from what the notebook computed;
* small copies of the figures of ``GALLERY`` and of every figure a verdict shows, in ``docs/figures/``.

Only deterministic numbers go into the README (no run times), so it can be checked:
``--check`` reports what is stale; ``tests/test_readme.py`` and the root ``conftest.py`` (after
``make test`` ran the notebooks) fail when it is.

Usage: python tools/readme.py [--check]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import re
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))

import ledger  # noqa: E402  (tools/ledger.py)

from navlib.papers import CHAPTERS  # noqa: E402  (notebooks without a paper)

README = ROOT / "README.md"
FIGURES = ROOT / "docs" / "figures"
START, END = "<!-- results:start -->", "<!-- results:end -->"
VALUE = re.compile(r"<!-- value (\S+) (\S+) (\S+) -->(.*?)<!-- /value -->", re.S)
LEDGER = re.compile(r"<!-- ledger:(\S+) -->\n.*?<!-- /ledger:\1 -->", re.S)
SUMMARY_ROW = re.compile(r"^\| `(\d\d_[^`]+)` \|.*\|$", re.M)
# figures shown in the README gallery: (notebook, figure stem)
GALLERY = [
    ("00_conventions_sensors", "allan_gyros"),
    ("00_conventions_sensors", "ins_error_theory"),
    ("01_north_finding", "fig4_rmse_vs_heading"),
    ("02_rotation_bias", "fig6_heading_error"),
    ("03_gauss_kruger_ekf", "fig4_fig5_tracks"),
    ("04_mimu_mag_rtk", "fig4_heading_modes"),
    ("05_pedestrian_ins_floors", "fig4_floor_test"),
    ("05_pedestrian_ins", "carpark_trajectory_error"),
    ("06_real_recordings", "attitude_real"),
]
GALLERY_WIDTH_PX = 480
THUMB_WIDTH_PX = 120  # shown in the README's claim matrices
THUMB_FILE_WIDTH_PX = 240  # docs/figures copy of a figure that only a verdict shows


def figure_copy(build_path: str) -> str:
    """The docs/figures/ name of a build/ figure path ``<stem>/figures/<name>.png``."""
    stem, _, name = build_path.split("/")
    return f"{stem[:2]}_{name}"


def cell(text: str) -> str:
    """Text for one markdown table cell."""
    return " ".join(str(text).split()).replace("|", "\\|")


def summary_rows(build: Path, leds: list[ledger.PaperLedger]) -> dict[str, str]:
    """One markdown row per notebook that has results: claims by verdict and checks passed."""
    rows = {}
    for led in leds:
        if not led.ran:
            continue
        counts = led.counts
        rows[led.stem] = (
            f"| `{led.stem}` | {cell(led.title)} | {len(led.rows)} | "
            + " | ".join(str(counts.get(v, 0)) for v in ledger.COLUMNS)
            + f" | {led.checks_passed}/{led.checks_total} |"
        )
    for stem, title in CHAPTERS.items():
        res = ledger.results(build, stem)
        if res is not None:
            passed = sum(bool(c["passed"]) for c in res["checks"])
            rows[stem] = (
                f"| `{stem}` | {cell(title)} | — | "
                + " | ".join("—" for _ in ledger.COLUMNS)
                + f" | {passed}/{len(res['checks'])} |"
            )
    return rows


def row_line(r: ledger.Row) -> str:
    """One claim as a markdown table row: id, item, paper, ours, verdict with its reason, thumbnail; then its
    real-data verdict, if any, as a row of its own (evidence: real data, and the notebook that recorded it)."""
    line = f"| `{r.claim}` | {cell(r.item)} | {cell(r.paper)} | {cell(r.ours)} | {cell(ledger.verdict_text(r))} | {thumb(r)} |"
    if r.real is None:
        return line
    real = r.real
    return (
        line + f"\n| ↳ real data | `{real.stem}` | {cell(real.paper)} | {cell(real.ours)} | "
        f"{cell(ledger.verdict_text(real))} | {thumb(real)} |"
    )


def thumb(r: ledger.Row) -> str:
    return f'<img src="docs/figures/{figure_copy(r.figure)}" width="{THUMB_WIDTH_PX}">' if r.figure else ""


def matrix(led: ledger.PaperLedger) -> str:
    """The claims of one paper as a collapsible markdown table, between its ledger markers."""
    counts = led.counts
    summary = ", ".join(f"{counts[v]} {v}" for v in ledger.COLUMNS if counts.get(v))
    if led.real_counts:
        summary += "; on real data: " + ", ".join(f"{n} {v}" for v, n in sorted(led.real_counts.items()))
    lines = [
        f"<!-- ledger:{led.stem} -->",
        f"<details><summary><b>{led.stem}</b> — {led.title}: {len(led.rows)} claims ({summary})</summary>",
        "",
        "| claim | paper item | paper | ours | verdict | figure |",
        "|---|---|---|---|---|---|",
    ]
    lines += [row_line(r) for r in led.rows]
    if led.extensions:
        lines += [
            "",
            f"Extensions ({len(led.extensions)}): the project's own quantities, test vectors and reconstructions, "
            "checked but not paper claims, so without a verdict word on the paper.",
            "",
            "| extension | item | paper | ours | checked | figure |",
            "|---|---|---|---|---|---|",
        ]
        lines += [row_line(r) for r in led.extensions]
    lines += ["", "</details>", f"<!-- /ledger:{led.stem} -->"]
    return "\n".join(lines)


def render(build: Path) -> tuple[str, dict[str, str]]:
    """The README block and, per notebook, the parts of it that depend on that notebook alone."""
    leds = ledger.ledgers(build)
    rows = summary_rows(build, leds)
    ran = [led for led in leds if led.ran]
    parts = {stem: row for stem, row in rows.items()}
    for led in ran:
        parts[led.stem] += "\n" + matrix(led)
    n_claims = sum(len(led.rows) for led in ran)
    total = {v: sum(led.counts.get(v, 0) for led in ran) for v in ledger.COLUMNS}
    head = (
        "| notebook | paper | claims | "
        + " | ".join(ledger.COLUMNS)
        + " | checks passed |\n"
        + "|---" * (len(ledger.COLUMNS) + 4)
        + "|"
    )
    order = sorted(rows)
    block = [
        START,
        "**Claims by verdict.** One verdict per claim of the papers (`data/claims.csv`), recorded by its "
        "notebook with `navlib.repro.verdict`; a *check* is one computed comparison of a notebook, a *claim* a "
        "statement of a paper.",
        "",
        head,
        *[rows[k] for k in order],
        "| **total** | | " + f"{n_claims} | " + " | ".join(str(total[v]) for v in ledger.COLUMNS) + " | |",
        "",
        f"**Coverage:** {sum(led.computed for led in ran)} of {n_claims} claims have a verdict that rests on a "
        f"computation (a check of the notebook); {total['not checkable here']} are not checkable here and "
        f"{total[ledger.NO_VERDICT]} have no verdict yet (never counted as reproduced). "
        f"{sum(len(led.extensions) for led in ran)} extensions (the project's own quantities) are listed apart, "
        "under each paper.",
        "",
        real_data_line(ran),
        "",
    ]
    block += [matrix(led) + "\n" for led in ran]
    block.append(END)
    return "\n".join(block), parts


def real_data_line(leds: list[ledger.PaperLedger]) -> str:
    """The count of the second verdicts, whose evidence is a committed real recording."""
    counts = sum((led.real_counts for led in leds), Counter())
    if not counts:
        return "**Real data:** no claim has a real-data verdict yet."
    return (
        f"**Real data:** {sum(counts.values())} claims also carry a verdict whose evidence is a committed real recording "
        f"(data/real/; the row marked *real data* under the claim, beside its simulation verdict): "
        + ", ".join(f"{n} {v}" for v, n in sorted(counts.items()))
        + "."
    )


def readme_parts(text: str) -> dict[str, str]:
    """The per-notebook parts currently in README's results block (summary row + matrix)."""
    block = text[text.index(START) : text.index(END)] if START in text and END in text else ""
    parts = {m.group(1): m.group(0) for m in SUMMARY_ROW.finditer(block)}
    for m in LEDGER.finditer(block):
        parts[m.group(1)] = parts.get(m.group(1), "") + "\n" + m.group(0)
    return parts


def fill_values(text: str, build: Path) -> tuple[str, list[str]]:
    """README text with every quoted value refreshed from the results; and the values that changed."""
    changed = []

    def sub(m: re.Match) -> str:
        stem, name, spec, old = m.groups()
        scale, _, fmt = spec.rpartition(":")
        value = ledger.check_value(build, stem, name) * (float(scale[1:]) if scale.startswith("x") else 1.0)
        new = format(value, fmt)
        if new != old:
            changed.append(f"{stem} {name}: README {old!r}, results {new!r}")
        return m.group(0).replace(f"-->{old}<!--", f"-->{new}<!--")

    return VALUE.sub(sub, text), changed


def quoted_values(text: str) -> list[tuple[str, str]]:
    """The (notebook, check name) of every number quoted in the README's prose."""
    return [(m.group(1), m.group(2)) for m in VALUE.finditer(text)]


def stale(text: str, build: Path, notebooks: set[str] | None = None) -> list[str]:
    """What in README.md differs from build/ (restricted to ``notebooks`` when given)."""
    _, parts = render(build)
    committed = readme_parts(text)
    out = [
        f"results section of {k}" for k in sorted(parts) if (notebooks is None or k in notebooks) and committed.get(k) != parts[k]
    ]
    if notebooks is None:
        block, _ = render(build)
        if START in text and text[text.index(START) : text.index(END) + len(END)] != block:
            out.append("results section (totals and coverage)")
    quotable = [q for q in quoted_values(text) if notebooks is None or q[0] in notebooks]
    if quotable:
        _, changed = fill_values(text, build)
        out += [c for c in changed if notebooks is None or c.split()[0] in notebooks]
    return out


def write_figures(build: Path, leds: list[ledger.PaperLedger]) -> list[str]:
    """Small copies (deterministic PNGs) of the GALLERY figures and of every verdict's figure in docs/figures/."""
    from PIL import Image  # Pillow comes with matplotlib

    FIGURES.mkdir(parents=True, exist_ok=True)
    rows = [r for led in leds for r in (*led.rows, *led.extensions)]
    wanted = {x.figure: THUMB_FILE_WIDTH_PX for r in rows for x in (r, r.real) if x is not None and x.figure}
    wanted |= {f"{stem}/figures/{fig}.png": GALLERY_WIDTH_PX for stem, fig in GALLERY}
    # Copies are remade only when their source PNG or width changed (build/readme-figures.json: the sources
    # of the last copies); re-encoding all of them took 1 s of every make reproduce.
    made_from = build / "readme-figures.json"
    sources = json.loads(made_from.read_text()) if made_from.is_file() else {}
    names = []
    for path, width in sorted(wanted.items()):
        src = build / path
        if not src.is_file():
            continue
        name = figure_copy(path)
        key = f"{hashlib.sha256(src.read_bytes()).hexdigest()} {width}"
        if sources.get(name) != key or not (FIGURES / name).is_file():
            img = Image.open(src).convert("RGB")
            h = round(img.height * width / img.width)
            img.resize((width, h), Image.LANCZOS).save(FIGURES / name, optimize=True)
            sources[name] = key
        names.append(name)
    made_from.write_text(json.dumps(sources, indent=1, sort_keys=True) + "\n")
    return names


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="only report whether the README is stale")
    args = ap.parse_args(argv)
    build = ROOT / "build"
    if not any(ledger.results(build, s) for s in [*CHAPTERS, *(led.stem for led in ledger.ledgers(build))]):
        print("no results in build/: run `make reproduce` first", file=sys.stderr)
        return 1
    text = README.read_text(encoding="utf-8")
    if args.check:
        found = stale(text, build)
        print("README is " + ("stale: " + "; ".join(found) if found else "up to date"))
        return 1 if found else 0
    block, _ = render(build)
    text = text[: text.index(START)] + block + text[text.index(END) + len(END) :] if START in text else text + "\n" + block + "\n"
    text, changed = fill_values(text, build)
    README.write_text(text, encoding="utf-8")
    names = write_figures(build, ledger.ledgers(build))
    print(
        f"README.md: results section and {len(quoted_values(text))} quoted values ({len(changed)} changed); "
        f"docs/figures: {len(names)} figures"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
