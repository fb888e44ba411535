"""``hotroll report DIR`` (issue 18, third part): one self-contained HTML page per run and per
study. The numbers on the page are read back with the standard library's HTML parser and
compared with the files the runs wrote (summary.json, compare.json, study.csv), through this
file's own table of display units; the pages are rendered in Debian's headless chromium
(playwright): they render, every figure loads, no console or page error, no request leaves
the file. A coarse Example 1 pass compared with slab theory (about 2 s) and a study of 2 x 3
cases, two of them refused by the schema (4 solves, about 3 s)."""
from __future__ import annotations

import csv
import html
import json
import math
import os
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from casebuild import EX1_COARSE_TOML, example1_coarse, shared_scope
from typer.testing import CliRunner

#: A shown unit -> its SI factor (written here, not taken from hotroll.results.report*).
TO_SI = {"N/m": 1.0, "kN/m": 1e3, "MN/m": 1e6, "N": 1.0, "kN": 1e3, "MN": 1e6,
         "N m/m": 1.0, "kN m/m": 1e3, "MN m/m": 1e6, "N m": 1.0, "kN m": 1e3,
         "W/m": 1.0, "kW/m": 1e3, "MW/m": 1e6, "W": 1.0, "kW": 1e3, "Pa": 1.0, "kPa": 1e3,
         "MPa": 1e6, "m": 1.0, "mm": 1e-3, "%": 1e-2, "°": math.pi / 180, "rad": 1.0,
         "s": 1.0, "1/s": 1.0, "m/s": 1.0, "–": 1.0}
BROWSER = os.environ.get("HOTROLL_CHROMIUM", "/usr/bin/chromium")   # Debian's chromium
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]

BASE = EX1_COARSE_TOML
STUDY = """name = "m_and_draft"
[base]
file = "base.toml"
[vary]
"material.m" = [0.15, 0.25]
"pass.exit_thickness" = [0.4, 0.45, 0.55]
"""


def _cli(*args: str):
    from hotroll.cli import app

    return CliRunner().invoke(app, list(args))


@pytest.fixture(scope=shared_scope)
def compared(tmp_path_factory):
    """A coarse Example 1 pass, 1.2 m wide, run by ``compare`` (FE in fe/, slab theory beside),
    then ``hotroll report`` on it."""
    from hotroll.config.case import case_from_dict
    from hotroll.workflows.compare import run_compare

    d = tmp_path_factory.mktemp("report") / "cmp"
    base = example1_coarse("ex1c", output={"figures": False, "vtk": False})
    base["pass"]["width"] = 1.2
    run_compare(case_from_dict(base), d)
    res = _cli("report", str(d))
    assert res.exit_code == 0, res.output
    assert str(d / "report.html") in res.output.replace("\n", "")
    return d


@pytest.fixture(scope=shared_scope)
def studied(tmp_path_factory):
    """``hotroll study --serial`` (it writes report.html at its end): exit 64 + 2 failed."""
    d = tmp_path_factory.mktemp("report_study")
    (d / "base.toml").write_text(BASE)
    (d / "study.toml").write_text(STUDY)
    res = _cli("study", str(d / "study.toml"), "--out", str(d / "out"), "--serial")
    assert res.exit_code == 64 + 2, res.output
    return d / "out"


class _Page(HTMLParser):
    """Table rows of a page: each <tr> as its attributes and (cell attributes, text) pairs."""

    def __init__(self, text: str):
        super().__init__()
        self.rows, self.imgs, self.links, self._row, self._cell = [], [], [], None, None
        self.scripts = 0
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "tr":
            self._row = (a, [])
            self.rows.append(self._row)
        elif tag in ("td", "th") and self._row is not None:
            self._cell = [a, ""]
            self._row[1].append(self._cell)
        elif tag == "img":
            self.imgs.append(a.get("src", ""))
        elif tag == "a":
            self.links.append(a.get("href", ""))
        elif tag in ("script", "iframe", "object"):
            self.scripts += 1
        elif tag == "link" and a.get("rel") != "icon":
            self.links.append(a.get("href", ""))

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[1] += data


def _page(path: Path) -> _Page:
    return _Page(path.read_text())


def _summary_row(page: _Page, key: str) -> tuple[float, str, str, str]:
    """(shown value, shown unit, SI text, data-si) of the summary table's row ``key``."""
    rows = [cells for a, cells in page.rows if a.get("data-key") == key]
    assert rows, f"no row {key} in the summary table"
    cells = rows[0]
    return (cells[1][1].strip(), cells[2][1].strip(), cells[3][1].strip(),
            cells[1][0].get("data-si"))


def _si(text: str, unit: str) -> list[float]:
    """Shown numbers in SI: ``number [, number]`` times the unit's factor (test's own table)."""
    return [float(x) * TO_SI[unit] for x in text.split(",")]


@pytest.mark.parametrize("key", ["roll_force", "roll_force_total", "roll_torque", "roll_power",
                                 "forward_slip", "neutral_angle_flux", "mean_pressure",
                                 "contact_length", "mean_strain_rate", "exit_velocity",
                                 "mass_flux_error", "wall_time_s"])
def test_run_page_numbers_are_the_summary_with_their_units(compared, key):
    """Every number of the summary table: the shown value in its shown unit equals
    summary.json's SI value to the shown 4 digits; the SI column to 6 digits."""
    s = json.loads((compared / "fe" / "summary.json").read_text())
    shown, unit, si_text, data = _summary_row(_page(compared / "report.html"), key)
    assert unit and unit in TO_SI, f"{key}: unit {unit!r}"
    assert _si(shown, unit)[0] == pytest.approx(s[key], rel=6e-4)
    number, si_unit = si_text.split(" ", 1)
    assert float(number) == pytest.approx(s[key], rel=6e-6)
    assert si_unit.strip().replace("–", "-") == s["units"].get(key, "-")
    assert float(data) == s[key]


def test_run_page_says_why_there_is_no_neutral_angle(compared):
    """Example 1 sticks (a_f from (3.15)): the page has no neutral-angle number but the
    summary's story and reason as a note, and the sticking zone in its unit."""
    s = json.loads((compared / "fe" / "summary.json").read_text())
    page = _page(compared / "report.html")
    assert s["neutral_angle"] is None
    assert not [c for a, c in page.rows if a.get("data-key") == "neutral_angle"]
    text = " ".join((compared / "report.html").read_text().split())
    assert (f"neutral point: {s['neutral']} ({s['neutral_angle_reason']})"
            in html.unescape(text))
    shown, unit, _, _ = _summary_row(page, "sticking_zone")
    assert _si(shown, unit) == pytest.approx(s["sticking_zone"], rel=6e-4)


def test_run_page_units_everywhere_and_self_contained(compared):
    """Every summary row and every input row with a number has a unit cell; the case's inputs
    are the case file's; the slab table's FE roll force is compare.json's; no script, no
    external file; the figures are data URIs (the flow stress drawn for the page: the run wrote
    no figures, and compare.png)."""
    page = _page(compared / "report.html")
    summary = [cells for a, cells in page.rows if a.get("data-key")]
    assert len(summary) > 30
    assert all(cells[2][1].strip() for cells in summary)
    inputs = {cells[0][1]: cells for _, cells in page.rows
              if len(cells) == 4 and cells[0][0].get("class") == "key"}
    assert inputs["roll_radius"][1][1] == "0.6" and inputs["roll_radius"][2][1] == "m"
    assert inputs["width"][1][1] == "1.2"
    assert inputs["roll_angular_velocity"][2][1] == "rad/s"
    cmp = json.loads((compared / "compare.json").read_text())
    row = next(r for r in cmp["rows"] if r["unit"] == "N/m")
    slab = [cells for _, cells in page.rows if cells and cells[0][1] == "roll force per unit width"
            and cells[1][1] == "N/m"][0]
    assert float(slab[2][1]) == pytest.approx(row["FE"], rel=6e-4)
    assert float(slab[3][1]) == pytest.approx(row["slab (Orowan)"], rel=6e-4)
    assert page.scripts == 0
    assert all(src.startswith("data:image/png;base64,") for src in page.imgs)
    assert len(page.imgs) == 2
    assert not [h for h in page.links if re.match(r"^[a-z]+://", h)]


def test_study_page_is_the_table(studied):
    """Each row: the roll force in the column's unit is study.csv's; failed rows marked with
    their reason; done cases link to their own report, which exists."""
    with open(studied / "study.csv") as fh:
        rows = list(csv.DictReader(fh))
    page = _page(studied / "report.html")
    head = [cells for a, cells in page.rows if cells and cells[0][1] == "case"][0]
    keys = [c[0].get("data-key") for c in head]
    unit = re.search(r"\[(.*)\]", head[keys.index("roll_force")][1]).group(1)
    body = {a["data-case"]: (a, cells) for a, cells in page.rows if "data-case" in a}
    assert len(body) == len(rows) == 6
    for r in rows:
        a, cells = body[r["case"]]
        force = [c for c in cells if c[0].get("data-key") == "roll_force"][0]
        link = studied / "cases" / r["case"] / "report.html"
        if r["status"] == "done":
            assert float(force[1]) * TO_SI[unit] == pytest.approx(float(r["roll_force"]),
                                                                  rel=6e-4)
            assert float(force[0]["data-si"]) == float(r["roll_force"])
            assert "failed" not in a.get("class", "") and link.is_file()
            assert any(h.startswith("cases/") and "report.html" in h for h in page.links)
        else:
            assert r["status"] == "bad_input" and "failed" in a["class"]
            assert force[1] == "-" and not link.exists()
    assert "pass.exit_thickness: must be smaller" in (studied / "report.html").read_text()
    assert page.scripts == 0 and len(page.imgs) == 1


def test_bad_directories_are_refused(tmp_path):
    """A missing directory and one that no command wrote: exit code 2, the path and what is
    expected named, nothing written."""
    res = _cli("report", str(tmp_path / "nothing"))
    assert res.exit_code == 2
    assert "nothing" in res.output and "summary.json" in res.output
    (tmp_path / "notes.txt").write_text("x")
    res = _cli("report", str(tmp_path))
    assert res.exit_code == 2 and "not a hotroll output directory" in res.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]


# ------------------------------------------------------------------------- in the browser
@pytest.fixture(scope=shared_scope)
def browser():
    """Debian's chromium driven by playwright (never ``playwright install``)."""
    if os.environ.get("HOTROLL_SKIP_BROWSER") == "1":
        pytest.skip("HOTROLL_SKIP_BROWSER=1")
    if not Path(BROWSER).is_file():
        pytest.fail(f"{BROWSER} not found: install Debian's chromium (apt-get install chromium "
                    f"chromium-driver), name another with HOTROLL_CHROMIUM, or set "
                    f"HOTROLL_SKIP_BROWSER=1", pytrace=False)
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.fail("the python package playwright is missing: pip install -e '.[test]'",
                    pytrace=False)
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=BROWSER, args=ARGS)
        yield b
        b.close()


def _open(browser, path: Path):
    """The page loaded from its file; its console errors, page errors and outside requests."""
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    seen = {"errors": [], "outside": []}
    page.on("console", lambda m: m.type == "error" and seen["errors"].append(m.text))
    page.on("pageerror", lambda e: seen["errors"].append(str(e)))
    page.on("requestfailed", lambda r: seen["errors"].append(f"failed: {r.url}"))

    def route(r):
        if r.request.url.startswith(("file://", "data:")):
            r.continue_()
        else:
            seen["outside"].append(r.request.url)
            r.abort()

    page.route("**/*", route)
    page.goto(path.resolve().as_uri(), wait_until="load")
    return page, seen


def _check_loaded(page, seen, n_images: int, shot: Path) -> None:
    imgs = page.eval_on_selector_all(
        "img", "els => els.map(e => [e.complete, e.naturalWidth, e.naturalHeight])")
    assert len(imgs) == n_images
    assert all(c and w > 0 and h > 0 for c, w, h in imgs), imgs
    assert seen["errors"] == [] and seen["outside"] == []
    shot.parent.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(shot), full_page=True)


def _shots(tmp_path) -> Path:
    return Path(os.environ.get("HOTROLL_REPORT_SHOTS") or tmp_path)


def test_run_page_in_the_browser(browser, compared, tmp_path):
    """Rendered: the title, the roll force row with its unit and summary.json's value, the
    figures loaded, the warnings box, nothing outside the file."""
    s = json.loads((compared / "fe" / "summary.json").read_text())
    page, seen = _open(browser, compared / "report.html")
    assert "ex1c" in page.title()
    row = page.locator("tr[data-key=roll_force]")
    value = row.locator("td").nth(1).inner_text().strip()
    unit = row.locator("td").nth(2).inner_text().strip()
    assert float(value) * TO_SI[unit] == pytest.approx(s["roll_force"], rel=6e-4)
    assert page.locator("#warnings li").count() >= 1
    assert page.locator("#slab-table tbody tr").count() >= 5
    _check_loaded(page, seen, 2, _shots(tmp_path) / "report_run.png")
    page.close()


def test_study_page_in_the_browser(browser, studied, tmp_path):
    """Rendered: the table's rows, failed ones highlighted, the figure loaded; a case's link
    opens its own report, which renders without errors."""
    page, seen = _open(browser, studied / "report.html")
    assert page.locator("#study-table tbody tr[data-case]").count() == 6
    failed = page.locator("#study-table tbody tr.failed[data-case]")
    assert failed.count() == 2
    colour = failed.first.locator("td").first.evaluate("e => getComputedStyle(e).backgroundColor")
    assert colour not in ("rgba(0, 0, 0, 0)", "rgb(255, 255, 255)")
    _check_loaded(page, seen, 1, _shots(tmp_path) / "report_study.png")
    page.locator("#study-table a").first.click()
    page.wait_for_load_state("load")
    assert page.url.endswith("/report.html") and "/cases/" in page.url
    assert page.locator("tr[data-key=roll_force]").count() == 1
    assert seen["errors"] == [] and seen["outside"] == []
    page.close()
