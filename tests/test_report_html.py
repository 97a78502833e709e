"""report.html opened as a reader would: in headless Chromium (Debian's package), from
a file, with no server. The page must load without errors and without a single
network request, its 3D view must show the shaft (not a blank canvas), and stepping to
another mode must change the view. The screenshots are kept in out/test-report-html/
to be looked at."""

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from shaftfem.cli import main

REPO = Path(__file__).resolve().parents[1]
SHOTS = REPO / "out" / "test-report-html"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed "
                                "(scripts/setup.sh test installs it)")

# Instrumentation put first into the test's copy of the page: Chromium logs every
# console message at one level, so errors, warnings and exceptions are marked.
WATCH = """<script>
(function () {
  for (const level of ["error", "warn"]) {
    const real = console[level].bind(console);
    console[level] = function () {
      console.log("PAGE-" + level.toUpperCase() + ":", ...arguments);
      real(...arguments);
    };
  }
  window.addEventListener("error", (e) => console.log("PAGE-ERROR: " + e.message));
  window.addEventListener("unhandledrejection", (e) => console.log("PAGE-ERROR: " + e.reason));
})();
</script>"""


def _chromium(profile: Path, url: str, *flags: str) -> subprocess.CompletedProcess:
    """Headless Chromium on `url`, WebGL in software (SwiftShader), nothing of its own
    on the network, 10 s of the page's time to load and draw."""
    return subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
         "--enable-unsafe-swiftshader", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--disable-quic",
         f"--user-data-dir={profile}", "--window-size=1200,900",
         "--virtual-time-budget=10000", *flags, url],
        capture_output=True, text=True, timeout=120)


def _page_requests(netlog: Path) -> list[str]:
    """URLs the page asked for that are not inside it (file:, data:, blob:), from
    Chromium's NetLog: the requests whose network isolation key is the file's."""
    text = netlog.read_text()
    if not text.rstrip().endswith("}"):   # a log cut off at exit lacks its closing
        text = text.rstrip().rstrip(",") + "]}"
    log = json.loads(text)
    start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    urls = []
    for e in log["events"]:
        p = e.get("params", {})
        if e["type"] == start and "file://" in p.get("network_isolation_key", ""):
            urls.append(p["url"])
    return [u for u in urls if not u.startswith(("file:", "data:", "blob:"))]


def _coloured(img: np.ndarray) -> np.ndarray:
    """Pixels of a saturated colour: the shaft's viridis colours and its glyphs (the
    page's text, tables and pale boxes are grey or nearly white)."""
    rgb = img[..., :3].astype(float)
    top, low = rgb.max(axis=2), rgb.min(axis=2)
    return (top - low) > 0.35 * np.maximum(top, 1)


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    """design on a stepped shaft in two bearings with a sprocket, coarse and quick."""
    out = tmp_path_factory.mktemp("design")
    assert main(["design", str(REPO / "examples" / "stepped_shaft.toml"), "--out", str(out),
                 "--mesh-size", "12", "--modes", "4", "--no-estimate", "-q"]) == 0
    page = out / "report.html"
    text = page.read_text()
    assert text.count("<head>") == 1
    page.write_text(text.replace("<head>", "<head>" + WATCH, 1))
    return page


def test_report_html_loads_offline_without_errors_and_its_3d_view_steps(report, tmp_path):
    from PIL import Image

    SHOTS.mkdir(parents=True, exist_ok=True)
    netlog = tmp_path / "net.json"
    first = _chromium(tmp_path / "a", report.as_uri() + "#mode=1", "--enable-logging=stderr",
                      "--v=0", f"--log-net-log={netlog}", f"--screenshot={SHOTS / 'mode1.png'}")
    assert (SHOTS / "mode1.png").exists(), first.stderr[-2000:]
    console = [line for line in first.stderr.splitlines() if ":CONSOLE" in line]
    errors = [line for line in console if "PAGE-ERROR" in line or "PAGE-WARN" in line
              or "Uncaught" in line]
    assert not errors, errors
    assert _page_requests(netlog) == []

    _chromium(tmp_path / "b", report.as_uri() + "#mode=3", f"--screenshot={SHOTS / 'mode3.png'}")
    dom = _chromium(tmp_path / "c", report.as_uri() + "#mode=3", "--dump-dom").stdout
    assert 'data-ready="true"' in dom and 'data-mode="3"' in dom   # the view's script ran

    one = np.asarray(Image.open(SHOTS / "mode1.png").convert("RGB"))
    three = np.asarray(Image.open(SHOTS / "mode3.png").convert("RGB"))
    a, b = _coloured(one), _coloured(three)
    for shown in (a, b):
        assert shown.mean() > 0.01   # the shaft drawn, not a blank canvas
        cols = np.flatnonzero(shown.any(axis=0))
        assert cols[-1] - cols[0] > 0.4 * shown.shape[1]   # and filling the view's width
        assert one[shown].std() > 20   # shaded and coloured, not one flat colour
    assert (a ^ b).sum() > 0.2 * (a | b).sum()   # mode 3 is not mode 1


# Marks, once the page has loaded, how many of the rotordynamic section's pictures the
# browser decoded (a picture that failed has no natural width).
PICTURES = """<script>
window.addEventListener("load", () => {
  const imgs = [...document.querySelectorAll("#rotordynamics img")];
  document.body.dataset.rotorPictures = imgs.length;
  document.body.dataset.rotorDecoded = imgs.filter((i) => i.naturalWidth > 100).length;
});
</script>"""


@pytest.fixture(scope="module")
def pump_report(tmp_path_factory) -> Path:
    """design on the pump on journals (a wear ring, a coupled motor), coarse and quick;
    with its work beside the run (the map, the pictures, the films) as a user's run has
    it (tests/conftest.py turns that off in the suite's workers)."""
    out = tmp_path_factory.mktemp("pump")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("SHAFTFEM_ASIDE", "1")
        assert main(["design", str(REPO / "examples" / "pump_on_journals.toml"), "--out",
                     str(out), "--mesh-size", "30", "--modes", "4", "--no-estimate",
                     "-q"]) == 0
    page = out / "report.html"
    text = page.read_text()
    page.write_text(text.replace("<head>", "<head>" + WATCH, 1).replace(
        "</body>", PICTURES + "</body>", 1))
    return page


def test_the_rotordynamics_section_reads_as_api_684_asks(pump_report, tmp_path):
    """The pump's report.html in Chromium: no error, the API 684 summary with each item
    judged, and the Campbell diagram, the critical speed map, the critical speeds'
    shapes, the unbalance response, Level I and the run-up the scene asks for drawn in
    the section (decoded by the browser); report.md has the same section. A screenshot
    is kept to look at."""
    import re

    SHOTS.mkdir(parents=True, exist_ok=True)
    run = _chromium(tmp_path / "r", pump_report.as_uri(), "--enable-logging=stderr", "--v=0")
    console = [line for line in run.stderr.splitlines() if ":CONSOLE" in line]
    assert not [line for line in console if "PAGE-ERROR" in line or "Uncaught" in line]
    dom = _chromium(tmp_path / "d", pump_report.as_uri(), "--dump-dom").stdout
    # the section on its own page with the report's style, to look at
    text = pump_report.read_text()
    start = text.index('<section id="rotordynamics">')
    alone = tmp_path / "section.html"
    alone.write_text("<html><head>" + re.findall(r"<style>.*?</style>", text, re.S)[-1]
                     + "</head><body>" + text[start:text.index("</section>", start) + 10]
                     + "</body></html>")
    _chromium(tmp_path / "s", alone.as_uri(), "--window-size=1100,3000",
              f"--screenshot={SHOTS / 'rotordynamics.png'}")
    assert (SHOTS / "rotordynamics.png").stat().st_size > 50_000
    # the nominal case's seven, and each other case's Campbell diagram, critical speeds'
    # shapes and unbalance response
    assert 'data-rotor-pictures="13"' in dom and 'data-rotor-decoded="13"' in dom
    section = dom[dom.index('<section id="rotordynamics">'):]
    section = section[:section.index("</section>")]
    for heading in ("Summary against API 684", "Campbell diagram", "Critical speed map",
                    "Deflected shapes at the critical speeds", "Unbalance response",
                    "Level I screening", "Run-up", "The study's cases",
                    "Bearing and seal coefficients against speed"):
        assert (f"<h3>{heading}</h3>" in section
                or f"<h3>{heading} (nominal case)</h3>" in section), heading
    for item in ("separation margin of the critical speeds", "least log decrement",
                 "zones of growth (instability)", "unbalance peak at impeller",
                 "nominal (the scene as given)", "the verdict (the worst case decides)",
                 "largest unbalance response (any probe, any speed)",
                 "unbalance response where the shaft runs (any probe)",
                 "Level I screening (API 617 8th ed.)"):
        assert item in section, item
    assert section.count('<td class="text">pass</td>') + section.count(
        '<td class="text">FAIL</td>') >= 4
    markdown = (pump_report.parent / "report.md").read_text()
    assert "## Rotordynamics (API 684)" in markdown and "![Critical speed map](ucs.png)" in markdown
    # an image link only to a picture; the diagram's numbers (campbell.csv) a plain link
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", markdown)
    assert images and all(i.endswith((".png", ".gif", ".jpg", ".svg")) for i in images), images
    assert re.search(r"(?<!!)\[[^\]]*\]\(campbell\.csv\)", markdown)


def test_each_case_is_pictured_and_tabled_as_itself(pump_report):
    """Every case of the pump's study under its own heading, in report.md and report.html:
    its Campbell diagram, critical speeds' shapes and unbalance response (its own files,
    not the nominal case's), and its whirl and critical speeds. Each is its own physics:
    a tighter, colder film is stiffer (the forward 1x critical rises from the loose, hot
    case through the nominal to the tight, cold one) and carries the journal sooner (its
    lift-off speed falls, the Sommerfeld number growing with viscosity over clearance
    squared)."""
    import re

    folder = pump_report.parent
    markdown = (folder / "report.md").read_text()
    page = pump_report.read_text()
    forward, lift = {}, {}
    for case, tail in (("min clearance, cold oil", "_min-clearance-cold-oil"),
                       ("max clearance, hot oil", "_max-clearance-hot-oil"),
                       ("nominal", "")):
        heading = (f"### Case: {case}" if tail else
                   "### Whirl, critical speeds and stability (nominal case)")
        part = markdown[markdown.index(heading):]
        part = part[:part.index("```", part.index("```text") + 7)]
        if tail:
            assert f"<h3>Case: {case}</h3>" in page
            for stem in ("campbell", "critical_shapes", "bode"):
                assert f"]({stem}{tail}.png)" in part, (case, stem)
                ours, nominal = folder / f"{stem}{tail}.png", folder / f"{stem}.png"
                assert ours.stat().st_size > 10_000
                assert ours.read_bytes() != nominal.read_bytes()
        forward[case] = float(re.search(r"1x forward\s+([\d,]+) r/min", part)[1]
                              .replace(",", ""))
        lift[case] = float(re.search(r"journals lifted from ([\d,]+) r/min", part)[1]
                           .replace(",", ""))
    assert (forward["min clearance, cold oil"] > forward["nominal"]
            > forward["max clearance, hot oil"]), forward
    assert lift["min clearance, cold oil"] < lift["nominal"] < lift["max clearance, hot oil"], lift


def test_the_report_has_its_title_block_its_cases_and_each_case_s_films(pump_report):
    """The pump's report: the title block from the scene's keys; the three tolerance
    cases side by side, the clearances of each case in its column; the films' cross-
    coupled stiffness at the running speed falling from the tight, cold case through the
    nominal to the loose, hot one (kxy ~ mu omega L (R / c)^3 for a lightly loaded film);
    the seal listed as a seal, with no coefficients at standstill; the journals not
    given at standstill (their film's placeholders)."""
    markdown = (pump_report.parent / "report.md").read_text()
    for row in ("| machine | P-101 process water pump |", "| job | J-2026-014 |",
                "| revision | B |", "| date | 2026-11-27 |"):
        assert row in markdown, row
    cases = markdown[markdown.index("### The study's cases"):]
    head = next(line for line in cases.splitlines() if line.startswith("|  |"))
    assert head == "|  | nominal | min clearance, cold oil | max clearance, hot oil |"
    assert "| drive-end journal: radial clearance, um | 60.0 | 55.0 | 65.0 |" in cases
    assert "| wear ring: radial clearance, um | 300.0 | 275.0 | 325.0 |" in cases
    films = markdown[markdown.index("### Bearing and seal coefficients against speed"):]
    kxy = {}
    for line in films.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 11 and cells[1] == "drive-end journal" and cells[2] == "3,000":
            kxy[cells[0]] = float(cells[4].replace(",", ""))
    assert kxy["min clearance, cold oil"] > kxy["nominal"] > kxy["max clearance, hot oil"] > 0
    install = markdown[markdown.index("## Installation"):markdown.index("## Natural")]
    assert "support wear ring: seat 515-545 mm, annular seal" in install
    assert "no force at standstill" in install and "kxx" not in install
