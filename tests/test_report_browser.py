"""report.html in a real browser: headless Chromium decodes every image and lays the page out.

A copy of the report gets a probe script that, on the load event (all images loaded or failed),
records which images did not decode (naturalWidth 0) and which elements stick out of a
1280-pixel window, and writes that as JSON into the DOM; ``--dump-dom`` prints the DOM. The
probe is shown to catch both faults on a page that has them. A screenshot of a failing report
checks that the red FAILED box is on the first screen.

Skipped, with the reason, only where no Chromium is installed (.ci/run installs Debian's
``chromium`` when apt-get is available); the ``browser`` fixture is in conftest.py.
"""

import copy
import html
import json
import re

import numpy as np
from headless import WINDOW
from PIL import Image

from shtaerman.output.report import render_html, report_context

PROBE = """<script>
window.addEventListener("load", () => {
  const width = document.documentElement.clientWidth;
  const images = [...document.images];
  const found = {
    images: images.length,
    undecoded: images.filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.alt),
    overflowing: [...document.querySelectorAll("body *")]
      .filter((e) => e.getBoundingClientRect().right > width + 0.5)
      .map((e) => e.tagName.toLowerCase()),
    scroll_width: document.documentElement.scrollWidth,
    width: width,
  };
  const out = document.createElement("pre");
  out.id = "probe";
  out.textContent = JSON.stringify(found);
  document.body.appendChild(out);
});
</script>"""
FAIL_RED = (187, 0, 0)
"""#b00: the FAILED box's border and heading."""


def probe(browser, page: str, folder) -> dict:
    """Load ``page`` (HTML text) with the probe in Chromium; the probe's findings."""
    path = folder / "probed.html"
    path.write_text(page.replace("</body>", PROBE + "</body>"), encoding="utf-8")
    dom = browser("--virtual-time-budget=15000", "--dump-dom", path.as_uri())
    match = re.search(r'<pre id="probe">(.*?)</pre>', dom, re.DOTALL)
    assert match, "the probe did not run: " + dom[-500:]
    return json.loads(html.unescape(match.group(1)))


def test_every_image_decodes_and_nothing_overflows(browser, quick_verify, tmp_path):
    _, out, _ = quick_verify
    page = (out / "report.html").read_text(encoding="utf-8")
    found = probe(browser, page, tmp_path)
    assert found["images"] == page.count("<img ") >= 2 * 9 + 1  # 9+ per study, the Ateb figure
    assert found["undecoded"] == []
    assert found["overflowing"] == [] and found["scroll_width"] <= found["width"]


def test_the_probe_sees_a_broken_image_and_an_overflow(browser, quick_verify, tmp_path):
    page = (quick_verify[1] / "report.html").read_text(encoding="utf-8")
    broken = re.sub(
        r'src="data:image/png;base64,[^"]*"', 'src="data:image/png;base64,AAAA"', page, count=1
    )
    broken = broken.replace('<table id="summary">', '<table id="summary" style="width:3000px">')
    found = probe(browser, broken, tmp_path)
    assert len(found["undecoded"]) == 1
    assert "table" in found["overflowing"] and found["scroll_width"] > found["width"]


def test_failures_are_on_the_first_screen(browser, quick_verify, tmp_path):
    _, out, results = quick_verify
    failed = copy.deepcopy(results)
    study = failed["studies"]["paper"]
    study["checks"][0]["tolerance"], study["checks"][0]["passed"] = 1e-9, False
    study["passed"] = failed["passed"] = False
    page = tmp_path / "failed.html"
    page.write_text(render_html(report_context(failed), out), encoding="utf-8")
    shot = tmp_path / "failed.png"
    browser(f"--screenshot={shot}", page.as_uri())
    image = np.asarray(Image.open(shot).convert("RGB"), dtype=int)
    assert image.shape[:2] == (WINDOW[1], WINDOW[0])
    assert image.std() > 20  # not blank: text, tables, the red box
    red = (np.abs(image - np.array(FAIL_RED)).max(axis=2) <= 30).sum()
    assert red > 3000  # the box's 3-pixel border alone is about 2 x 3 x 1100 pixels
