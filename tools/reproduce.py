#!/usr/bin/env python3
"""Execute every numbered notebook and build the reproduction report in build/.

For each ``notebooks/NN_*.ipynb`` in name order (kernel ``python3``, working
directory ``notebooks/``) this writes

* ``build/<stem>.ipynb`` and ``build/<stem>.html`` - the executed notebook,
* ``build/<stem>.kernel.log`` - the kernel process's own stderr,

and reads ``build/<stem>/results.json`` and ``build/<stem>/figures/*.png``,
which the notebook itself writes through ``navlib.repro``. Then it writes
``build/index.html`` (paper-vs-reproduction tables and figure thumbnails) and
``build/summary.json`` and ``build/manifest.json`` (SHA-256 of every
results file and figure), and prints one line per notebook.
``--check-against MANIFEST`` fails the run unless those files are
byte-identical to an earlier run's (``make determinism``).

Notebooks run ``--jobs`` at a time (default 2), each in its own kernel, the longest first (by the
previous run's times in ``build/summary.json``); each is reported with its wall time and its kernel's
peak memory (resident set size). A notebook that raises is
reported and the run goes on with the others; the
exit status is non-zero if any notebook failed. ``--only`` runs a subset, and
the report then covers that subset only. Needs no network.

Usage: python tools/reproduce.py [--only PATTERN] [--root DIR] [--timeout S] [--jobs N]
"""
from __future__ import annotations

import argparse
import fnmatch
import hashlib
import html
import json
import multiprocessing
import os
import resource
import shutil
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter
from nbconvert.filters.markdown_mistune import markdown2html_mistune

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))


def unregistered(notebooks: list[Path]) -> list[str]:
    """Notebook stems that are neither a chapter without a paper nor a registered paper (navlib/papers/__init__.py)."""
    from navlib.papers import CHAPTERS, PAPERS  # the registry (imported here: the notebook workers need no navlib)

    known = set(CHAPTERS) | {p.notebook for p in PAPERS}
    return [p.stem for p in notebooks if p.stem not in known]


def error_line(exc: BaseException) -> str:
    """The one line that says what went wrong (the traceback's last line)."""
    if getattr(exc, "ename", None):  # nbclient.exceptions.CellExecutionError
        return f"{exc.ename}: {exc.evalue}"
    lines = [ln.strip() for ln in str(exc).splitlines() if ln.strip()]
    return lines[-1] if lines else type(exc).__name__


def run_notebook(path: Path, build: Path, timeout: int) -> dict:
    """Execute one notebook, write its .ipynb/.html, return its summary entry."""
    stem = path.stem
    shutil.rmtree(build / stem, ignore_errors=True)  # no stale results or figures
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, kernel_name="python3", timeout=timeout,
                            resources={"metadata": {"path": str(path.parent)}})
    error = None
    start = time.perf_counter()
    with open(build / f"{stem}.kernel.log", "w") as log:
        try:
            client.execute(stderr=log)
        except Exception as exc:  # report it and go on with the next notebook
            error = error_line(exc)
    seconds = time.perf_counter() - start
    # This worker runs one notebook (max_tasks_per_child=1): its reaped children are this kernel.
    peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    nbformat.write(nb, build / f"{stem}.ipynb")
    body, _ = HTMLExporter().from_notebook_node(nb)
    (build / f"{stem}.html").write_text(body, encoding="utf-8")

    results = build / stem / "results.json"
    checks = json.loads(results.read_text())["checks"] if results.is_file() else []
    passed = sum(bool(c.get("passed")) for c in checks)
    figures = sorted(p.relative_to(build).as_posix() for p in (build / stem / "figures").glob("*.png"))
    header = next((c.source for c in nb.cells if c.cell_type == "markdown"), "")
    return {"notebook": stem, "ok": error is None and passed == len(checks), "error": error,
            "seconds": round(seconds, 1), "peak_mb": round(peak_mb), "claims_passed": passed, "claims_total": len(checks),
            "checks": checks, "figures": figures, "header": header}


def fmt(x, unit: str = "") -> str:
    if x is None:
        return ""
    s = f"{x:.6g}" if isinstance(x, (int, float)) else str(x)
    return f"{s} {unit}".strip()


def claims_table(checks: list[dict]) -> str:
    if not checks:
        return "<p><em>No claims recorded.</em></p>"
    rows = []
    for c in checks:
        unit = c.get("unit") or ""
        if c.get("expected") is not None:
            target, tol = fmt(c["expected"], unit), f"± {fmt(c.get('tol'))}"
        else:
            lo, hi = c.get("lower"), c.get("upper")
            target = f"[{fmt(lo) if lo is not None else '−∞'}, {fmt(hi) if hi is not None else '∞'}] {unit}"
            tol = "range"
        paper = c.get("paper_value")
        if paper is None:
            paper = "= target" if c.get("expected") is not None else ""
        ok = bool(c.get("passed"))
        cells = [c["name"], paper, target, fmt(c.get("value"), unit), tol, c.get("source", ""), c.get("note", "")]
        tds = "".join(f"<td>{html.escape(str(v))}</td>" for v in cells)
        rows.append(f'<tr>{tds}<td class="{"pass" if ok else "fail"}">{"pass" if ok else "FAIL"}</td></tr>')
    head = "".join(f"<th>{h}</th>" for h in
                   ("claim", "paper value", "target", "reproduced", "tolerance", "source", "note", "result"))
    return f"<table><tr>{head}</tr>\n" + "\n".join(rows) + "\n</table>"


def write_index(build: Path, entries: list[dict]) -> None:
    style = ("body{font-family:sans-serif;max-width:80em;margin:2em auto;padding:0 1em}"
             "table{border-collapse:collapse;font-size:90%}td,th{border:1px solid #ccc;padding:.2em .5em}"
             "th{background:#f4f4f4}.pass{background:#d4f4d4}.fail{background:#f8d0d0;font-weight:bold}"
             ".err{color:#a00}img{margin:4px;border:1px solid #ddd}")
    total_s = sum(e["seconds"] for e in entries)
    passed = sum(e["claims_passed"] for e in entries)
    total = sum(e["claims_total"] for e in entries)
    parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>navlib reproduction</title>"
             f"<style>{style}</style></head><body><h1>navlib: paper claims reproduced</h1>"
             f"<p>{passed}/{total} checks passed in {len(entries)} notebooks; total run time {total_s:.1f} s.</p><ul>"]
    for e in entries:
        status = "ok" if e["ok"] else "FAILED"
        parts.append(f"<li><a href='#{e['notebook']}'>{e['notebook']}</a>: {e['claims_passed']}/"
                     f"{e['claims_total']} claims passed, {e['seconds']:.1f} s, {status}</li>")
    parts.append("</ul>")
    for e in entries:
        nb = html.escape(e["notebook"])
        parts.append(f"<h2 id='{nb}'><a href='{nb}.html'>{nb}</a></h2>"
                     f"<p>run time {e['seconds']:.1f} s; {e['claims_passed']}/{e['claims_total']} claims passed"
                     f" (<a href='{nb}.ipynb'>executed notebook</a>)</p>")
        if e["error"]:
            parts.append(f"<p class='err'>Notebook failed: {html.escape(e['error'])}</p>")
        # the notebook's own header: citation, what is reproduced, status table with reasons
        header = markdown2html_mistune(e.get("header", "")).replace("<h1", "<h3").replace("</h1>", "</h3>")
        parts.append(f"<div class='header'>{header}</div>")
        parts.append(claims_table(e["checks"]))
        parts.append("<p>" + "".join(f"<a href='{f}'><img src='{f}' width='240' alt='{html.escape(f)}'></a>"
                                     for f in e["figures"]) + "</p>")
    parts.append("</body></html>\n")
    (build / "index.html").write_text("\n".join(parts), encoding="utf-8")


def write_manifest(build: Path, entries: list[dict]) -> dict:
    """SHA-256 of every results.json and PNG figure: what must not change between two runs."""
    files = []
    for e in entries:
        files += [build / e["notebook"] / "results.json"] + [build / f for f in e["figures"]]
    manifest = {p.relative_to(build).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
                for p in files if p.is_file()}
    (build / "manifest.json").write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n")
    return manifest


def compare_manifest(manifest: dict, reference: Path, notebooks: list[str]) -> list[str]:
    """Files of ``notebooks`` whose hash differs from (or is missing in) a previous run's manifest."""
    ref = {k: v for k, v in json.loads(reference.read_text()).items() if k.split("/")[0] in notebooks}
    return sorted(k for k in set(ref) | set(manifest) if ref.get(k) != manifest.get(k))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", metavar="PATTERN", help="run only notebooks whose name matches (substring or glob)")
    ap.add_argument("--root", type=Path, default=REPO, help="repository root holding notebooks/ (default: this repo)")
    ap.add_argument("--timeout", type=int, default=1800, help="per-cell timeout in seconds (default 1800)")
    ap.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1),
                    help="notebooks executed at once, each in its own kernel (default: 2, or 1 on one core)")
    ap.add_argument("--check-against", type=Path, metavar="MANIFEST",
                    help="fail unless every results.json and PNG is byte-identical to this earlier manifest")
    args = ap.parse_args(argv)

    root = args.root.resolve()
    notebooks = sorted((root / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    if args.only:
        notebooks = [p for p in notebooks if fnmatch.fnmatch(p.stem, f"*{args.only}*")]
    stray = unregistered(notebooks)
    if stray:
        print(f"not in the paper registry (navlib/papers/__init__.py): {', '.join(stray)}", file=sys.stderr)
        return 1
    if not notebooks:
        print(f"no notebooks matched in {root / 'notebooks'}", file=sys.stderr)
        return 1
    build = root / "build"
    build.mkdir(exist_ok=True)
    # Kernels inherit this environment: navlib.repro writes to <root>/build, and
    # figures render with the (headless) inline backend so the HTML shows them.
    os.environ["NAVLIB_ROOT"] = str(root)
    os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"

    # Notebooks are independent (own kernel, own build/<stem>/, own seeds): run --jobs at once, the
    # longest first (by the last run's times) so that the last one to start is a short one.
    last = json.loads((build / "summary.json").read_text()) if (build / "summary.json").is_file() else {}
    order = sorted(notebooks, key=lambda p: -last.get(p.stem, {}).get("seconds", 0.0))
    start = time.perf_counter()
    done = {}
    with ProcessPoolExecutor(max(1, args.jobs), mp_context=multiprocessing.get_context("spawn"),
                             max_tasks_per_child=1) as pool:
        futures = {pool.submit(run_notebook, path, build, args.timeout): path for path in order}
        print(f"executing {len(notebooks)} notebooks, {max(1, args.jobs)} at a time ...", flush=True)
        for future in as_completed(futures):
            e = done[futures[future]] = future.result()
            tail = "" if e["error"] is None else f"\n    ERROR: {e['error']}"
            print(f"[{len(done)}/{len(notebooks)}] {e['notebook']} {'done' if e['ok'] else 'FAILED'} "
                  f"in {e['seconds']:.1f} s, peak memory {e['peak_mb']} MB{tail}", flush=True)
    entries = [done[path] for path in notebooks]
    wall = time.perf_counter() - start

    write_index(build, entries)
    manifest = write_manifest(build, entries)
    summary = {e["notebook"]: {k: e[k] for k in ("claims_passed", "claims_total", "seconds", "peak_mb", "ok", "error")}
               for e in entries}
    (build / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")

    width = max(len(e["notebook"]) for e in entries) + 3
    print()
    for e in entries:
        mark = "" if e["ok"] else "   FAILED"
        claims = f"{e['claims_passed']}/{e['claims_total']}"
        print(f"{e['notebook']:<{width}}{claims:>7} claims passed{e['seconds']:>9.1f} s{e['peak_mb']:>7} MB{mark}")
    n_ok = sum(e["ok"] for e in entries)
    passed = sum(e["claims_passed"] for e in entries)
    total = sum(e["claims_total"] for e in entries)
    seconds = sum(e["seconds"] for e in entries)
    print(f"{'total':<{width}}{f'{passed}/{total}':>7} claims passed{seconds:>9.1f} s"
          f"   ({n_ok}/{len(entries)} notebooks ok; {wall:.1f} s wall with {max(1, args.jobs)} at a time)")
    print(f"report: {build / 'index.html'}")
    if args.check_against:
        changed = compare_manifest(manifest, args.check_against, [p.stem for p in notebooks])
        print(f"determinism: {len(manifest)} files, {len(changed)} differ from {args.check_against.name}"
              + "".join(f"\n    {c}" for c in changed))
        if changed:
            return 1
    return 0 if n_ok == len(entries) else 1


if __name__ == "__main__":
    sys.exit(main())
