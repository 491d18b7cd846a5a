#!/usr/bin/env python3
"""Execute every numbered notebook and build the reproduction report in build/.

For each ``notebooks/NN_*.ipynb`` in name order (kernel ``python3``, working
directory ``notebooks/``) this writes

* ``build/<stem>.ipynb`` and ``build/<stem>.html`` - the executed notebook,
* ``build/<stem>.kernel.log`` - the kernel process's own stderr,

and reads ``build/<stem>/results.json`` and ``build/<stem>/figures/*.png``,
which the notebook itself writes through ``navlib.repro``. Then it writes
``build/index.html`` (per paper: every claim of ``data/claims.csv`` with the paper's value, ours,
the notebook's verdict and a thumbnail, counts by verdict; per notebook: every check) and
``build/summary.json`` and ``build/manifest.json`` (SHA-256 of every
results file and figure), and prints one line per notebook.
``--check-against MANIFEST`` fails the run unless those files are
byte-identical to an earlier run's (``make determinism``).

Notebooks run ``--jobs`` at a time (default 2), each in its own kernel, the longest first (by the
previous run's times in ``build/summary.json``); each is reported with its wall time and its kernel's
peak memory (resident set size, read from /proc while the kernel runs; "n/a" where there is none). A notebook that raises is
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
import shutil
import sys
import time
from collections import Counter
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter
from nbconvert.filters.markdown_mistune import markdown2html_mistune

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import ledger  # noqa: E402  (tools/ledger.py: claims with their verdicts; no navlib import at module level)


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


def kernel_peak_mb(client: NotebookClient) -> float | None:
    """Peak resident memory (MB) of the client's kernel process so far (Linux: VmHWM), or None."""
    try:
        status = Path(f"/proc/{client.km.provisioner.process.pid}/status").read_text()
    except (AttributeError, OSError):
        return None
    return next((int(line.split()[1]) / 1024 for line in status.splitlines() if line.startswith("VmHWM:")), None)


def run_notebook(path: Path, build: Path, timeout: int) -> dict:
    """Execute one notebook, write its .ipynb/.html, return its summary entry."""
    stem = path.stem
    shutil.rmtree(build / stem, ignore_errors=True)  # no stale results or figures
    nb = nbformat.read(path, as_version=4)
    peak = {"mb": None}

    def after_cell(**_):                    # the kernel's high-water mark, read while it is alive
        peak["mb"] = kernel_peak_mb(client) or peak["mb"]

    client = NotebookClient(nb, kernel_name="python3", timeout=timeout, on_cell_executed=after_cell,
                            resources={"metadata": {"path": str(path.parent)}})
    error = None
    start = time.perf_counter()
    with open(build / f"{stem}.kernel.log", "w") as log:
        try:
            client.execute(stderr=log)
        except Exception as exc:  # report it and go on with the next notebook
            error = error_line(exc)
    seconds = time.perf_counter() - start
    peak_mb = None if peak["mb"] is None else round(peak["mb"])
    nbformat.write(nb, build / f"{stem}.ipynb")
    body, _ = HTMLExporter().from_notebook_node(nb)
    (build / f"{stem}.html").write_text(body, encoding="utf-8")

    results = build / stem / "results.json"
    checks = json.loads(results.read_text())["checks"] if results.is_file() else []
    passed = sum(bool(c.get("passed")) for c in checks)
    figures = sorted(p.relative_to(build).as_posix() for p in (build / stem / "figures").glob("*.png"))
    header = next((c.source for c in nb.cells if c.cell_type == "markdown"), "")
    return {"notebook": stem, "ok": error is None and passed == len(checks), "error": error,
            "seconds": round(seconds, 1), "peak_mb": peak_mb, "checks_passed": passed, "checks_total": len(checks),
            "checks": checks, "figures": figures, "header": header}


def mb(x: float | None) -> str:
    return "n/a" if x is None else f"{x} MB"


def fmt(x, unit: str = "") -> str:
    if x is None:
        return ""
    s = f"{x:.6g}" if isinstance(x, (int, float)) else str(x)
    return f"{s} {unit}".strip()


def checks_table(checks: list[dict]) -> str:
    """Every check of a notebook: what it compares, its target or bound, and whether it passed."""
    if not checks:
        return "<p><em>No checks recorded.</em></p>"
    rows = []
    for c in checks:
        unit = c.get("unit") or ""
        if c.get("expected") is not None:
            target, tol = fmt(c["expected"], unit), f"± {fmt(c.get('tol'))}"
        else:
            lo, hi = c.get("lower"), c.get("upper")
            target = f"[{fmt(lo) if lo is not None else '−∞'}, {fmt(hi) if hi is not None else '∞'}] {unit}".strip()
            tol = "outside" if c.get("outside") else "range"
        ok = bool(c.get("passed"))
        # the paper's value only where the check names one: a target is not a paper number by default
        cells = [c["name"], c.get("paper_value") or "", target, fmt(c.get("value"), unit), tol, c.get("source", ""),
                 c.get("note", "")]
        tds = "".join(f"<td>{html.escape(str(v))}</td>" for v in cells)
        rows.append(f'<tr id="check-{html.escape(c["name"])}">{tds}<td class="{"pass" if ok else "fail"}">'
                    f'{"pass" if ok else "FAIL"}</td></tr>')
    head = "".join(f"<th>{h}</th>" for h in
                   ("check", "paper value", "target or bound", "reproduced", "tolerance", "source", "note", "result"))
    return f"<table><tr>{head}</tr>\n" + "\n".join(rows) + "\n</table>"


VERDICT_CLASS = {v: "v" + str(i) for i, v in enumerate(ledger.COLUMNS)}


def claims_matrix(led: ledger.PaperLedger) -> str:
    """Every claim of the paper: paper item, paper value, ours, verdict (with reason) and thumbnail."""
    rows = []
    for r in led.rows:
        checks = ", ".join(f"<a href='#check-{html.escape(n)}'>{html.escape(n.removeprefix(r.claim) or n)}</a>"
                           for n in r.checks)
        thumb = (f"<a href='{r.figure}'><img src='{r.figure}' width='120' alt='{html.escape(r.figure)}'></a>"
                 if r.figure else "")
        why = ledger.verdict_text(r)[len(r.verdict):].lstrip(": ")
        verdict = f"<span class='{VERDICT_CLASS[r.verdict]}'>{html.escape(r.verdict)}</span>"
        cells = [html.escape(r.item), f"<code>{html.escape(r.claim)}</code><br><small>{html.escape(r.quantity)}</small>",
                 html.escape(r.paper), html.escape(r.ours), verdict + (f"<br><small>{html.escape(why)}</small>" if why else ""),
                 checks, thumb]
        rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    head = "".join(f"<th>{h}</th>" for h in ("paper item", "claim", "paper", "ours", "verdict", "checks", "figure"))
    return f"<table class='matrix'><tr>{head}</tr>\n" + "\n".join(rows) + "\n</table>"


def counts_table(leds: list[ledger.PaperLedger], entries: dict[str, dict]) -> str:
    """Claims by verdict per paper, and each notebook's checks passed."""
    head = "".join(f"<th>{h}</th>" for h in ("notebook", "paper", "claims", *ledger.COLUMNS, "checks passed"))
    rows, total = [], Counter()
    for led in leds:
        counts = led.counts
        total.update(counts)
        e = entries.get(led.stem)
        passed = f"{e['checks_passed']}/{e['checks_total']}" if e else "not run"
        cells = [f"<a href='#{led.stem}'>{led.stem}</a>", html.escape(led.title), str(len(led.rows)),
                 *(str(counts.get(v, 0)) for v in ledger.COLUMNS), passed]
        rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    cells = ["<b>total</b>", "", str(sum(len(led.rows) for led in leds)), *(str(total.get(v, 0)) for v in ledger.COLUMNS), ""]
    rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    return f"<table><tr>{head}</tr>\n" + "\n".join(rows) + "\n</table>"


def write_index(build: Path, entries: list[dict], root: Path = REPO) -> None:
    style = ("body{font-family:sans-serif;max-width:90em;margin:2em auto;padding:0 1em}"
             "table{border-collapse:collapse;font-size:90%}td,th{border:1px solid #ccc;padding:.2em .5em;vertical-align:top}"
             "th{background:#f4f4f4}.pass{background:#d4f4d4}.fail{background:#f8d0d0;font-weight:bold}"
             ".v0,.v1{background:#d4f4d4}.v2,.v3{background:#f8e0c0}.v4{background:#e0e8f8}.v5{background:#eee}"
             ".v6{background:#f8d0d0}.err{color:#a00}img{margin:4px;border:1px solid #ddd}")
    by_stem = {e["notebook"]: e for e in entries}
    leds = [led for led in ledger.ledgers(build, root) if led.stem in by_stem]
    total_s = sum(e["seconds"] for e in entries)
    passed = sum(e["checks_passed"] for e in entries)
    total = sum(e["checks_total"] for e in entries)
    n_claims = sum(len(led.rows) for led in leds)
    computed = sum(led.computed for led in leds)
    parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>navlib reproduction</title>"
             f"<style>{style}</style></head><body><h1>navlib: the papers' claims and their verdicts</h1>"
             f"<p>{n_claims} claims of {len(leds)} papers; {computed} have a verdict that rests on a computation "
             f"(a check of the notebook). A claim is a statement of a paper (<code>data/claims.csv</code>); a check is "
             f"one computed comparison. {passed}/{total} checks passed in {len(entries)} notebooks; total run time "
             f"{total_s:.1f} s.</p>", counts_table(leds, by_stem)]
    for led in leds:
        parts += [f"<h2 id='{led.stem}-claims'>{html.escape(led.stem)}: {html.escape(led.title)}</h2>",
                  f"<p><a href='#{led.stem}'>checks and figures</a></p>"]
        parts += [f"<p class='err'>{html.escape(p)}</p>" for p in led.problems]
        parts.append(claims_matrix(led))
    for e in entries:
        nb = html.escape(e["notebook"])
        parts.append(f"<h2 id='{nb}'><a href='{nb}.html'>{nb}</a></h2>"
                     f"<p>run time {e['seconds']:.1f} s; {e['checks_passed']}/{e['checks_total']} checks passed"
                     f" (<a href='{nb}.ipynb'>executed notebook</a>)</p>")
        if e["error"]:
            parts.append(f"<p class='err'>Notebook failed: {html.escape(e['error'])}</p>")
        # the notebook's own header: citation, what is reproduced, status table with reasons
        header = markdown2html_mistune(e.get("header", "")).replace("<h1", "<h3").replace("</h1>", "</h3>")
        parts.append(f"<div class='header'>{header}</div>")
        parts.append(checks_table(e["checks"]))
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
    # The ledger's run: the papers' scale, checks that raise, no progress bars kept in the HTML, and
    # results in build/ (a shell's teaching or fast switches, or another build directory, do not leak in).
    os.environ["NAVLIB_PROGRESS"] = "0"
    for name in ("NAVLIB_TEACHING", "NAVLIB_FAST", "NAVLIB_BUILD_DIR"):
        os.environ.pop(name, None)

    # Notebooks are independent (own kernel, own build/<stem>/, own seeds): run --jobs at once, the
    # longest first (by the last run's times) so that the last one to start is a short one.
    last = json.loads((build / "summary.json").read_text()) if (build / "summary.json").is_file() else {}
    order = sorted(notebooks, key=lambda p: -last.get(p.stem, {}).get("seconds", 0.0))
    start = time.perf_counter()
    done = {}
    # Workers are reused (each imports nbclient and nbconvert once, ~3 s); every notebook gets a new kernel.
    with ProcessPoolExecutor(max(1, args.jobs), mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {pool.submit(run_notebook, path, build, args.timeout): path for path in order}
        print(f"executing {len(notebooks)} notebooks, {max(1, args.jobs)} at a time ...", flush=True)
        for future in as_completed(futures):
            e = done[futures[future]] = future.result()
            tail = "" if e["error"] is None else f"\n    ERROR: {e['error']}"
            print(f"[{len(done)}/{len(notebooks)}] {e['notebook']} {'done' if e['ok'] else 'FAILED'} "
                  f"in {e['seconds']:.1f} s, peak memory {mb(e['peak_mb'])}{tail}", flush=True)
    entries = [done[path] for path in notebooks]
    wall = time.perf_counter() - start

    write_index(build, entries, root)
    manifest = write_manifest(build, entries)
    summary = {e["notebook"]: {k: e[k] for k in ("checks_passed", "checks_total", "seconds", "peak_mb", "ok", "error")}
               for e in entries}
    (build / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")

    width = max(len(e["notebook"]) for e in entries) + 3
    print()
    for e in entries:
        mark = "" if e["ok"] else "   FAILED"
        checks = f"{e['checks_passed']}/{e['checks_total']}"
        print(f"{e['notebook']:<{width}}{checks:>7} checks passed{e['seconds']:>9.1f} s{mb(e['peak_mb']):>10}{mark}")
    n_ok = sum(e["ok"] for e in entries)
    passed = sum(e["checks_passed"] for e in entries)
    total = sum(e["checks_total"] for e in entries)
    seconds = sum(e["seconds"] for e in entries)
    print(f"{'total':<{width}}{f'{passed}/{total}':>7} checks passed{seconds:>9.1f} s"
          f"   ({n_ok}/{len(entries)} notebooks ok; {wall:.1f} s wall with {max(1, args.jobs)} at a time)")
    for led in ledger.ledgers(build, root):
        if led.stem in {e["notebook"] for e in entries}:
            counts = led.counts
            print(f"{led.stem:<{width}}{len(led.rows):>4} claims: " + ", ".join(
                f"{counts[v]} {v}" for v in ledger.COLUMNS if counts.get(v)) + "".join(f"\n    {p}" for p in led.problems))
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
