#!/usr/bin/env python3
"""Where a notebook's time goes: imports, numba compilation per kernel, computation per cell, peak memory.

Runs each notebook's code cells in this process (an IPython shell, as the kernel would) and listens to
numba's compile events, so the report separates

* ``import``  - the first code cell (the notebook's imports),
* ``compile`` - time inside numba compilations (outermost ones only; a kernel's callees are included),
* ``compute`` - everything else,

and lists the kernels by compile time and the slowest cells. ``--cold`` points numba at an empty cache
directory (``NUMBA_CACHE_DIR``), as on a fresh clone; without it the repository's cache is used (a warm
rerun). Each notebook runs in its own subprocess so that imports and caches do not carry over.

Usage: python tools/profile_notebooks.py [--only PATTERN] [--cold] [--json OUT]
"""
from __future__ import annotations

import argparse
import collections
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def profile_one(path: Path) -> dict:
    """Execute ``path``'s code cells here; return the timings (called in a fresh subprocess)."""
    from numba.core import event

    compile_s, n_compiles, stack = collections.Counter(), collections.Counter(), []

    class CompileTimer(event.Listener):
        def on_start(self, ev):
            f = ev.data["dispatcher"].py_func
            stack.append((f"{f.__module__}.{f.__qualname__}", time.perf_counter()))

        def on_end(self, ev):
            name, started = stack.pop()
            n_compiles[name] += 1
            if not stack:                       # outermost compilation: includes its callees
                compile_s[name] += time.perf_counter() - started

    event.register("numba:compile", CompileTimer())
    import nbformat
    from IPython.core.interactiveshell import InteractiveShell

    os.chdir(path.parent)
    shell = InteractiveShell.instance()
    cells = []
    for index, cell in enumerate(nbformat.read(path, as_version=4).cells):
        if cell.cell_type != "code":
            continue
        before = sum(compile_s.values())
        start = time.perf_counter()
        result = shell.run_cell(cell.source, silent=True)
        seconds = time.perf_counter() - start
        if not result.success:
            raise SystemExit(f"{path.name}: cell {index} failed")
        first_line = next((ln for ln in cell.source.splitlines() if ln.strip()), "")
        cells.append({"cell": index, "seconds": seconds, "compile": sum(compile_s.values()) - before,
                      "source": first_line[:70]})
    total = sum(c["seconds"] for c in cells)
    compile_total = sum(compile_s.values())
    import_s = cells[0]["seconds"] if cells else 0.0
    return {"notebook": path.stem, "total": total, "import": import_s, "compile": compile_total,
            "compute": total - compile_total - import_s + cells[0]["compile"] if cells else 0.0,
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
            "kernels": sorted(([k, v, n_compiles[k]] for k, v in compile_s.items()), key=lambda r: -r[1]),
            "cells": sorted(cells, key=lambda c: -c["seconds"])}


def report(p: dict, top: int = 5) -> str:
    lines = [f"{p['notebook']}: {p['total']:.1f} s = import {p['import']:.1f} + compile {p['compile']:.1f} + "
             f"compute {p['compute']:.1f}; peak {p['peak_mb']:.0f} MB"]
    lines += [f"    compile {s:6.1f} s  {n} signature(s)  {k}" for k, s, n in p["kernels"][:top]]
    lines += [f"    cell {c['cell']:3d} {c['seconds']:6.1f} s (compile {c['compile']:.1f})  {c['source']}"
              for c in p["cells"][:top]]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="", help="notebooks whose name contains this")
    ap.add_argument("--cold", action="store_true", help="empty numba cache, as on a fresh clone")
    ap.add_argument("--json", type=Path, help="write all profiles to this file")
    ap.add_argument("--one", type=Path, help=argparse.SUPPRESS)      # internal: profile one notebook, print JSON
    args = ap.parse_args(argv)
    if args.one:
        print(json.dumps(profile_one(args.one.resolve())))
        return 0
    env = dict(os.environ, NAVLIB_ROOT=str(REPO), MPLBACKEND="Agg", PYTHONHASHSEED="0",
               PYTHONPATH=os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]))
    profiles = []
    for path in sorted((REPO / "notebooks").glob("[0-9][0-9]_*.ipynb")):
        if args.only not in path.stem:
            continue
        with tempfile.TemporaryDirectory() as cache:
            if args.cold:
                env["NUMBA_CACHE_DIR"] = cache
            out = subprocess.run([sys.executable, __file__, "--one", str(path)], env=env, text=True,
                                 stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True)
        profiles.append(json.loads(out.stdout.strip().splitlines()[-1]))
        print(report(profiles[-1]), flush=True)
    if args.json:
        args.json.write_text(json.dumps(profiles, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
