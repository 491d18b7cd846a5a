"""The paper-vs-reproduction ledger: every claim of ``data/claims.csv`` with its verdict.

Shared by ``tools/build_site.py`` (the site's home page and ledger), ``tools/reproduce.py`` and
``tools/readme.py`` (the README's results section). A claim's verdict is owned by its notebook: the notebook records it with
``navlib.repro.verdict`` into ``build/<notebook>/results.json``, resting on the checks recorded
there. ``data/claims.csv`` holds no verdict (one owner, no second copy that could disagree); a
claim whose notebook records none is shown as *no verdict yet* and never counted as reproduced.

Two words are kept apart everywhere: a *claim* is a statement of a paper (a catalogue row), a
*check* is one computed comparison of a notebook (a row of results.json). Coverage counts the
claims whose verdict rests on at least one passed check.

A claim is *not checkable here* for a reason of a fixed vocabulary, its catalogue kind (``NOT_CHECKABLE``: hardware
only, datasheet, data not available, paper too vague, not a result), with the notebook's sentence why; the ledger
shows both.

A claim may carry a second verdict whose evidence is a committed real recording (``repro.verdict(...,
real_data=True)``, recorded by the notebook that holds the recording, e.g. 07_real_references): the ledger shows it
beside the simulation verdict (``Row.real``) and counts it apart; coverage and the verdict columns count the
claim's own (simulation) verdict only.

Verdict words judge what a paper states. A catalogue row of kind ``extension`` (the project's own quantity, a
test vector, a reconstruction of something the paper does not print) is not a paper claim: it sits in the
ledger's separate *extensions* list with the one verdict ``extension`` (its checks passed), outside the counts.
"""

from __future__ import annotations

import csv
import json
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NO_VERDICT = "no verdict yet"
VERDICTS = (
    "reproduced",
    "reproduced with correction",
    "differs",
    "refuted",
    "direction only",
    "undecided at this scale",
    "not checkable here",
    "extension",
)
"""The verdicts in the ledger's order (the same tuple as ``navlib.repro.VERDICTS``; tests/test_ledger.py checks)."""
EXTENSION = "extension"
NOT_CHECKABLE = {
    "hardware-only": "hardware only",
    "datasheet": "datasheet",
    "data-not-available": "data not available",
    "paper-too-vague": "paper too vague",
    "not-a-result": "not a result",
}
"""The catalogue kinds that say why a claim is *not checkable here*, as the ledger shows them (the same mapping as
``navlib.repro.NOT_CHECKABLE``; tests/test_ledger.py checks)."""
COLUMNS = (*(v for v in VERDICTS if v != EXTENSION), NO_VERDICT)
"""The verdict columns of the paper claims (an extension is not one)."""


def read_csv(path: Path) -> list[dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


def claims(root: Path = ROOT) -> list[dict[str, str]]:
    """The rows of ``data/claims.csv``, in catalogue order."""
    return read_csv(root / "data" / "claims.csv")


def results(build: Path, stem: str) -> dict | None:
    """``build/<stem>/results.json``, or None when the notebook has not run."""
    path = build / stem / "results.json"
    return json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None


@dataclass
class Row:
    """One claim in the ledger."""

    claim: str
    item: str
    quantity: str
    kind: str
    paper: str
    ours: str = ""
    verdict: str = NO_VERDICT
    reason: str = ""
    erratum: str = ""
    figure: str = ""  # path relative to build/, or ""
    checks: list[str] = field(default_factory=list)
    stem: str = ""  # the notebook that recorded the verdict, or ""
    real: Row | None = None  # the verdict on real data (evidence: a committed recording), if any

    @property
    def computed(self) -> bool:
        """The verdict rests on a computation: at least one check of the notebook."""
        return self.verdict not in (NO_VERDICT, "not checkable here") and bool(self.checks)


@dataclass
class PaperLedger:
    """The claims of one paper with their verdicts, and the checks of its notebooks."""

    stem: str  # the paper's notebook (the first, when it is taught in several: ``stems``)
    paper: str
    title: str
    rows: list[Row]
    extensions: list[Row] = field(default_factory=list)  # the project's own quantities (kind extension)
    checks_passed: int = 0
    checks_total: int = 0
    ran: bool = False
    problems: list[str] = field(default_factory=list)
    stems: list[str] = field(default_factory=list)  # every notebook of the paper, ``stem`` first

    @property
    def counts(self) -> Counter:
        return Counter(r.verdict for r in self.rows)

    @property
    def computed(self) -> int:
        return sum(r.computed for r in self.rows)

    @property
    def real_counts(self) -> Counter:
        """The real-data verdicts by word (paper claims and extensions)."""
        return Counter(r.real.verdict for r in (*self.rows, *self.extensions) if r.real is not None)


def paper_ledger(
    stem: str,
    paper: str,
    title: str,
    catalogue: list[dict[str, str]],
    res: dict | None,
    parts: dict[str, dict | None] | None = None,
) -> PaperLedger:
    """Join the catalogue's claims of ``paper`` with the verdicts of its notebook's results.

    ``parts`` holds the results of the paper's further notebooks by stem (``navlib.papers.Paper.parts``, a paper taught
    in several lessons): their checks add up with the first notebook's, and each claim takes its verdict from the one
    notebook that records it; a claim given a verdict twice, or a notebook that has not run, is a problem.
    """
    own = [c for c in catalogue if c["paper"] == paper]
    rows = {c["id"]: Row(c["id"], c["item"], c["quantity"], c["kind"], c["paper_value"]) for c in own}
    runs = {stem: res, **(parts or {})}
    led = PaperLedger(
        stem,
        paper,
        title,
        [r for r in rows.values() if r.kind != EXTENSION],
        [r for r in rows.values() if r.kind == EXTENSION],
        stems=list(runs),
    )
    led.ran = any(r is not None for r in runs.values())
    for part, part_res in runs.items():
        if part_res is not None:
            join(led, rows, part, part_res)
        elif led.ran:
            led.problems.append(f"{part} has not run: the claims it checks have no verdict")
    return led


def join(led: PaperLedger, rows: dict[str, Row], stem: str, res: dict) -> None:
    """Add one notebook's checks and verdicts to its paper's ledger."""
    paper = led.paper
    checks = res.get("checks", [])
    led.checks_passed += sum(bool(c.get("passed")) for c in checks)
    led.checks_total += len(checks)
    if res.get("paper") not in (None, paper):
        led.problems.append(f"{stem}/results.json names paper {res.get('paper')}, the registry {paper}")
    if res.get("mode"):  # a teaching or fast run: not the ledger's evidence
        led.problems.append(f"{stem}/results.json was written in {res['mode']} mode; rerun make reproduce")
    for v in res.get("verdicts", []):
        if v.get("real_data"):  # joined by ledgers(), from whichever notebook recorded it
            continue
        row = rows.get(v["claim"])
        if row is None:
            led.problems.append(f"verdict for {v['claim']}, not a claim of paper {paper}")
            continue
        _apply(row, v, stem, led.problems)


def _apply(row: Row, v: dict, stem: str, problems: list[str], real_data: bool = False) -> bool:
    """Put the verdict ``v`` (a results.json entry of notebook ``stem``) on ``row``; False (and a problem) if invalid.

    A claim not checkable here by simulation may still carry a real-data verdict: the kind's guard holds for the
    claim's own (simulation) verdict only."""
    if v["verdict"] not in VERDICTS:
        problems.append(f"{v['claim']}: unknown verdict {v['verdict']!r}")
        return False
    if (row.kind == EXTENSION) != (v["verdict"] == EXTENSION):
        problems.append(f"{v['claim']}: verdict {v['verdict']!r} on a row of kind {row.kind!r}")
        return False
    if not real_data and (row.kind in NOT_CHECKABLE) != (v["verdict"] == "not checkable here"):
        problems.append(
            f"{v['claim']}: verdict {v['verdict']!r} on a row of kind {row.kind!r} (the kinds that say "
            "why a claim is not checkable here go with that verdict, and only they)"
        )
        return False
    if row.stem:
        problems.append(f"{v['claim']}: a verdict in {row.stem} and another in {stem}")
        return False
    row.stem = stem
    row.verdict, row.reason, row.erratum, row.checks = v["verdict"], v["reason"], v["erratum"], v["checks"]
    row.ours = v["ours"] or ""
    if v["paper"] is not None:
        row.paper = v["paper"]
    if v["figure"]:
        row.figure = f"{stem}/figures/{v['figure']}.png"
    return True


def join_real_data(leds: list[PaperLedger], runs: dict[str, dict | None]) -> None:
    """Attach the real-data verdicts of the notebooks' results (by stem) to their claims' rows (``Row.real``)."""
    by_id = {r.claim: (led, r) for led in leds for r in (*led.rows, *led.extensions)}
    for stem, res in runs.items():
        for v in (res or {}).get("verdicts", []):
            if not v.get("real_data"):
                continue
            if v["claim"] not in by_id:
                leds[0].problems.append(f"{stem}: real-data verdict for {v['claim']}, not a claim of data/claims.csv")
                continue
            led, row = by_id[v["claim"]]
            real = row.real or Row(row.claim, row.item, row.quantity, row.kind, row.paper)  # a second one: a problem
            if _apply(real, v, stem, led.problems, real_data=True):
                row.real = real


def ledgers(build: Path, root: Path = ROOT) -> list[PaperLedger]:
    """One ledger per registered paper (all its notebooks), in notebook order."""
    from navlib.papers import CHAPTERS, PAPERS  # the registry (imported here: reproduce.py's workers need no navlib)

    catalogue = claims(root)
    leds = [
        paper_ledger(
            p.notebook,
            p.claims_id,
            p.citation,
            catalogue,
            results(build, p.notebook),
            {s: results(build, s) for s in p.notebooks[1:]},
        )
        for p in sorted(PAPERS, key=lambda p: p.number)
    ]
    join_real_data(leds, {s: results(build, s) for s in sorted({*CHAPTERS, *(s for led in leds for s in led.stems)})})
    return leds


def verdict_text(row: Row) -> str:
    """The verdict with its erratum or reason, as one line (a real-data row's own verdict: pass ``row.real``)."""
    text = row.verdict
    if row.verdict == "not checkable here" and row.kind in NOT_CHECKABLE:
        text += f" ({NOT_CHECKABLE[row.kind]})"
    if row.erratum and row.verdict == "reproduced with correction":
        text += f" ({row.erratum})"
    if row.reason:
        text += f": {row.reason}"
    return text


def check_value(build: Path, stem: str, name: str) -> float:
    """The value of check ``name`` of notebook ``stem`` (for numbers quoted in prose)."""
    res = results(build, stem)
    if res is None:
        raise KeyError(f"{stem} has no results in {build}")
    for c in res["checks"]:
        if c["name"] == name:
            return c["value"]
    raise KeyError(f"{stem} recorded no check {name!r}")
