"""Every chapter in one frame (issue 39): it opens with the question, what you will learn, prerequisites and time,
numbers its sections by one rule, closes with the same sections in the same order, and has exercises marked by
difficulty, among them coding exercises whose collapsed solutions are checked.

The rule for headings (a failure names the cell and says what to write instead):

* cell 0 opens with the title ``# NN — Title`` (NN the chapter's number, as in its file name); no other ``#``
  heading and no ``####``;
* optionally ``## The method in brief`` (unnumbered, before section 1);
* the body: ``## 1 Title``, ``## 2 Title``, ... numbered without gaps; subsections ``### N.1 Title``, ``### N.2 Title``,
  ... inside section N only;
* then the closing sections, unnumbered, in this order: ``## Explore: <what>`` (a chapter with an explorer),
  ``## Key points``, ``## Exercises``, ``## Discussion`` (or ``## Discussion: <what>``).

Exercises live in ``## Exercises``, each a paragraph opening ``**K. Title** (★)``, K = 1, 2, ... and one to three
stars (the legend is on the course page, docs/course.md); a coding exercise's title starts with ``Code it:``.
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

from navlib.papers import CHAPTERS, PAPERS

ROOT = Path(__file__).resolve().parents[1]
STEMS = sorted({*CHAPTERS, *(stem for p in PAPERS for stem in p.notebooks)})
PATHS = [ROOT / "notebooks" / f"{stem}.ipynb" for stem in STEMS]
chapters = pytest.mark.parametrize("path", PATHS, ids=STEMS)

OPENING = "The method in brief"
CLOSING = ("Explore: ", "Key points", "Exercises", "Discussion")
NUMBERED = re.compile(r"(\d+) (\S.*)")
SUBSECTION = re.compile(r"(\d+)\.(\d+) (\S.*)")
EXERCISE = re.compile(r"\*\*(\d+)\. ([^*]+)\*\* \((★{1,3})[,)]")
CODE_IT_MIN = 2


def markdown(path: Path) -> list[tuple[int, str]]:
    return [(i, c.source) for i, c in enumerate(nbformat.read(path, as_version=4).cells) if c.cell_type == "markdown"]


def headings(path: Path) -> list[tuple[int, int, str]]:
    """(cell, level, text) of every markdown heading, in order."""
    found = []
    for i, text in markdown(path):
        for line in text.splitlines():
            if m := re.match(r"(#+) (.*)", line):
                found.append((i, len(m.group(1)), m.group(2).strip()))
    return found


def closing_kind(title: str) -> str | None:
    """The closing section a heading is (``Explore: ``, ``Key points``, ...), or None."""
    if title.startswith("Explore: "):
        return "Explore: "
    if title == "Discussion" or title.startswith("Discussion: "):
        return "Discussion"
    return title if title in CLOSING else None


def numbering_problems(path: Path) -> list[str]:
    """What breaks the heading rule of the module docstring, one line per heading."""
    problems, section, sub, closing = [], 0, 0, []
    heads = headings(path)
    if not heads or heads[0][:2] != (0, 1) or not re.fullmatch(rf"{path.stem[:2]}[a-z]? — \S.*", heads[0][2]):
        problems.append(f"cell 0 must open with the title '# {path.stem[:2]} — <title>'")
    for cell, level, title in heads[1:]:
        where = f"cell {cell}: '{'#' * level} {title}'"
        m = NUMBERED.fullmatch(title)
        if level == 2 and m and closing_kind(m.group(2)):
            problems.append(f"{where}: write '## {m.group(2)}' (the closing sections are unnumbered)")
            title = m.group(2)
        if level == 1 or level > 3:
            problems.append(f"{where}: only the title is a '#' heading and there are no '####' headings; use '##' or '###'")
        elif level == 2 and (kind := closing_kind(title)):
            if kind in closing or any(CLOSING.index(k) > CLOSING.index(kind) for k in closing):
                problems.append(f"{where}: the closing sections come once each in the order {' / '.join(CLOSING)}")
            closing.append(kind)
        elif level == 2 and closing:
            problems.append(f"{where}: comes after '## {closing[-1]}'; move it before the closing sections, numbered")
        elif level == 2 and title == OPENING:
            if section:
                problems.append(f"{where}: '## {OPENING}' comes before section 1")
        elif level == 2:
            m = NUMBERED.fullmatch(title)
            text = m.group(2) if m else title
            if not m or int(m.group(1)) != section + 1:
                problems.append(f"{where}: write '## {section + 1} {text}' (sections are numbered 1, 2, ... without gaps)")
            section, sub = section + 1, 0
        else:
            m = SUBSECTION.fullmatch(title)
            text = m.group(3) if m else title
            if closing or not section:
                problems.append(f"{where}: subsections belong to a numbered section; make it a paragraph or a section")
            elif not m or (int(m.group(1)), int(m.group(2))) != (section, sub + 1):
                problems.append(f"{where}: write '### {section}.{sub + 1} {text}' (subsection {sub + 1} of section {section})")
            sub += 1
    missing = [k for k in CLOSING[1:] if k not in closing]
    if missing:
        problems.append(f"no closing section{'s' * (len(missing) > 1)} {', '.join(f'## {k}' for k in missing)} at the end")
    return problems


@chapters
def test_chapter_frame(path):
    text = [t for _, t in markdown(path)]
    opening = text[1]
    for part in ("**The question.**", "**What you will learn**", "**Prerequisites.**", "**Time.**"):
        assert part in opening, f"the cell after the title has no {part}"


@chapters
def test_section_numbering(path):
    problems = numbering_problems(path)
    assert not problems, "headings that break the rule of tests/test_chapter_frame.py:\n" + "\n".join(problems)


@chapters
def test_an_explorer_has_its_section(path):
    uses = any("repro.explorer(" in c.source for c in nbformat.read(path, as_version=4).cells if c.cell_type == "code")
    has = any(level == 2 and title.startswith("Explore: ") for _, level, title in headings(path))
    assert uses == has, "a chapter calling repro.explorer has one '## Explore: <what>' section, and only such a chapter"


def exercises(path: Path) -> tuple[list[tuple[int, str, str]], list[str]]:
    """The exercises of '## Exercises' as (number, title, stars), and what breaks the exercise rule."""
    found, problems, inside = [], [], False
    for cell, text in markdown(path):
        for line in text.splitlines():
            if line.startswith("## "):
                inside = line == "## Exercises"
            elif line.startswith("**") and (line[2:3].isdigit() or line.startswith("**Code it")):
                m = EXERCISE.match(line)
                if not inside:
                    problems.append(f"cell {cell}: an exercise outside '## Exercises': {line[:60]}")
                elif not m:
                    problems.append(f"cell {cell}: write '**{len(found) + 1}. <title>** (★) ...' (★ to ★★★): {line[:60]}")
                else:
                    found.append((int(m.group(1)), m.group(2), m.group(3)))
    numbers = [n for n, _, _ in found]
    if numbers != list(range(1, len(found) + 1)):
        problems.append(f"exercises numbered {numbers}: number them 1 to {len(found)} in order")
    return found, problems


@chapters
def test_exercises_are_numbered_and_marked(path):
    found, problems = exercises(path)
    assert found and not problems, "\n".join(problems or ["no exercises in '## Exercises'"])


@chapters
def test_coding_exercises_with_checked_solutions(path):
    cells = nbformat.read(path, as_version=4).cells
    coding = [title for _, title, _ in exercises(path)[0] if title.startswith("Code it:")]
    stubs = [c for c in cells if c.cell_type == "code" and "return None   # your code here" in c.source]
    solutions = [c for c in cells if "solution" in c.metadata.get("tags", [])]
    assert len(coding) >= CODE_IT_MIN, f"{len(coding)} coding exercises ('**K. Code it: ...**'); at least {CODE_IT_MIN}"
    assert len(stubs) == len(solutions) == len(coding), (
        f"{len(coding)} coding exercises, {len(stubs)} stubs returning None, {len(solutions)} cells tagged 'solution': "
        "one of each per exercise"
    )
    assert all("assert repro.exercise(" in c.source and ").passed" in c.source for c in solutions), "a solution is not checked"
    assert all(c.metadata.get("jupyter", {}).get("source_hidden") for c in solutions), "a solution is not collapsed"


def test_every_notebook_is_a_chapter():
    on_disk = sorted(p.stem for p in (ROOT / "notebooks").glob("*.ipynb"))
    assert on_disk == STEMS, "notebooks/ and the registry (navlib/papers/__init__.py) list different chapters"


def test_the_course_page_explains_the_stars():
    course = (ROOT / "docs" / "course.md").read_text(encoding="utf-8")
    for stars in ("★", "★★", "★★★"):
        assert f"| {stars} |" in course, f"docs/course.md has no legend row for {stars}"
