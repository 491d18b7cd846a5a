#!/usr/bin/env python3
"""Strip notebooks in place before committing: outputs, execution counts,
per-cell execution timing and widget state. Prints the notebooks it changed.

Usage: python tools/strip_notebooks.py [NOTEBOOK.ipynb ...]   (default: notebooks/*.ipynb)
Exit status 0; with --check, 1 if any notebook would change (nothing is written).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import nbformat

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"


def strip(nb) -> None:
    nb.metadata.pop("widgets", None)
    for cell in nb.cells:
        cell.metadata.pop("execution", None)  # timing recorded by JupyterLab/nbclient
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="*", type=Path, help="notebooks (default: notebooks/*.ipynb)")
    ap.add_argument("--check", action="store_true", help="only report; exit 1 if any would change")
    args = ap.parse_args(argv)
    paths = args.paths or sorted(NOTEBOOKS.glob("*.ipynb"))
    changed = []
    for path in paths:
        before = path.read_text(encoding="utf-8")
        nb = nbformat.reads(before, as_version=4)
        strip(nb)
        after = nbformat.writes(nb) + "\n"
        if after != before:
            changed.append(path)
            if not args.check:
                path.write_text(after, encoding="utf-8")
    for path in changed:
        print(f"{'would strip' if args.check else 'stripped'} {path}")
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    sys.exit(main())
