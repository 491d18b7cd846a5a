#!/usr/bin/env python3
"""Execute every numbered notebook into build/ (the documentation site is built from it: make docs).

For each ``notebooks/NN_*.ipynb`` in name order (kernel ``python3``, working
directory ``notebooks/``) this writes

* ``build/<stem>.ipynb`` - the executed notebook (``tools/build_site.py`` renders it as a chapter),
* ``build/<stem>.kernel.log`` - the kernel process's own stderr,
* ``build/<stem>.run.json`` - the record of the execution: its report entry, the SHA-256 of its inputs
  (:func:`inputs_digest`) and of its outputs (executed notebook, results, figures),

and reads ``build/<stem>/results.json`` and ``build/<stem>/figures/*.png``,
which the notebook itself writes through ``navlib.repro``. Then it writes
``build/summary.json`` and ``build/manifest.json`` (SHA-256 of every
results file and figure), and prints one line per notebook and the claims by verdict per paper
(the site's home page and ledger show every claim and check: ``make docs``).
``--check-against MANIFEST`` fails the run unless those files are
byte-identical to an earlier run's (``make determinism``).

Notebooks run ``--jobs`` at a time (default: one more than the cores, :func:`default_jobs`), each in its own kernel,
longest first by the previous run's times in ``build/summary.json`` less their numba compilation
(:func:`expected_seconds`; typical times on a fresh clone; the kernels log each compilation to
``build/<stem>.compile.log``, see ``navlib._kernels.CompileLog``); each is reported with its wall time and its
kernel's CPU time and peak memory (user + system time and resident set size, read from /proc while the kernel runs;
"n/a" where there is none; CPU time, unlike wall time, does not grow on a busy machine). When the notebooks will
compile kernels (a fresh clone, ``--cold``, navlib edited, numba's cache emptied), a warm-up goes first
(:func:`warm_up`, ``python -m navlib.warmup``, its two parts at once on two cores): every kernel the notebooks call is
compiled once, and the notebooks load them from numba's cache; a paper's further notebooks
(``05_pedestrian_ins_floors``) then start when its first one is done, for the same reason. Each kernel is a new
process; on Linux it is forked from a server that has imported ipykernel and the scientific stack once
(``tools/kernel_fork.py``; ~1.5 s of CPU less per notebook than a kernel started from nothing). A notebook that raises
is reported and the run goes on with the others; the exit status is non-zero if any notebook (or the warm-up) failed.
``--only`` runs a subset, and the report then covers that subset only. Needs no network.

``--stale`` (``make test``) executes only the notebooks whose last execution into build/ is missing, failed
or out of date (:func:`last_execution`) and reuses the others: each notebook is executed once per
``make test``, none again right after ``make reproduce``. ``tests/test_notebook_runs.py`` reads the records.

``--seeds N`` (or ``--seed-list 7,123,9999``) is the seed sweep (``make seeds``): every notebook whose
parameters cell sets ``SEED`` (the Monte Carlo ones) runs at full scale once per seed, the seed injected
papermill-style after that cell, in teaching mode (a failed check is recorded, not raised) with results in
``build/seeds/<seed>/``. It prints, per notebook, every check's values across the seeds and every claim's
verdicts, names each failed check and each verdict that is not the same on every seed (a flip), writes
``build/seeds.json`` and fails on any. A sweep seed inside a range used to set a tolerance
(``data/seed_studies/calibration_seeds.csv``) is refused: a tolerance is never tested on its own seeds.

``--profile`` also says where each notebook's time went: numba compilation against the rest, the
kernels by compile time and the slowest cells (the first is usually the imports). ``--cold`` gives the
kernels an empty numba cache (``NUMBA_CACHE_DIR``), as on a fresh clone; without it the repository's
cache is used (a warm rerun).

Usage: python tools/reproduce.py [--only PATTERN] [--root DIR] [--timeout S] [--jobs N] [--profile] [--cold]
                                 [--stale] [--seeds N | --seed-list S1,S2,...]
"""

from __future__ import annotations

import argparse
import ast
import csv
import ctypes
import fnmatch
import hashlib
import importlib.metadata
import json
import multiprocessing
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, as_completed, wait
from datetime import datetime
from pathlib import Path

# jsonschema (nbformat's validator) imports its optional IRI format checker, rfc3987_syntax, which builds
# ~35 Earley parsers at import: 1.3 s before the first notebook starts (python-jsonschema/jsonschema#1428).
# The notebook schema has no IRI fields; marked absent, jsonschema skips that checker.
sys.modules.setdefault("rfc3987_syntax", None)

import nbformat  # noqa: E402
from nbclient import NotebookClient  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import kernel_fork  # noqa: E402  (tools/kernel_fork.py: kernels forked from a process with the imports done)
import ledger  # noqa: E402  (tools/ledger.py: claims with their verdicts; no navlib import at module level)

SWEEP_SEEDS = (11, 29, 47, 83, 131, 257, 521, 1031, 5003, 8191)
"""The sweep's seeds, first ``--seeds N`` of them: outside every calibration range (calibration_seeds.csv)."""

START_METHOD = "fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn"


def unregistered(notebooks: list[Path]) -> list[str]:
    """Notebook stems that are neither a chapter without a paper nor a registered paper (navlib/papers/__init__.py)."""
    from navlib.papers import CHAPTERS, PAPERS  # the registry (imported here: the notebook workers need no navlib)

    known = set(CHAPTERS) | {stem for p in PAPERS for stem in p.notebooks}
    return [p.stem for p in notebooks if p.stem not in known]


def error_line(exc: BaseException) -> str:
    """The one line that says what went wrong (the traceback's last line)."""
    if getattr(exc, "ename", None):  # nbclient.exceptions.CellExecutionError
        return f"{exc.ename}: {exc.evalue}"
    lines = [ln.strip() for ln in str(exc).splitlines() if ln.strip()]
    return lines[-1] if lines else type(exc).__name__


KERNEL_START_TRIES = 3


def execute(client: NotebookClient, **kwargs) -> None:
    """``client.execute(**kwargs)``, with the kernel started again if it died before running a cell: kernels started
    at once can race for one free port ("Address already in use", seen in a seed sweep), a failed start, not a
    failed notebook (nbclient has cleaned the dead kernel up, so the next try starts a new one on new ports)."""
    for attempt in range(1, KERNEL_START_TRIES + 1):
        try:
            client.execute(**kwargs)
            return
        except RuntimeError as exc:
            if "before replying to kernel_info" not in str(exc) or attempt == KERNEL_START_TRIES:
                raise


def kernel_usage(client: NotebookClient) -> tuple[float | None, float | None]:
    """Peak resident memory (MB, VmHWM) and CPU time (s, user + system) of the client's kernel so far; Linux only.

    CPU seconds, unlike wall time, do not grow when other processes share the cores.
    """
    try:
        proc = Path(f"/proc/{client.km.provisioner.process.pid}")
        status, stat = (proc / "status").read_text(), (proc / "stat").read_text()
    except (AttributeError, OSError):
        return None, None
    peak = next((int(line.split()[1]) / 1024 for line in status.splitlines() if line.startswith("VmHWM:")), None)
    utime, stime = stat.rsplit(")", 1)[1].split()[11:13]  # fields 14 and 15 of proc(5), in clock ticks
    return peak, (int(utime) + int(stime)) / os.sysconf("SC_CLK_TCK")


LEDGER_ENV = {"MPLBACKEND": "module://matplotlib_inline.backend_inline", "NAVLIB_PROGRESS": "0"}
NOT_INHERITED = ("NAVLIB_TEACHING", "NAVLIB_FAST", "NAVLIB_BUILD_DIR")


def kernel_environment(root: Path) -> dict[str, str]:
    """This process's environment as the ledger's kernels get it.

    navlib.repro writes to <root>/build, figures render with the (headless) inline backend so the executed
    notebook shows them, no progress bars are kept, and a shell's teaching or fast switches or another build
    directory do not leak in: the papers' scale, checks that raise.
    """
    env = {k: v for k, v in os.environ.items() if k not in NOT_INHERITED}
    return env | LEDGER_ENV | {"NAVLIB_ROOT": str(root)}


# ------------------------------------------------------------------------- records of executed notebooks

RUN_INPUTS = ("navlib", "data", "tools/reproduce.py", "tools/kernel_fork.py")
"""What a notebook's execution depends on besides the notebook itself (paths under the repository root)."""


def inputs_digest(path: Path) -> str:
    """SHA-256 of everything the execution of notebook ``path`` depends on.

    The notebook, every file under navlib/ and data/ (``__pycache__`` left out: numba's cache does not change
    results), this runner, the Python version and the name and version of every installed distribution.
    """
    root = path.parents[1]
    files = [path]
    for name in RUN_INPUTS:
        top = root / name
        files += sorted(f for f in top.rglob("*") if "__pycache__" not in f.parts) if top.is_dir() else [top]
    digest = hashlib.sha256("\n".join([sys.version, *installed_distributions()]).encode())
    for f in files:
        if f.is_file():
            digest.update(f"\n{f.relative_to(root).as_posix()} {hashed(f)}".encode())
    return digest.hexdigest()


def installed_distributions() -> list[str]:
    """``name==version`` of every distribution on ``sys.path``, read from the names of their .dist-info folders (the
    wheel format spells both there; reading every METADATA file cost ~1 s per digest) or an .egg-info's metadata.

    A set: a distribution found twice on sys.path (the checkout's own egg-info beside the installed one) is one.
    """
    found = set()
    for entry in dict.fromkeys(sys.path):
        try:
            names = os.listdir(entry or ".")
        except OSError:  # a zip archive, a missing folder
            continue
        for name in names:
            if name.endswith(".dist-info"):
                found.add(name.removesuffix(".dist-info").replace("-", "==", 1))
            elif name.endswith(".egg-info"):
                dist = importlib.metadata.PathDistribution(Path(entry or ".", name))
                found.add(f"{name.removesuffix('.egg-info').split('-')[0]}=={dist.version}")
    return sorted(found)


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


_hashes: dict[Path, tuple[tuple[int, int], str]] = {}


def hashed(path: Path) -> str:
    """:func:`sha256` of ``path``, hashed again only when its modification time or size changed since this process
    last read it: every record's digest reads the same 17 MB of navlib/ and data/."""
    stat = path.stat()
    key = (stat.st_mtime_ns, stat.st_size)
    if path not in _hashes or _hashes[path][0] != key:
        _hashes[path] = (key, sha256(path))
    return _hashes[path][1]


def outputs_digest(build: Path, entry: dict) -> dict[str, str]:
    """SHA-256 of an execution's outputs: the executed notebook, its results.json and figures."""
    stem = entry["notebook"]
    files = [build / f"{stem}.ipynb", build / stem / "results.json"] + [build / f for f in entry["figures"]]
    return {f.relative_to(build).as_posix(): sha256(f) for f in files if f.is_file()}


def write_record(build: Path, entry: dict, inputs: str) -> None:
    """``build/<stem>.run.json``: an execution's report entry with the digests of its inputs and outputs."""
    record = {"inputs": inputs, "outputs": outputs_digest(build, entry), "entry": entry}
    (build / f"{entry['notebook']}.run.json").write_text(json.dumps(record, indent=1) + "\n")


def last_execution(path: Path, build: Path) -> tuple[dict | None, str]:
    """The report entry of notebook ``path``'s last execution into ``build``, if it still stands, and why not.

    It stands when ``build/<stem>.run.json`` exists, the notebook's inputs (:func:`inputs_digest`) are the same
    as when it ran and its outputs in ``build`` are the ones it wrote; else ``(None, reason)``. A failed
    execution stands too (its entry says so): running it again on the same inputs fails the same way.
    """
    file = build / f"{path.stem}.run.json"
    if not file.is_file():
        return None, "no execution recorded in build/"
    record = json.loads(file.read_text())
    if record["inputs"] != inputs_digest(path):
        return None, "the notebook, navlib, data/, the runner or the installed packages changed since it ran"
    if record["outputs"] != outputs_digest(build, record["entry"]):
        return None, "its executed notebook, results or figures in build/ changed since it ran"
    return record["entry"], "up to date"


def executed(path: Path, timeout: int = 1800) -> dict:
    """The report entry of notebook ``path`` executed into <root>/build: the last execution if it stands, else a new one."""
    build = path.parents[1] / "build"
    entry, _ = last_execution(path, build)
    if entry is None:
        build.mkdir(exist_ok=True)
        entry = run_notebook(path, build, timeout)
    return entry


def run_notebook(path: Path, build: Path, timeout: int, kernels: str | None = None) -> dict:
    """Execute one notebook, write the executed .ipynb, return its summary entry.

    ``kernels``: the address of a :mod:`kernel_fork` server to fork the notebook's kernel from (a new process
    either way); default a kernel started from nothing."""
    stem = path.stem
    shutil.rmtree(build / stem, ignore_errors=True)  # no stale results or figures
    inputs = inputs_digest(path)  # before the run: an input edited while it runs makes the record stale
    nb = nbformat.read(path, as_version=4)
    usage = {"peak_mb": None, "cpu_s": None}

    def after_cell(**_):  # the kernel's high-water mark and CPU time, read while it is alive
        peak_mb, cpu_s = kernel_usage(client)
        usage["peak_mb"], usage["cpu_s"] = peak_mb or usage["peak_mb"], cpu_s or usage["cpu_s"]

    compile_log = build / f"{stem}.compile.log"  # one line per numba compilation (navlib._kernels.CompileLog)
    compile_log.unlink(missing_ok=True)
    env = kernel_environment(path.parents[1]) | {"NAVLIB_COMPILE_LOG": str(compile_log)}
    # The kernel is killed once the last cell is done: every result, figure and log line is on disk by then,
    # and a graceful shutdown (the interpreter freeing a notebook's gigabyte) kept this worker ~1 s from the next.
    client = NotebookClient(
        nb,
        kernel_name="python3",
        timeout=timeout,
        on_cell_executed=after_cell,
        shutdown_kernel="immediate",
        resources={"metadata": {"path": str(path.parent)}},
        kernel_manager_class=kernel_fork.manager_class(kernels),
    )
    error = None
    start = time.perf_counter()
    with open(build / f"{stem}.kernel.log", "w") as log:
        try:
            execute(client, stderr=log, env=env)
        except Exception as exc:  # report it and go on with the next notebook
            error = error_line(exc)
    seconds = time.perf_counter() - start
    nbformat.write(nb, build / f"{stem}.ipynb")
    (build / f"{stem}.html").unlink(missing_ok=True)  # the last report's page (now: make docs)

    results = build / stem / "results.json"
    checks = json.loads(results.read_text())["checks"] if results.is_file() else []
    passed = sum(bool(c.get("passed")) for c in checks)
    figures = sorted(p.relative_to(build).as_posix() for p in (build / stem / "figures").glob("*.png"))
    compilations = read_compile_log(compile_log)
    compile_cpu = sum(cpu_s for _, _, cpu_s in read_compile_lines(compile_log))
    entry = {
        "notebook": stem,
        "ok": error is None and passed == len(checks),
        "error": error,
        "seconds": round(seconds, 1),
        "cpu_seconds": None if usage["cpu_s"] is None else round(usage["cpu_s"], 1),
        "compile_seconds": round(sum(s for s, _ in compilations), 1),
        "compile_cpu_seconds": round(compile_cpu, 1),
        "peak_mb": None if usage["peak_mb"] is None else round(usage["peak_mb"]),
        "checks_passed": passed,
        "checks_total": len(checks),
        "checks": checks,
        "figures": figures,
        "kernels": kernels_by_compile_time(compilations),
        "cells": cell_seconds(nb),
    }
    write_record(build, entry, inputs)
    return entry


def read_compile_log(path: Path) -> list[tuple[float, str]]:
    """``(seconds, function)`` of each outermost numba compilation a kernel logged (none without the file)."""
    return [(seconds, name) for seconds, name, _ in read_compile_lines(path)]


def read_compile_lines(path: Path) -> list[tuple[float, str, float]]:
    """``(seconds, function, CPU seconds)`` of each compilation a kernel logged (CPU 0 where it is not logged)."""
    if not path.is_file():
        return []
    lines = [line.split() for line in path.read_text().splitlines() if line.strip()]
    return [(float(p[0]), p[1] if len(p) > 1 else "?", float(p[2]) if len(p) > 2 else 0.0) for p in lines]


def kernels_by_compile_time(compilations: list[tuple[float, str]]) -> list[tuple[str, float, int]]:
    """``(function, seconds, compilations)`` per compiled function, longest compile time first."""
    total: dict[str, list] = {}
    for seconds, name in compilations:
        entry = total.setdefault(name, [0.0, 0])
        entry[0] += seconds
        entry[1] += 1
    return sorted(((name, round(s, 3), n) for name, (s, n) in total.items()), key=lambda k: -k[1])


def cell_seconds(nb) -> list[tuple[int, float, str]]:
    """``(cell index, seconds, first source line)`` of each executed code cell, slowest first (nbclient's timing)."""
    cells = []
    for index, cell in enumerate(nb.cells):
        timing = cell.get("metadata", {}).get("execution", {})
        if cell.cell_type == "code" and {"iopub.execute_input", "shell.execute_reply"} <= set(timing):
            seconds = (
                datetime.fromisoformat(timing["shell.execute_reply"]) - datetime.fromisoformat(timing["iopub.execute_input"])
            ).total_seconds()
            first_line = next((ln for ln in cell.source.splitlines() if ln.strip()), "")
            cells.append((index, round(seconds, 3), first_line[:70]))
    return sorted(cells, key=lambda c: -c[1])


WARM_UP_ALSO = ("navlib.papers.rotation_bias",)
"""Paper companions whose own kernels the warm-up compiles too (``_warm_up()``; the core names no paper): in the
first part, with all of them when the warm-up is one process."""


def warm_up(build: Path, part: int | None = None) -> dict:
    """Compile the kernels the notebooks call, before them: ``python -m navlib.warmup [--part N]``.

    The two parts (``navlib.warmup.PARTS``) run first, one per core, so that the notebooks load every kernel
    from numba's cache instead of compiling it, and never two at the same time (the quaternion Kalman filter alone
    is ~5 s of CPU). Its wall and CPU time and its compilations (``build/warmup[-N].compile.log``) are reported
    like a notebook's.
    """
    log = build / f"warmup{'' if part is None else f'-{part}'}.compile.log"
    log.unlink(missing_ok=True)
    before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "navlib.warmup"]
        + ([] if part is None else ["--part", str(part)])
        + [arg for module in (WARM_UP_ALSO if part in (None, 1) else ()) for arg in ("--also", module)],
        env=os.environ | {"NAVLIB_COMPILE_LOG": str(log)},
        capture_output=True,
        text=True,
        check=False,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return {
        "part": part,
        "error": None if done.returncode == 0 else error_line(RuntimeError(done.stderr or "navlib.warmup failed")),
        "seconds": round(time.perf_counter() - start, 1),
        "cpu_seconds": round(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, 1),
        "compile_cpu_seconds": round(sum(cpu_s for _, _, cpu_s in read_compile_lines(log)), 1),
    }


def default_jobs() -> int:
    """Notebooks run at once by default: one more than the cores this process may use (1 on one core).

    A notebook keeps its core busy about 85 % of its wall time (kernel start, messages, writing files are the
    rest); a third notebook on two cores fills those gaps: a warm run took 28.8-29.6 s with three at a time
    against 30.7-30.8 s with two, and 31.2 s with four (alternated, on the reference machine)."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return cores + 1 if cores > 1 else 1


def warm_up_parts(jobs: int) -> list[int | None]:
    """The warm-up's parts, one process each: both of ``navlib.warmup.PARTS`` on two cores or more, all in one else."""
    from navlib.warmup import PARTS

    return list(range(1, len(PARTS) + 1)) if jobs >= len(PARTS) else [None]


def paper_parts(notebooks: list[Path]) -> dict[Path, Path]:
    """Each further notebook of a paper (``05_pedestrian_ins_floors``) mapped to the paper's first one, both in
    ``notebooks``: it runs after that one, whose kernels it shares, so that it loads them from numba's cache
    instead of compiling them at the same time (navlib/papers/__init__.py)."""
    from navlib.papers import PAPERS

    by_stem = {p.stem: p for p in notebooks}
    return {
        by_stem[stem]: by_stem[paper.notebook]
        for paper in PAPERS
        for stem in paper.notebooks[1:]
        if stem in by_stem and paper.notebook in by_stem
    }


COLD_MARK = "cold-cache"
"""The file in build/ that says the last run compiled into a temporary numba cache (``--cold``)."""


def compilation_expected(build: Path, summary: dict, root: Path) -> bool:
    """Whether this run's notebooks will compile kernels: no earlier run, an earlier ``--cold`` one (its kernels went
    to a temporary cache), numba's cache emptied since (:func:`kernels_cached`) or navlib edited since it. An earlier
    run that compiled left its kernels in numba's cache: a warm run skips the warm-up (two processes, ~3 s of CPU)."""
    summary_file = build / "summary.json"
    if not summary or (build / COLD_MARK).is_file() or not kernels_cached(root):
        return True
    since = summary_file.stat().st_mtime
    return any(f.stat().st_mtime > since for f in (root / "navlib").rglob("*.py"))


def kernels_cached(root: Path) -> bool:
    """Whether numba's cache holds compiled navlib kernels: its index files in navlib's ``__pycache__`` folders, or
    under ``NUMBA_CACHE_DIR`` where that moves the cache."""
    cache = os.environ.get("NUMBA_CACHE_DIR")
    return next((Path(cache) if cache else root / "navlib").rglob("*.nbi"), None) is not None


TYPICAL_SECONDS = {
    "02_rotation_bias": 12.5,
    "07_real_references": 12.9,
    "01_north_finding": 8.7,
    "04_mimu_mag_rtk": 8.3,
    "00_conventions_sensors": 8.2,
    "05_pedestrian_ins": 6.6,
    "03_gauss_kruger_ekf": 6.1,
    "06_real_recordings": 4.5,
    "05_pedestrian_ins_floors": 4.4,
}
"""Each notebook's CPU seconds in a warm run on the reference machine: the order of a first run (a fresh clone
has no ``build/summary.json``), longest first, so that the last notebooks to start are short ones."""


def expected_seconds(summary: dict, notebooks: list[Path]) -> dict[Path, float]:
    """Each notebook's time in a run's ``summary.json`` less its numba compilation (:data:`TYPICAL_SECONDS` when not
    in it, else 0)."""
    return {
        p: summary[p.stem].get("seconds", 0.0) - summary[p.stem].get("compile_seconds", 0.0)
        if p.stem in summary
        else TYPICAL_SECONDS.get(p.stem, 0.0)
        for p in notebooks
    }


def longest_first(notebooks: list[Path], seconds: dict[Path, float]) -> list[Path]:
    """``notebooks`` by expected ``seconds``, longest first (ties and unknown ones, at 0 s, in name order)."""
    return sorted(notebooks, key=lambda p: -seconds[p])


def profile(e: dict, top: int = 5) -> str:
    """Where a notebook's time went: compilation against the rest, the kernels by compile time, the slowest cells."""
    lines = [
        f"{e['notebook']}: {e['seconds']:.1f} s = compile {e['compile_seconds']:.1f} + "
        f"other {e['seconds'] - e['compile_seconds']:.1f}; peak memory {mb(e['peak_mb'])}"
    ]
    if e.get("cpu_seconds") is not None:
        lines[0] += f"; CPU {e['cpu_seconds']:.1f} s, of which compile {e.get('compile_cpu_seconds') or 0.0:.1f} s"
    lines += [f"    compile {s:6.1f} s  {n} signature(s)  {name}" for name, s, n in e["kernels"][:top]]
    lines += [f"    cell {i:3d} {s:6.1f} s  {source}" for i, s, source in e["cells"][:top]]
    return "\n".join(lines)


def mb(x: float | None) -> str:
    return "n/a" if x is None else f"{x} MB"


def cpu(e: dict) -> str:
    """A notebook's kernel CPU time (user + system), "n/a" where it was not measured."""
    return "n/a" if e.get("cpu_seconds") is None else f"{e['cpu_seconds']:.1f} s"


def die_with_parent() -> None:
    """Pool worker initializer (Linux): the kernel ends the worker when this runner dies.

    Without it a runner killed alone left its forked workers waiting for work forever, and with them every
    file they inherited (a `flock` that queued the run stayed taken).
    """
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def write_manifest(build: Path, entries: list[dict]) -> dict:
    """SHA-256 of every results.json and PNG figure: what must not change between two runs."""
    files = []
    for e in entries:
        files += [build / e["notebook"] / "results.json"] + [build / f for f in e["figures"]]
    manifest = {p.relative_to(build).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest() for p in files if p.is_file()}
    (build / "manifest.json").write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n")
    return manifest


def compare_manifest(manifest: dict, reference: Path, notebooks: list[str]) -> list[str]:
    """Files of ``notebooks`` whose hash differs from (or is missing in) a previous run's manifest."""
    ref = {k: v for k, v in json.loads(reference.read_text()).items() if k.split("/")[0] in notebooks}
    return sorted(k for k in set(ref) | set(manifest) if ref.get(k) != manifest.get(k))


# ------------------------------------------------------------------------------------------ teaching runs

TEACHING_ENV = {"NAVLIB_TEACHING": "1", "NAVLIB_FAST": "1", "MPLBACKEND": "Agg"}
"""The switches of a teaching run (tests/test_teaching.py): failed checks warn, the small parameter set."""


def try_parameters(nb) -> list[dict[str, str]]:
    """The parameter changes a notebook invites (``metadata.navlib.try_parameters``): one mapping per teaching run."""
    changes = nb.metadata.get("navlib", {}).get("try_parameters", {})
    return [changes] if isinstance(changes, dict) else list(changes)


def teaching_runs(notebooks: list[Path]) -> list[tuple[Path, int]]:
    """``(notebook, run)`` of every teaching run: each notebook once per parameter change it invites."""
    return [(p, k) for p in notebooks for k in range(len(try_parameters(nbformat.read(p, as_version=4))))]


def inject(nb, assignments: dict[str, str]) -> None:
    """Insert ``NAME = value`` lines after the ``parameters`` cell (papermill's convention)."""
    code = "\n".join(f"{name} = {value}" for name, value in assignments.items())
    cell = nbformat.v4.new_code_cell("# injected parameters\n" + code)
    cell.metadata["tags"] = ["injected-parameters"]
    nb.cells.insert(parameters_cell(nb) + 1, cell)


def teaching_record(path: Path, run: int, build: Path) -> Path:
    """``build/teaching/<stem>-<run>.json``: the record of a teaching run (the site's course page lists them); its
    results are under ``build/teaching/<stem>-<run>/``."""
    return build / "teaching" / f"{path.stem}-{run}.json"


def teaching_inputs(path: Path, run: int) -> str:
    """SHA-256 of what a teaching run depends on: the notebook's :func:`inputs_digest` (its parameter changes are in
    the notebook), which change is injected, and the switches."""
    return hashlib.sha256(f"{inputs_digest(path)} {run} {sorted(TEACHING_ENV.items())}".encode()).hexdigest()


def teaching_outputs(path: Path, run: int, build: Path) -> dict[str, str]:
    """SHA-256 of a teaching run's results.json (the file the test reads)."""
    results = teaching_record(path, run, build).with_suffix("") / path.stem / "results.json"
    return {results.relative_to(build).as_posix(): sha256(results)} if results.is_file() else {}


def last_teaching_run(path: Path, run: int, build: Path) -> tuple[dict | None, str]:
    """The record of teaching run ``run`` of notebook ``path`` if it still stands (its inputs and results unchanged,
    as :func:`last_execution` decides for a notebook's execution), and why not."""
    file = teaching_record(path, run, build)
    if not file.is_file():
        return None, "no teaching run recorded in build/teaching/"
    record = json.loads(file.read_text())
    if record.get("inputs") != teaching_inputs(path, run):
        return None, "the notebook, navlib, data/, the runner or the installed packages changed since it ran"
    if record["outputs"] != teaching_outputs(path, run, build):
        return None, "its results in build/teaching/ changed since it ran"
    return record, "up to date"


def run_teaching(path: Path, run: int, build: Path, timeout: int) -> dict:
    """Execute teaching run ``run`` of a notebook (its ``run``-th parameter change injected, in teaching and fast mode,
    results under ``build/teaching/<stem>-<run>/``) and write its record; the record."""
    file = teaching_record(path, run, build)
    out = file.with_suffix("")
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    inputs = teaching_inputs(path, run)  # before the run, as for a notebook's execution
    nb = nbformat.read(path, as_version=4)
    changes = try_parameters(nb)[run]
    inject(nb, changes)
    env = kernel_environment(path.parents[1]) | TEACHING_ENV | {"NAVLIB_BUILD_DIR": str(out)}
    resources = {"metadata": {"path": str(path.parent)}}
    client = NotebookClient(nb, kernel_name="python3", timeout=timeout, shutdown_kernel="immediate", resources=resources)
    error, start = None, time.perf_counter()
    with open(file.with_suffix(".kernel.log"), "w") as log:
        try:
            execute(client, stderr=log, env=env)
        except Exception as exc:  # recorded; the test reports it
            error = error_line(exc)
    results = out / path.stem / "results.json"
    checks = json.loads(results.read_text()).get("checks", []) if results.is_file() else []
    record = {
        "notebook": path.stem,
        "run": run,
        "parameters": changes,
        "seconds": round(time.perf_counter() - start, 1),
        "checks_held": f"{sum(bool(c.get('passed')) for c in checks)}/{len(checks)}",
        "error": error,
        "inputs": inputs,
        "outputs": teaching_outputs(path, run, build),
    }
    file.write_text(json.dumps(record, indent=1) + "\n")
    return record


def teaching_executed(path: Path, run: int, timeout: int = 1800) -> dict:
    """The record of a teaching run of notebook ``path`` into <root>/build: the last one if it stands, else a new one."""
    build = path.parents[1] / "build"
    record, _ = last_teaching_run(path, run, build)
    return record if record is not None else run_teaching(path, run, build, timeout)


def stale_teaching_runs(notebooks: list[Path], build: Path) -> list[tuple[Path, int]]:
    """The teaching runs of ``notebooks`` whose record is missing, failed or out of date, longest first by their last
    times (a failed run is run again: its failure may have been the machine's, a timeout)."""
    runs = teaching_runs(notebooks)
    last = {(p, k): json.loads(f.read_text()) for p, k in runs if (f := teaching_record(p, k, build)).is_file()}
    todo = [(p, k) for p, k in runs if not ((r := last_teaching_run(p, k, build)[0]) and r["error"] is None)]
    return sorted(todo, key=lambda run: -last.get(run, {}).get("seconds", 0.0))


def run_stale_teaching(notebooks: list[Path], build: Path, jobs: int, timeout: int) -> int:
    """``--stale``: execute the :func:`stale_teaching_runs`, ``jobs`` at a time; reuse the others. The exit status: 1 if
    any failed."""
    todo = stale_teaching_runs(notebooks, build)
    print(f"teaching runs: executing {len(todo)}, the others up to date in build/teaching/ ...", flush=True)
    failed = 0
    with ProcessPoolExecutor(
        max(1, jobs), mp_context=multiprocessing.get_context(START_METHOD), initializer=die_with_parent
    ) as pool:
        for future in as_completed([pool.submit(run_teaching, p, k, build, timeout) for p, k in todo]):
            r = future.result()
            failed += r["error"] is not None
            print(
                f"teaching run {r['notebook']}-{r['run']} with {r['parameters']}: {r['seconds']:.1f} s, "
                f"{r['checks_held']} checks held" + (f", ERROR {r['error']}" if r["error"] else ""),
                flush=True,
            )
    return 1 if failed else 0


# ---------------------------------------------------------------------------------------------- seed sweep


def parameters_cell(nb) -> int:
    """Index of the cell tagged ``parameters``."""
    return next(i for i, c in enumerate(nb.cells) if "parameters" in c.metadata.get("tags", []))


def seeded_notebooks(notebooks: list[Path]) -> list[Path]:
    """The notebooks whose parameters cell assigns ``SEED`` (the Monte Carlo ones)."""

    def sets_seed(path: Path) -> bool:
        nb = nbformat.read(path, as_version=4)
        tree = ast.parse(nb.cells[parameters_cell(nb)].source)
        return any(
            isinstance(t, ast.Name) and t.id == "SEED" for node in tree.body if isinstance(node, ast.Assign) for t in node.targets
        )

    return [p for p in notebooks if sets_seed(p)]


def calibration_seeds(root: Path) -> dict[str, set[int]]:
    """Seeds used to set tolerances, per notebook stem (``data/seed_studies/calibration_seeds.csv``)."""
    used: dict[str, set[int]] = {}
    path = root / "data" / "seed_studies" / "calibration_seeds.csv"
    if path.is_file():
        lines = [line for line in path.read_text(encoding="utf-8").splitlines() if not line.startswith("#")]
        for row in csv.DictReader(lines):
            used.setdefault(row["notebook"], set()).update(range(int(row["first"]), int(row["last"]) + 1))
    return used


def run_seed(path: Path, seed: int, out: Path, timeout: int) -> dict:
    """Execute one notebook with ``SEED = seed`` in teaching mode into ``out``; its checks and verdicts."""
    nb = nbformat.read(path, as_version=4)
    cell = nbformat.v4.new_code_cell(f"# injected by tools/reproduce.py --seeds\nSEED = {seed}")
    cell.metadata["tags"] = ["injected-parameters"]
    nb.cells.insert(parameters_cell(nb) + 1, cell)
    shutil.rmtree(out / path.stem, ignore_errors=True)  # a run that fails must not report the last run's checks
    os.environ.update(NAVLIB_TEACHING="1", NAVLIB_BUILD_DIR=str(out))  # the kernel inherits them
    client = NotebookClient(
        nb,
        kernel_name="python3",
        timeout=timeout,
        shutdown_kernel="immediate",
        resources={"metadata": {"path": str(path.parent)}},
    )
    error, start = None, time.perf_counter()
    try:
        execute(client)
    except Exception as exc:  # reported with the run; the sweep goes on
        error = error_line(exc)
    seconds = time.perf_counter() - start
    res = ledger.results(out, path.stem) or {}
    return {
        "notebook": path.stem,
        "seed": seed,
        "seconds": round(seconds, 1),
        "error": error,
        "checks": {c["name"]: {"value": c["value"], "passed": bool(c["passed"])} for c in res.get("checks", [])},
        "verdicts": {v["claim"]: v["verdict"] for v in res.get("verdicts", [])},
    }


def sweep_table(runs: list[dict], seeds: list[int]) -> dict:
    """One notebook's runs gathered per check and per claim, with the failures and flips."""
    by_seed = {r["seed"]: r for r in runs}
    names = list(dict.fromkeys(n for r in runs for n in r["checks"]))
    claims = list(dict.fromkeys(c for r in runs for c in r["verdicts"]))
    checks = {
        n: {
            "values": [by_seed[s]["checks"].get(n, {}).get("value") for s in seeds],
            "failed": [s for s in seeds if not by_seed[s]["checks"].get(n, {}).get("passed", False)],
        }
        for n in names
    }
    verdicts = {c: [by_seed[s]["verdicts"].get(c, "no verdict") for s in seeds] for c in claims}
    return {
        "seconds": [by_seed[s]["seconds"] for s in seeds],
        "errors": {s: by_seed[s]["error"] for s in seeds if by_seed[s]["error"]},
        "checks": checks,
        "verdicts": verdicts,
        "failures": {n: c["failed"] for n, c in checks.items() if c["failed"]},
        "flips": {c: v for c, v in verdicts.items() if len(set(v)) > 1},
    }


def number(x) -> str:
    return "missing" if x is None else f"{x:.5g}"


def print_sweep(stem: str, table: dict, seeds: list[int]) -> None:
    """Every check's values and every claim's verdicts across the seeds; failures and flips marked."""
    print(f"\n== {stem}: seeds {', '.join(map(str, seeds))}; {sum(table['seconds']):.0f} s")
    width = max([len(n) for n in table["checks"]] + [len(c) for c in table["verdicts"]] + [10])
    for name, c in table["checks"].items():
        mark = f"   FAILED on {', '.join(map(str, c['failed']))}" if c["failed"] else ""
        print(f"  {name:<{width}}  " + "  ".join(f"{number(v):>10}" for v in c["values"]) + mark)
    for claim, words in table["verdicts"].items():
        print(f"  {claim:<{width}}  " + (" | ".join(words) + "   FLIP" if len(set(words)) > 1 else words[0]))
    for seed, error in table["errors"].items():
        print(f"  seed {seed}: ERROR {error}")


def sweep(args: argparse.Namespace, root: Path, notebooks: list[Path], build: Path) -> int:
    """The seed sweep: every seeded notebook once per seed; prints and writes build/seeds.json; the exit status."""
    seeds = [int(s) for s in args.seed_list.split(",")] if args.seed_list else list(SWEEP_SEEDS[: args.seeds])
    notebooks = seeded_notebooks(notebooks)
    used = calibration_seeds(root)
    clash = {p.stem: sorted(set(seeds) & used.get(p.stem, set())) for p in notebooks}
    if any(clash.values()):
        print(
            "seeds used to set tolerances (data/seed_studies/calibration_seeds.csv), not a test of them: "
            + "; ".join(f"{k}: {v}" for k, v in clash.items() if v),
            file=sys.stderr,
        )
        return 1
    os.environ.pop("NAVLIB_FAST", None)
    last = json.loads((build / "summary.json").read_text()) if (build / "summary.json").is_file() else {}
    order = longest_first(notebooks, expected_seconds(last, notebooks))
    print(
        f"seed sweep: {len(notebooks)} notebooks x {len(seeds)} seeds ({', '.join(map(str, seeds))}), "
        f"{max(1, args.jobs)} at a time ...",
        flush=True,
    )
    start, runs = time.perf_counter(), []
    with ProcessPoolExecutor(
        max(1, args.jobs), mp_context=multiprocessing.get_context(START_METHOD), initializer=die_with_parent
    ) as pool:
        futures = [pool.submit(run_seed, p, s, build / "seeds" / str(s), args.timeout) for p in order for s in seeds]
        for future in as_completed(futures):
            r = future.result()
            runs.append(r)
            bad = sum(not c["passed"] for c in r["checks"].values())
            print(
                f"[{len(runs)}/{len(futures)}] {r['notebook']} seed {r['seed']}: {r['seconds']:.1f} s, "
                f"{len(r['checks']) - bad}/{len(r['checks'])} checks passed" + (f", ERROR {r['error']}" if r["error"] else ""),
                flush=True,
            )
    wall = time.perf_counter() - start
    tables = {p.stem: sweep_table([r for r in runs if r["notebook"] == p.stem], seeds) for p in notebooks}
    for stem, table in tables.items():
        print_sweep(stem, table, seeds)
    failures = sum(len(t["failures"]) for t in tables.values())
    flips = sum(len(t["flips"]) for t in tables.values())
    errors = sum(len(t["errors"]) for t in tables.values())
    (build / "seeds.json").write_text(
        json.dumps({"seeds": seeds, "wall_seconds": round(wall, 1), "notebooks": tables}, indent=1) + "\n"
    )
    print(
        f"\nseed sweep: {len(notebooks)} notebooks x {len(seeds)} seeds in {wall:.0f} s wall: {failures} failed "
        f"checks, {flips} verdict flips, {errors} notebook errors (build/seeds.json)"
    )
    for stem, t in tables.items():
        for name, failed in t["failures"].items():
            print(f"    {stem}: check {name} failed on seed {', '.join(map(str, failed))}")
        for claim, words in t["flips"].items():
            print(f"    {stem}: verdict of {claim} flips: " + ", ".join(f"{s} {w}" for s, w in zip(seeds, words, strict=True)))
    return 0 if failures == flips == errors == 0 else 1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", metavar="PATTERN", help="run only notebooks whose name matches (substring or glob)")
    ap.add_argument("--root", type=Path, default=REPO, help="repository root holding notebooks/ (default: this repo)")
    ap.add_argument("--timeout", type=int, default=1800, help="per-cell timeout in seconds (default 1800)")
    ap.add_argument(
        "--jobs",
        type=int,
        default=default_jobs(),
        help="notebooks executed at once, each in its own kernel (default: one more than the cores, 1 on one core)",
    )
    ap.add_argument(
        "--check-against",
        type=Path,
        metavar="MANIFEST",
        help="fail unless every results.json and PNG is byte-identical to this earlier manifest",
    )
    ap.add_argument(
        "--profile",
        action="store_true",
        help="also report each notebook's compile time, kernels by compile time and slowest cells",
    )
    ap.add_argument("--cold", action="store_true", help="an empty numba cache for the kernels, as on a fresh clone")
    ap.add_argument(
        "--stale",
        action="store_true",
        help="execute only the notebooks whose last execution into build/ is missing, failed or out of date "
        "(make test); reuse the others",
    )
    seeds = ap.add_mutually_exclusive_group()
    seeds.add_argument(
        "--seeds",
        type=int,
        metavar="N",
        choices=range(1, len(SWEEP_SEEDS) + 1),
        help=f"seed sweep with the first N of {SWEEP_SEEDS} (make seeds)",
    )
    seeds.add_argument("--seed-list", metavar="S1,S2,...", help="seed sweep with these seeds")
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
    for name in NOT_INHERITED:  # the seed sweep's kernels inherit os.environ (and set their own switches)
        os.environ.pop(name, None)
    os.environ.update(kernel_environment(root))
    if args.seeds or args.seed_list:
        return sweep(args, root, notebooks, build)
    with tempfile.TemporaryDirectory(prefix="navlib-numba-cache-") as empty_cache:
        if args.cold:
            os.environ["NUMBA_CACHE_DIR"] = empty_cache  # the kernels compile as on a fresh clone
        status = run_all(args, root, notebooks, build)
        if args.stale:  # make test: the teaching runs of tests/test_teaching.py too
            status |= run_stale_teaching(notebooks, build, args.jobs, args.timeout)
        return status


def run_all(args: argparse.Namespace, root: Path, notebooks: list[Path], build: Path) -> int:
    """Execute ``notebooks``, write build/'s summary and manifest, print the report; the exit status."""
    # Notebooks are independent (own kernel, own build/<stem>/, own seeds): run --jobs at once, longest first
    # by the last run's times without its numba compilation (cached for this run).
    last = json.loads((build / "summary.json").read_text()) if (build / "summary.json").is_file() else {}
    done = {}
    if args.stale:  # passed executions whose inputs and outputs are unchanged are not run again
        done = {p: e for p in notebooks if (e := last_execution(p, build)[0]) and e["ok"]}
        for path in done:
            print(f"{path.stem}: up to date in build/ (not executed again)", flush=True)
    order = longest_first([p for p in notebooks if p not in done], expected_seconds(last, notebooks))
    warm: list = []
    start = time.perf_counter()
    # Workers are reused and forked: they start with nbclient and nbformat already imported (spawned ones
    # imported them again, ~1.5 s each, while the notebooks waited); every notebook gets a new kernel, forked
    # from a server that has imported ipykernel and the scientific stack once (tools/kernel_fork.py).
    with (
        tempfile.TemporaryDirectory(prefix="navlib-kernels-") as folder,
        ProcessPoolExecutor(
            max(1, args.jobs), mp_context=multiprocessing.get_context(START_METHOD), initializer=die_with_parent
        ) as pool,
    ):
        kernels = str(Path(folder) / "fork.sock") if kernel_fork.SUPPORTED else None
        server = kernel_fork.start(kernels) if order and kernels else None
        if order and (args.cold or compilation_expected(build, last, root)):
            # first, one part per worker, and the notebooks after both: every kernel compiled once, none while a
            # notebook that calls it runs (the parts' times differ by a second or two: that is the wait)
            warm = [pool.submit(warm_up, build, part) for part in warm_up_parts(max(1, args.jobs))]
            print(f"warm-up: compiling the kernels in {len(warm)} process(es) ...", flush=True)
            for future in as_completed(warm):
                w = future.result()
                part = "" if w["part"] is None else f" --part {w['part']}"
                print(
                    f"warm-up (python -m navlib.warmup{part}) {'done' if w['error'] is None else 'FAILED'} in "
                    f"{w['seconds']:.1f} s ({w['cpu_seconds']:.1f} s CPU, {w['compile_cpu_seconds']:.1f} s compiling)"
                    + ("" if w["error"] is None else f"\n    ERROR: {w['error']}"),
                    flush=True,
                )
        # a paper's further notebooks after its first when they would compile the same kernels (not in a warm run)
        parts = paper_parts(order) if warm else {}  # submitted when their paper's first notebook is done
        futures = {pool.submit(run_notebook, path, build, args.timeout, kernels): path for path in order if path not in parts}
        if server is not None and not kernel_fork.wait_ready(kernels, server):  # the workers wait for it meanwhile
            print("kernel fork server did not start: kernels start from nothing", flush=True)
        print(f"executing {len(order)} notebooks, {max(1, args.jobs)} at a time ...", flush=True)
        pending = set(futures)
        while pending:
            finished, pending = wait(pending, return_when=FIRST_COMPLETED)
            for path in [p for p, first in parts.items() for f in finished if futures.get(f) == first]:
                future = pool.submit(run_notebook, path, build, args.timeout, kernels)
                futures[future] = path
                pending.add(future)
            for future in finished:
                e = done[futures[future]] = future.result()
                tail = "" if e["error"] is None else f"\n    ERROR: {e['error']}"
                print(
                    f"[{len(done)}/{len(notebooks)}] {e['notebook']} {'done' if e['ok'] else 'FAILED'} "
                    f"in {e['seconds']:.1f} s ({cpu(e)} CPU), peak memory {mb(e['peak_mb'])}{tail}",
                    flush=True,
                )
        if server is not None:
            server.kill()
            server.wait()
    entries = [done[path] for path in notebooks]
    wall = time.perf_counter() - start
    warm_up_run = [w.result() for w in warm]  # its CPU and compilation count in the totals

    (build / "index.html").unlink(missing_ok=True)  # the hand-written report: replaced by make docs
    manifest = write_manifest(build, entries)
    summary = {
        e["notebook"]: {
            k: e.get(k)
            for k in (
                "checks_passed",
                "checks_total",
                "seconds",
                "cpu_seconds",
                "compile_seconds",
                "compile_cpu_seconds",
                "peak_mb",
                "ok",
                "error",
            )
        }
        for e in entries
    }
    (build / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    if args.cold:
        (build / COLD_MARK).write_text("the last run compiled into a temporary numba cache (--cold)\n")
    else:
        (build / COLD_MARK).unlink(missing_ok=True)

    width = max(len(e["notebook"]) for e in entries) + 3
    print()
    for e in entries:
        mark = "" if e["ok"] else "   FAILED"
        checks = f"{e['checks_passed']}/{e['checks_total']}"
        print(
            f"{e['notebook']:<{width}}{checks:>7} checks passed{e['seconds']:>9.1f} s{cpu(e):>9} CPU{mb(e['peak_mb']):>10}{mark}"
        )
    for w in warm_up_run:
        label = "warm-up" if w["part"] is None else f"warm-up {w['part']}"
        print(
            f"{label:<{width}}{'':>7}{'':>14}{w['seconds']:>9.1f} s{cpu(w):>9} CPU" + ("" if w["error"] is None else "   FAILED")
        )
    n_ok = sum(e["ok"] for e in entries)
    passed = sum(e["checks_passed"] for e in entries)
    total = sum(e["checks_total"] for e in entries)
    seconds = sum(e["seconds"] for e in entries)
    cpu_total = {"cpu_seconds": sum(e.get("cpu_seconds") or 0.0 for e in entries + warm_up_run)}
    compile_cpu = sum(e.get("compile_cpu_seconds") or 0.0 for e in entries + warm_up_run)
    print(
        f"{'total':<{width}}{f'{passed}/{total}':>7} checks passed{seconds:>9.1f} s{cpu(cpu_total):>9} CPU"
        f"   ({n_ok}/{len(entries)} notebooks ok; {compile_cpu:.1f} s CPU compiling; {wall:.1f} s wall with "
        f"{max(1, args.jobs)} at a time"
        + (f"; {len(notebooks) - len(order)} up to date, not executed again)" if args.stale else ")")
    )
    for led in ledger.ledgers(build, root):
        if led.stem in {e["notebook"] for e in entries}:
            counts = led.counts
            print(
                f"{led.stem:<{width}}{len(led.rows):>4} claims: "
                + ", ".join(f"{counts[v]} {v}" for v in ledger.COLUMNS if counts.get(v))
                + "".join(f"\n    {p}" for p in led.problems)
            )
    if args.profile:
        print("\n" + "\n".join(profile(e) for e in entries))
    print("site: make docs (build/site/index.html)")
    if args.check_against:
        changed = compare_manifest(manifest, args.check_against, [p.stem for p in notebooks])
        print(
            f"determinism: {len(manifest)} files, {len(changed)} differ from {args.check_against.name}"
            + "".join(f"\n    {c}" for c in changed)
        )
        if changed:
            return 1
    return 0 if n_ok == len(entries) and all(w["error"] is None for w in warm_up_run) else 1


if __name__ == "__main__":
    sys.exit(main())
