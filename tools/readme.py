#!/usr/bin/env python3
"""Regenerate the README's results table and figure gallery from build/.

Reads ``build/<notebook>/results.json`` (written by the notebooks through
``navlib.repro``) and rewrites the block between the ``results`` markers of
README.md: one row per notebook with its checks passed / total and how many
of the paper's checkable claims (``data/claims.csv``) have a check. It also copies the figures listed in
``GALLERY`` into ``docs/figures/`` at a small size for the README.

Only deterministic numbers go into the table (no run times), so the root
``conftest.py`` can fail ``make test`` when the committed table is stale.

Usage: python tools/readme.py [--check]
"""
from __future__ import annotations

import argparse
import csv
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from navlib.papers import CHAPTERS  # noqa: E402  (notebooks without a paper)
from navlib.papers import PAPERS as REGISTRY  # noqa: E402

README = ROOT / "README.md"
CLAIMS = ROOT / "data" / "claims.csv"
START, END = "<!-- results:start -->", "<!-- results:end -->"

# notebook stem -> (paper id in claims.csv, short citation), from the paper registry
PAPERS = {stem: (None, title) for stem, title in CHAPTERS.items()}
PAPERS.update({p.notebook: (p.claims_id, p.citation) for p in REGISTRY})
# figures shown in the README: (notebook, figure stem)
GALLERY = [("00_conventions_sensors", "allan_gyros"), ("00_conventions_sensors", "ins_error_theory"),
           ("01_north_finding", "fig4_rmse_vs_heading"), ("02_rotation_bias", "fig6_heading_error"),
           ("03_gauss_kruger_ekf", "fig4_fig5_tracks"), ("04_mimu_mag_rtk", "fig4_heading_modes"),
           ("05_pedestrian_ins", "fig4_floor_test"), ("05_pedestrian_ins", "carpark_trajectory_error"),
           ("06_real_recordings", "attitude_real")]
GALLERY_WIDTH_PX = 480


def coverable_claims() -> dict[str, list[str]]:
    """Claim ids per paper that count towards coverage (kind != hardware-only)."""
    out: dict[str, list[str]] = {}
    with open(CLAIMS, encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            if row["kind"] != "hardware-only":
                out.setdefault(row["paper"], []).append(row["id"])
    return out


def table_rows(build: Path) -> dict[str, str]:
    """Markdown row per notebook that has results, keyed by notebook stem."""
    claims = coverable_claims()
    rows = {}
    for stem, (paper, title) in PAPERS.items():
        path = build / stem / "results.json"
        if not path.is_file():
            continue
        checks = json.loads(path.read_text())["checks"]
        passed = sum(bool(c["passed"]) for c in checks)
        covered = "—"
        if paper is not None and paper in claims:
            ids = claims[paper]
            hit = sum(any(c["name"].startswith(i) for c in checks) for i in ids)
            covered = f"{hit}/{len(ids)}"
        rows[stem] = f"| `{stem}` | {title} | {passed}/{len(checks)} | {covered} |"
    return rows


def render(rows: dict[str, str]) -> str:
    head = ("| notebook | paper | checks passed | paper claims covered |\n"
            "|---|---|---|---|")
    return "\n".join([START, head, *[rows[k] for k in sorted(rows)], END])


def readme_rows(text: str) -> dict[str, str]:
    """The rows currently in README's results block."""
    block = text[text.index(START):text.index(END)] if START in text and END in text else ""
    return {m.group(1): m.group(0) for m in re.finditer(r"^\| `([^`]+)` \|.*\|$", block, re.M)}


def write_gallery(build: Path) -> list[str]:
    """Small copies of the GALLERY figures in docs/figures/ (deterministic PNGs)."""
    from PIL import Image  # Pillow comes with matplotlib

    out_dir = ROOT / "docs" / "figures"
    out_dir.mkdir(parents=True, exist_ok=True)
    names = []
    for stem, fig in GALLERY:
        src = build / stem / "figures" / f"{fig}.png"
        if not src.is_file():
            continue
        img = Image.open(src).convert("RGB")
        h = round(img.height * GALLERY_WIDTH_PX / img.width)
        name = f"{stem[:2]}_{fig}.png"
        img.resize((GALLERY_WIDTH_PX, h), Image.LANCZOS).save(out_dir / name, optimize=True)
        names.append(name)
    return names


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="only report whether the README table is stale")
    args = ap.parse_args(argv)
    build = ROOT / "build"
    rows = table_rows(build)
    if not rows:
        print("no results in build/: run `make reproduce` first", file=sys.stderr)
        return 1
    text = README.read_text(encoding="utf-8")
    if args.check:
        stale = {k for k in rows if readme_rows(text).get(k) != rows[k]}
        print("README results table is " + (f"stale for {sorted(stale)}" if stale else "up to date"))
        return 1 if stale else 0
    block = render(rows)
    text = text[:text.index(START)] + block + text[text.index(END) + len(END):] if START in text else text + "\n" + block + "\n"
    README.write_text(text, encoding="utf-8")
    names = write_gallery(build)
    print(f"README.md: {len(rows)} notebooks; docs/figures: {', '.join(names)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
