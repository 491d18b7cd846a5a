"""The ledger of claims and verdicts, checked on the committed files (no notebook is run).

* Every paper notebook calls ``repro.setup("<stem>", paper="<claims_id>")`` with its registry entry's
  claims id; the notebooks without a paper pass none.
* Every ``repro.verdict(...)`` call written in a notebook names a claim of that notebook's paper (a real-data
  verdict, ``real_data=True``: of any paper), a known verdict, and at most once per kind of evidence; "not checkable
  here" is the simulation verdict of (and only of) a claim whose catalogue kind says why (hardware only, datasheet,
  data not available, paper too vague, not a result), and the ledger shows it.
* ``tools/ledger.py`` and ``navlib.repro`` know the same verdicts, and ``docs/claims.md`` explains each.
* The ledger joins a results file with the catalogue as documented: every claim appears once, a claim
  without a verdict is "no verdict yet" and does not count as covered.
"""

from __future__ import annotations

import ast
import csv
import json
import sys
from pathlib import Path

import pytest

from navlib import repro
from navlib.papers import CHAPTERS, PAPERS, by_notebook

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import ledger  # noqa: E402

NOTEBOOKS = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
with open(ROOT / "data" / "claims.csv", newline="", encoding="utf-8") as _fh:
    CLAIMS = {r["id"]: r for r in csv.DictReader(_fh)}


def code(path: Path) -> list[str]:
    nb = json.loads(path.read_text(encoding="utf-8"))
    return ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]


def calls(path: Path, name: str) -> list[ast.Call]:
    """Every call of ``name`` or ``<module>.name`` in the notebook's code cells."""
    out = []
    for src in code(path):
        src = "\n".join(line for line in src.splitlines() if not line.lstrip().startswith(("%", "!")))
        for node in ast.walk(ast.parse(src)):
            if isinstance(node, ast.Call):
                f = node.func
                if (isinstance(f, ast.Name) and f.id == name) or (isinstance(f, ast.Attribute) and f.attr == name):
                    out.append(node)
    return out


def literal(node: ast.Call, pos: int, key: str):
    """The literal value of argument ``pos`` / keyword ``key``, or None when it is not a literal."""
    arg = node.args[pos] if len(node.args) > pos else next((k.value for k in node.keywords if k.arg == key), None)
    try:
        return ast.literal_eval(arg) if arg is not None else None
    except ValueError:
        return None


def static_verdicts(path: Path, real_data: bool = False) -> dict[str, str]:
    """claim id -> verdict of the notebook's literal ``verdict(...)`` calls (those with ``real_data=True``, or not)."""
    out = {}
    for node in calls(path, "verdict"):
        claim, verdict = literal(node, 0, "claim"), literal(node, 1, "verdict")
        if isinstance(claim, str) and isinstance(verdict, str) and bool(literal(node, 99, "real_data")) == real_data:
            assert claim not in out, f"{path.stem}: two verdict calls for {claim}"
            out[claim] = verdict
    return out


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_setup_names_the_registered_paper(path):
    paper = by_notebook(path.stem)
    setups = [literal(node, 99, "paper") for node in calls(path, "setup")]
    assert setups, "no repro.setup call"
    assert setups == [paper.claims_id if paper else None] * len(setups), (
        f"repro.setup(..., paper=...) must be the registry's claims_id {paper.claims_id if paper else None!r}"
    )


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_verdict_calls_name_claims_of_the_notebooks_paper(path):
    paper = by_notebook(path.stem)
    found = static_verdicts(path)
    for claim, verdict in static_verdicts(path, real_data=True).items():
        assert claim in CLAIMS, f"{claim}: not in data/claims.csv"
        assert verdict in repro.VERDICTS, f"{claim}: unknown verdict {verdict!r}"
    if paper is None:
        assert not found, "a notebook without a paper records only real-data verdicts"
        return
    for claim, verdict in found.items():
        assert claim in CLAIMS, f"{claim}: not in data/claims.csv"
        assert CLAIMS[claim]["paper"] == paper.claims_id, f"{claim}: not a claim of paper {paper.claims_id}"
        assert verdict in repro.VERDICTS, f"{claim}: unknown verdict {verdict!r}"
        why = CLAIMS[claim]["kind"] in repro.NOT_CHECKABLE
        assert why == (verdict == "not checkable here"), (
            f"{claim} is of kind {CLAIMS[claim]['kind']!r} with verdict {verdict!r}: a claim not checkable here has a kind "
            f"saying why ({', '.join(repro.NOT_CHECKABLE)}), and a claim of such a kind is not checkable here"
        )


def test_verdict_calls_are_found():
    """The static reading above sees the notebooks' verdicts (it must not pass by finding none)."""
    assert sum(len(static_verdicts(p)) for p in NOTEBOOKS) >= 20


def test_one_vocabulary():
    assert ledger.VERDICTS == repro.VERDICTS
    assert ledger.NOT_CHECKABLE == repro.NOT_CHECKABLE
    doc = (ROOT / "docs/claims.md").read_text(encoding="utf-8")
    for v in (*repro.VERDICTS, ledger.NO_VERDICT):
        assert f"*{v}*" in doc, f"docs/claims.md does not explain the verdict {v!r}"
    for kind in repro.NOT_CHECKABLE:
        assert f"| `{kind}` |" in doc, f"docs/claims.md does not explain the kind {kind!r} (why a claim is not checkable)"


def test_catalogue_holds_no_second_copy_of_the_verdicts():
    """The notebook owns the verdict; data/claims.csv has no verdict column that could disagree."""
    assert "verdict" not in next(iter(CLAIMS.values()))


def _results(tmp_path, stem, verdicts, checks=()):
    (tmp_path / stem).mkdir(parents=True)
    data = {"notebook": stem, "checks": list(checks), "paper": by_notebook(stem).claims_id, "verdicts": verdicts}
    (tmp_path / stem / "results.json").write_text(json.dumps(data), encoding="utf-8")


def test_ledger_joins_results_with_the_catalogue(tmp_path):
    p = PAPERS[0]
    ids = [c for c, r in CLAIMS.items() if r["paper"] == p.claims_id and r["kind"] != "extension"]
    hw = next(c for c in ids if CLAIMS[c]["kind"] == "hardware-only")
    check = {"name": ids[0] + "/a", "value": 1.0, "passed": True}
    _results(
        tmp_path,
        p.notebook,
        [
            {
                "claim": ids[0],
                "verdict": "reproduced",
                "checks": [check["name"]],
                "evidence": [],
                "paper": None,
                "ours": "1 deg",
                "reason": "",
                "erratum": "",
                "figure": "fig",
            },
            {
                "claim": hw,
                "verdict": "not checkable here",
                "checks": [],
                "evidence": [],
                "paper": "4.77",
                "ours": None,
                "reason": "hardware",
                "erratum": "",
                "figure": "",
            },
            {
                "claim": "P999-NOT-A-CLAIM",
                "verdict": "reproduced",
                "checks": [],
                "evidence": [],
                "paper": None,
                "ours": None,
                "reason": "",
                "erratum": "",
                "figure": "",
            },
        ],
        [check],
    )
    leds = {led.stem: led for led in ledger.ledgers(tmp_path)}
    led = leds[p.notebook]
    assert [r.claim for r in led.rows] == ids  # every claim once, in catalogue order
    assert led.counts["reproduced"] == 1 and led.counts["not checkable here"] == 1
    assert led.counts[ledger.NO_VERDICT] == len(ids) - 2
    assert led.computed == 1  # only the verdict resting on a check
    hw_row = next(r for r in led.rows if r.claim == hw)
    assert led.rows[0].figure == f"{p.notebook}/figures/fig.png" and hw_row.paper == "4.77"
    assert ledger.verdict_text(hw_row) == "not checkable here (hardware only): hardware"  # the category, then the sentence
    assert led.problems and "P999-NOT-A-CLAIM" in led.problems[0]
    assert led.checks_passed == led.checks_total == 1
    other = leds[PAPERS[1].notebook]
    assert not other.ran and other.counts[ledger.NO_VERDICT] == len(other.rows)


def _verdict(claim, checks=(), figure=""):
    return {
        "claim": claim,
        "verdict": "reproduced",
        "checks": list(checks),
        "evidence": [],
        "paper": None,
        "ours": None,
        "reason": "",
        "erratum": "",
        "figure": figure,
    }


SPLIT = [p for p in PAPERS if p.parts]


@pytest.mark.skipif(not SPLIT, reason="no paper is taught in more than one notebook")
def test_a_paper_in_two_notebooks_has_one_ledger(tmp_path):
    p = SPLIT[0]
    first, second = p.notebooks[:2]
    ids = [c for c, r in CLAIMS.items() if r["paper"] == p.claims_id and r["kind"] != "extension"]
    _results(tmp_path, first, [_verdict(ids[0], [ids[0] + "/a"])], [{"name": ids[0] + "/a", "value": 1.0, "passed": True}])
    _results(
        tmp_path, second, [_verdict(ids[1], [ids[1] + "/b"], "fig")], [{"name": ids[1] + "/b", "value": 2.0, "passed": False}]
    )
    led = {led.stem: led for led in ledger.ledgers(tmp_path)}[first]
    assert led.stems == list(p.notebooks) and led.ran and not led.problems
    assert (led.checks_passed, led.checks_total) == (1, 2)  # both notebooks' checks
    assert [(r.claim, r.stem) for r in led.rows[:2]] == [(ids[0], first), (ids[1], second)]
    assert led.rows[1].figure == f"{second}/figures/fig.png"  # the figure of the notebook that recorded the verdict
    _results(tmp_path / "twice", first, [_verdict(ids[1])])
    _results(tmp_path / "twice", second, [_verdict(ids[1])])
    problems = {led.stem: led for led in ledger.ledgers(tmp_path / "twice")}[first].problems
    assert problems == [f"{ids[1]}: a verdict in {first} and another in {second}"]
    _results(tmp_path / "half", first, [_verdict(ids[0])])
    problems = {led.stem: led for led in ledger.ledgers(tmp_path / "half")}[first].problems
    assert problems == [f"{second} has not run: the claims it checks have no verdict"]


@pytest.mark.parametrize("p", PAPERS, ids=[p.name for p in PAPERS])
def test_each_claim_gets_its_verdict_in_one_notebook(p):
    found = [set(static_verdicts(ROOT / "notebooks" / f"{stem}.ipynb")) for stem in p.notebooks]
    twice = sorted(set.intersection(*found)) if len(found) > 1 else []
    assert not twice, f"claims given a verdict in more than one notebook of paper {p.claims_id}: {twice}"


def test_real_data_verdicts_join_their_claims_from_any_notebook(tmp_path):
    p, chapter = PAPERS[2], "07_real_references"
    ids = [c for c, r in CLAIMS.items() if r["paper"] == p.claims_id and r["kind"] != "extension"]
    entry = dict(checks=["x/real"], evidence=[], paper=None, ours="0.4 m", reason="", erratum="", figure="drive")
    _results(tmp_path, p.notebook, [{"claim": ids[0], "verdict": "direction only", **entry, "reason": "stand-in"}])
    (tmp_path / chapter).mkdir()
    verdicts = [
        {"claim": ids[0], "verdict": "reproduced", "real_data": True, **entry},
        {"claim": "P999-NOT-A-CLAIM", "verdict": "reproduced", "real_data": True, **entry},
    ]
    (tmp_path / chapter / "results.json").write_text(json.dumps({"notebook": chapter, "checks": [], "verdicts": verdicts}))
    leds = ledger.ledgers(tmp_path)
    row = next(led for led in leds if led.stem == p.notebook).rows[0]
    assert row.verdict == "direction only" and row.stem == p.notebook  # the simulation verdict stays
    assert row.real.verdict == "reproduced" and row.real.stem == chapter
    assert row.real.figure == f"{chapter}/figures/drive.png" and row.real.ours == "0.4 m"
    assert next(led for led in leds if led.stem == p.notebook).real_counts == {"reproduced": 1}
    assert any("P999-NOT-A-CLAIM" in m for led in leds for m in led.problems)


def test_chapters_have_no_claims():
    assert not set(CHAPTERS) & {p.notebook for p in PAPERS}


def test_site_pages_lead_with_verdicts_and_keep_checks_and_claims_apart(tmp_path):
    site = pytest.importorskip("build_site")  # tools/build_site.py (needs nbformat, sphinx)
    p = PAPERS[0]
    ids = [c for c, r in CLAIMS.items() if r["paper"] == p.claims_id]
    check = {
        "name": ids[0] + "/a",
        "value": 1.0,
        "expected": 1.0,
        "tol": 0.1,
        "passed": True,
        "source": "paper Eq. (3)",
        "paper_value": None,
        "lower": None,
        "upper": None,
        "unit": "",
        "note": "",
    }
    outside = dict(check, name=ids[1] + "/differs", expected=None, tol=None, lower=2.0, upper=3.0, outside=True)
    _results(
        tmp_path,
        p.notebook,
        [
            {
                "claim": ids[0],
                "verdict": "reproduced",
                "checks": [check["name"]],
                "evidence": [],
                "paper": None,
                "ours": "1",
                "reason": "",
                "erratum": "",
                "figure": "",
            },
            {
                "claim": ids[1],
                "verdict": "differs",
                "checks": [outside["name"]],
                "evidence": [outside["name"]],
                "paper": "2.5",
                "ours": "1",
                "reason": "hardware",
                "erratum": "",
                "figure": "",
            },
        ],
        [check, outside],
    )
    leds = [led for led in ledger.ledgers(tmp_path) if led.stem == p.notebook]
    home = site.home_page(leds, [p.notebook])
    assert home.index("no verdict yet") < home.index("## Two commands")  # the verdicts lead
    assert "claims passed" not in home and "2/2" in home  # checks passed, counted as checks
    assert "= target" not in home and "hardware" in home  # no invented paper values; the reason
    page = site.ledger_page(leds, tmp_path)
    assert page.count("<tr data-paper=") == 2 + sum(1 for r in leds[0].rows if not r.checks)
    assert "data-verdict='differs'" in page and "outside [2, 3]" in page


# Verdict words judge what a paper states (issue 35): the catalogue marks the project's own quantities, test
# vectors and reconstructions of what the paper does not print as kind "extension", and only they get the
# verdict "extension".
OWN_QUANTITY = (
    "the project's own",
    "not a paper claim",
    "the paper gives no number",
    "the paper gives no coordinates",
    "the paper does not show",
    "absent from the text",
    "prints none",
)


def test_the_projects_own_quantities_are_extensions():
    for cid, row in CLAIMS.items():
        text = f"{row['item']} {row['note']}".lower()
        marked = [m for m in OWN_QUANTITY if m in text]
        if marked and not row["paper_value"]:
            assert row["kind"] == "extension", f"{cid}: the catalogue calls it {marked[0]!r} but its kind is {row['kind']!r}"
        if row["kind"] == "extension":
            assert marked, f"{cid}: an extension says in its note whose quantity it is (e.g. {OWN_QUANTITY[0]!r})"


def test_a_paper_verdict_rests_on_a_paper_statement():
    """A paper verdict word needs a catalogue row that quotes the paper: a printed value, or an item naming where."""
    where = ("Eq", "Fig", "Table", "§", "text", "abstract", "conclusion")
    for cid, row in CLAIMS.items():
        if row["kind"] != "extension":
            assert row["paper_value"] or any(w in row["item"] for w in where), f"{cid}: no paper statement quoted"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_extensions_and_paper_claims_get_their_own_words(path):
    for claim, verdict in static_verdicts(path).items():
        extension = CLAIMS[claim]["kind"] == repro.EXTENSION
        assert extension == (verdict == repro.EXTENSION), (
            f"{claim}: kind {CLAIMS[claim]['kind']!r} with verdict {verdict!r}; the project's own quantities get "
            f"{repro.EXTENSION!r}, paper statements a verdict word"
        )


def test_the_ledger_lists_extensions_apart(tmp_path):
    stem, paper = "03_gauss_kruger_ekf", "002"
    ext = next(cid for cid, r in CLAIMS.items() if r["paper"] == paper and r["kind"] == "extension")
    _results(
        tmp_path,
        stem,
        [
            {
                "claim": ext,
                "verdict": "extension",
                "checks": ["x"],
                "evidence": [],
                "paper": None,
                "ours": "1",
                "reason": "own",
                "erratum": "",
                "figure": "",
            }
        ],
    )
    led = next(led for led in ledger.ledgers(tmp_path) if led.stem == stem)
    assert ext in [r.claim for r in led.extensions] and ext not in [r.claim for r in led.rows]
    assert not led.problems and "extension" not in led.counts


# Not checkable here, and why (issue 35): the catalogue kind of such a claim is one of a fixed vocabulary, and the
# notebook's verdict gives the sentence; the ledger refuses a "not checkable here" without a kind saying why.
def test_every_not_checkable_claim_says_why_in_the_ledger(tmp_path):
    stem, paper = "03_gauss_kruger_ekf", "002"
    own = [cid for cid, r in CLAIMS.items() if r["paper"] == paper]
    why = next(cid for cid in own if CLAIMS[cid]["kind"] == "not-a-result")
    computed = next(cid for cid in own if CLAIMS[cid]["kind"] == "analytic")
    row = {"checks": [], "evidence": [], "paper": "x", "ours": None, "erratum": "", "figure": ""}
    _results(
        tmp_path,
        stem,
        [
            dict(row, claim=why, verdict="not checkable here", reason="the paper's filter settings"),
            dict(row, claim=computed, verdict="not checkable here", reason="no reason of the vocabulary"),
        ],
    )
    led = next(led for led in ledger.ledgers(tmp_path) if led.stem == stem)
    rows = {r.claim: r for r in led.rows}
    assert ledger.verdict_text(rows[why]) == "not checkable here (not a result): the paper's filter settings"
    assert rows[computed].verdict == ledger.NO_VERDICT  # refused: its kind does not say why it is not checkable
    assert len(led.problems) == 1 and computed in led.problems[0]


def test_each_reason_of_the_vocabulary_is_used():
    assert set(repro.NOT_CHECKABLE) <= {r["kind"] for r in CLAIMS.values()}
