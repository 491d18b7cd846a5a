"""The README: its "Your own data" example runs as written, on the committed sample in the app's layout; its
results section (claims by verdict, per-paper matrices, quoted numbers) agrees with the notebooks and results."""

import re
import sys
import warnings
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from test_ledger import NOTEBOOKS, static_verdicts

from navlib.papers import PAPERS

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import readme  # noqa: E402  (tools/readme.py)


def _your_own_data() -> tuple[str, str]:
    """The README's "Your own data" example block, and its generic-CSV reader line."""
    section = (ROOT / "README.md").read_text(encoding="utf-8").split("## Your own data", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    return blocks[0], blocks[1].strip()


SAMPLE = 'io.read_sensor_logger("data/samples/sensor-logger")'


@pytest.mark.parametrize("sample", ["sensor-logger", "sensor-logger-ios", "sensor-logger-ios-nomag", "board.csv"])
def test_your_own_data_snippet_runs_as_written(monkeypatch, sample):
    """The block as written on each committed sample (Android and iOS with magnetometer, iOS without one,
    a generic board CSV with its reader line from the README). Each simulated phone turns by 90 deg
    clockwise (tools/make_sample_log.py): the heading plotted must turn by that much, and where the export
    carries the phone's own attitude (Orientation.csv) the filter's tilt must agree with it."""
    code, board_line = _your_own_data()
    assert len(code.strip().splitlines()) <= 12  # "a few lines" (import lines included)
    assert SAMPLE in code
    if sample == "board.csv":
        code = re.sub(r"rec = io\.read_sensor_logger\(.*?\)", lambda _: board_line.split("  #")[0], code, count=1)
    else:
        code = code.replace(SAMPLE, f'io.read_sensor_logger("data/samples/{sample}")')
    monkeypatch.chdir(ROOT)
    scope = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no axis looks flipped in a correct recording
        exec(compile(code, "README.md", "exec"), scope)  # noqa: S102 - the README's own example
    rec, res, attitude = scope["rec"], scope["res"], scope["attitude"]
    hpr = attitude.quat_to_euler(res.q_bn)
    heading = np.rad2deg(np.unwrap(hpr[:, 0]))
    # The MPU-6050-class accelerometer bias (0.16 m/s^2) tilts the levelled start by up to 1.9 deg, which enters
    # a magnetic heading through the dip (tan(dip) = 2.3 at 51.5 deg N), differently at each heading; without a
    # magnetometer the heading is the bias-corrected gyro's alone.
    assert abs(heading[-1] - heading[0] - 90.0) < 10.0
    assert any(c.startswith("gyro bias at rest removed") for c in rec.conversions)
    if rec.q_bn_ref is not None:  # the phone's own attitude, in navlib's frame
        ref = attitude.quat_to_euler(rec.q_bn_ref)
        tilt = np.rad2deg(np.abs(attitude.wrap_pi(hpr[:, 1:] - ref[:, 1:])))
        assert np.max(tilt) < 3.0


# ---------------------------------------------------------------- the results section (tools/readme.py)

README_TEXT = (ROOT / "README.md").read_text(encoding="utf-8")


def matrix_verdicts(text: str) -> dict[str, str]:
    """claim id -> verdict as the README's per-paper matrices show it."""
    out = {}
    for block in readme.LEDGER.finditer(text):
        for row in block.group(0).splitlines():
            cells = [c.strip() for c in row.strip("|").split(" | ")]
            if len(cells) == 6 and cells[0].startswith("`P"):
                out[cells[0].strip("`")] = cells[4]
    return out


def test_every_paper_has_a_matrix():
    parts = readme.readme_parts(README_TEXT)
    for p in PAPERS:
        assert f"<!-- ledger:{p.notebook} -->" in parts.get(p.notebook, ""), f"no claim matrix for {p.notebook}"


def test_matrix_verdicts_agree_with_the_notebooks():
    """A verdict changed in a notebook and not regenerated into the README fails here, without running anything."""
    shown = matrix_verdicts(README_TEXT)
    assert len(shown) > 100
    for path in NOTEBOOKS:
        for claim, verdict in static_verdicts(path).items():
            assert shown.get(claim, "").split(":")[0].split(" (")[0] == verdict, (  # (erratum) or (why not checkable)
                f"{claim}: README shows {shown.get(claim)!r}, {path.stem} records {verdict!r}: run `make readme`"
            )


def test_claims_without_verdict_are_not_counted_as_reproduced():
    shown = matrix_verdicts(README_TEXT)
    written = {c for p in NOTEBOOKS for c in static_verdicts(p)}
    for claim, verdict in shown.items():
        if verdict == "no verdict yet":
            assert claim not in written, claim


def test_readme_figures_exist():
    for name in re.findall(r'(?:src="|\]\()docs/figures/([^")]+)', README_TEXT):
        assert (ROOT / "docs" / "figures" / name).is_file(), name


def test_quoted_values_are_well_formed():
    quoted = readme.quoted_values(README_TEXT)
    assert len(quoted) >= 5, "the README quotes its numbers from results"
    stems = {p.stem for p in NOTEBOOKS}
    for m in readme.VALUE.finditer(README_TEXT):
        stem, name, spec, text = m.groups()
        assert stem in stems, stem
        scale, _, fmt = spec.rpartition(":")
        assert not scale or re.fullmatch(r"x\d+(\.\d+)?", scale), spec
        format(1.0, fmt)  # a valid format spec


def test_readme_matches_fresh_results():
    """After the notebooks ran (and wrote results newer than README.md), the README must be regenerated."""
    build = ROOT / "build"
    stems = [p.notebook for p in PAPERS] + list(readme.CHAPTERS)
    paths = [build / s / "results.json" for s in stems]
    if not all(p.is_file() for p in paths):
        pytest.skip("build/ holds no results of every notebook: run `make reproduce`")
    if min(p.stat().st_mtime for p in paths) < (ROOT / "README.md").stat().st_mtime:
        pytest.skip("some results are older than README.md")
    assert not readme.stale(README_TEXT, build), "README is stale: run `make readme` and commit"


def test_stale_readme_is_detected(tmp_path):
    """readme.stale notices a changed verdict and a changed quoted value."""
    build = ROOT / "build"
    if not all((build / p.notebook / "results.json").is_file() for p in PAPERS):
        pytest.skip("needs the results of every paper notebook in build/")
    fresh = README_TEXT
    if readme.stale(fresh, build):
        pytest.skip("README is not generated from this build/")
    edited = fresh.replace("| reproduced |", "| differs |", 1)
    assert readme.stale(edited, build)
    m = next(readme.VALUE.finditer(fresh))
    assert readme.stale(fresh.replace(m.group(0), m.group(0).replace(f"-->{m.group(4)}<!--", "-->9999<!--")), build)
