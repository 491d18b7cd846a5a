"""The repository stands on its own.

* No tracked file reads, names or links anything outside the repository: the sibling folder the
  project was once developed beside, the working notes on each paper, or the old design notes.
* The project's own catalogues (``data/claims.csv``, ``data/errata.csv``) are well formed and
  consistent with each other and with the errata ids the notebooks and modules cite.
* The published reference files in ``data/reference/`` carry their source and tolerance and match
  the checksums of ``data/reference/README.md``.
"""

from __future__ import annotations

import csv
import hashlib
import re
from pathlib import Path

import pytest
from helpers import project_files

from navlib import repro
from navlib.papers import PAPERS as REGISTRY

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data"

# Assembled from pieces so that this file does not match its own patterns.
OUTSIDE = re.compile(
    "|".join(
        [
            r"\.\./" + "sha" + "red",  # the sibling folder
            "sha" + r"red/(vectors|papers|reviews)",  # its sub-folders, however reached
            "DESIGN" + r"\.md|DESIGN" + " §",  # the old design notes
            r"\bgui" + r"des?\b",  # the per-paper working notes, cited as "<that word> Err 4"
            r"(?<!docs/)(?<!\]\()" + "claims" + r"\.md",  # the old catalogue's explanation (now docs/claims.md)
        ]
    ),
    re.IGNORECASE,
)
KINDS = {"analytic", "deterministic", "monte-carlo", "simulation-stand-in", "qualitative", "extension", *repro.NOT_CHECKABLE}
PAPERS = {p.claims_id for p in REGISTRY}
ERRATUM_ID = re.compile(r"\bE(?:" + "|".join(sorted(PAPERS)) + r")-\d\d\b")


def text_files() -> dict[Path, str]:
    out = {}
    for path in project_files():
        try:
            out[path] = path.read_text(encoding="utf-8")
        except (UnicodeDecodeError, FileNotFoundError):
            continue  # images; files deleted in the work tree
    return out


def read_csv(path: Path) -> list[dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


def test_no_file_refers_outside_the_repository():
    hits = [
        f"{p.relative_to(ROOT)}:{n}: {line.strip()[:120]}"
        for p, text in text_files().items()
        for n, line in enumerate(text.splitlines(), 1)
        if OUTSIDE.search(line)
    ]
    assert not hits, "references to files outside the repository:\n" + "\n".join(hits)


def test_the_pattern_catches_what_it_must():
    word = "gui" + "de"
    for line in (
        "see ../" + "sha" + "red/vec" + "tors/x.csv",
        f"({word} Err 4)",
        "DESIGN" + ".md §2",
        f"{word}-derived",
        "claims" + ".md rule",
    ):
        assert OUTSIDE.search(line), line
    assert not OUTSIDE.search("EPSG Guidance Note 7-2; gyrobias.design(); a shared stream; docs/claims.md")
    assert not OUTSIDE.search("[the catalogue format](claims.md)")


# ---------------------------------------------------------------- claims and errata

CLAIMS = read_csv(DATA / "claims.csv")
ERRATA = read_csv(DATA / "errata.csv")


def test_claims_catalogue_columns_and_values():
    assert list(CLAIMS[0]) == ["id", "paper", "item", "quantity", "paper_value", "kind", "erratum", "note"]
    ids = [c["id"] for c in CLAIMS]
    assert len(ids) == len(set(ids)), "duplicate claim ids"
    for c in CLAIMS:
        assert c["paper"] in PAPERS and c["id"].startswith(f"P{c['paper']}-"), c["id"]
        assert c["kind"] in KINDS, (c["id"], c["kind"])
        assert c["item"] and c["quantity"], c["id"]
    assert {c["paper"] for c in CLAIMS} == PAPERS


def test_claim_ids_are_prefix_free():
    """A check name starts with one claim id; no id may be the prefix of another."""
    ids = sorted(c["id"] for c in CLAIMS)
    clashes = [(a, b) for a, b in zip(ids, ids[1:], strict=False) if b.startswith(a)]
    assert not clashes


def test_errata_catalogue_columns_and_values():
    assert list(ERRATA[0]) == ["id", "paper", "item", "printed", "corrected", "numeric", "shown_by"]
    ids = [e["id"] for e in ERRATA]
    assert len(ids) == len(set(ids)), "duplicate erratum ids"
    for e in ERRATA:
        assert ERRATUM_ID.fullmatch(e["id"]) and e["id"][1:4] == e["paper"], e["id"]
        assert e["numeric"] in ("yes", "no"), e["id"]
        assert e["item"] and e["corrected"], e["id"]


def test_every_cited_erratum_exists():
    known = {e["id"] for e in ERRATA}
    cited = {m for c in CLAIMS for m in ERRATUM_ID.findall(c["erratum"])}
    for path, text in text_files().items():
        if path.suffix in (".py", ".ipynb", ".md", ".csv") and path.name != "errata.csv":
            cited |= set(ERRATUM_ID.findall(text))
    assert cited - known == set(), f"cited but not in data/errata.csv: {sorted(cited - known)}"


def test_erratum_boxes_in_notebooks_name_known_errata():
    known = {e["id"] for e in ERRATA}
    box = re.compile(r"\*\*Erratum (" + ERRATUM_ID.pattern.removeprefix(r"\b").removesuffix(r"\b") + r")\b")
    boxes = {m for p in (ROOT / "notebooks").glob("*.ipynb") for m in box.findall(p.read_text(encoding="utf-8"))}
    assert boxes, "no erratum boxes in the notebooks"
    assert boxes <= known


# ---------------------------------------------------------------- reference values

REFERENCE = DATA / "reference"
REFERENCE_FILES = sorted(REFERENCE.glob("*.csv"))


@pytest.mark.parametrize("path", REFERENCE_FILES, ids=lambda p: p.name)
def test_reference_file_has_source_tolerance_and_checksum(path):
    header = [line for line in path.read_text(encoding="utf-8").splitlines() if line.startswith("#")]
    assert any(h.startswith("# source:") for h in header), "no '# source:' line"
    assert any(h.startswith("# tolerance:") for h in header), "no '# tolerance:' line"
    readme = (REFERENCE / "README.md").read_text(encoding="utf-8")
    row = next((line for line in readme.splitlines() if f"`{path.name}`" in line), None)
    assert row, f"{path.name} is not listed in data/reference/README.md"
    assert hashlib.sha256(path.read_bytes()).hexdigest() in row, f"{path.name} differs from its recorded SHA-256"


def test_reference_files_present():
    assert {p.name for p in REFERENCE_FILES} == {
        "barometric_altitude.csv",
        "bmp180_datasheet_example.csv",
        "geodetic_constants.csv",
        "normal_gravity.csv",
        "tmerc_gauss_kruger.csv",
        "wmm_test_values.csv",
    }
