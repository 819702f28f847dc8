"""The diagnosis report: every target in one page, figures embedded, links inside the page,
figures in hours with legends; and the page as headless Chromium renders it."""

from __future__ import annotations

import base64
import json
import os
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest

from conftest import thermocomp
from thermocomp.apps.diagnose import figures as diag_figures
from thermocomp.apps.diagnose.report import slug
from thermocomp.core.figures.plots import AFTER

CHROMIUM = Path("/usr/bin/chromium")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
SECTIONS = ("before-and-after", "accepted-effects", "figures", "evidence-round-by-round")


class Page(HTMLParser):
    """Ids, links, images and ``h2`` headings of an HTML page, in document order."""

    def __init__(self, text: str):
        super().__init__()
        self.ids, self.hrefs, self.images, self.h2 = [], [], [], []
        self._in_h2 = False
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.append(a["id"])
        if tag == "a" and "href" in a:
            self.hrefs.append(a["href"])
        if tag == "img":
            self.images.append(a.get("src", ""))
        if tag == "h2":
            self._in_h2 = True

    def handle_endtag(self, tag):
        self._in_h2 = self._in_h2 and tag != "h2"

    def handle_data(self, data):
        if self._in_h2:
            self.h2.append(data.strip())


@pytest.fixture(scope="session")
def report(door_dataset, tmp_path_factory):
    """A diagnosis of three targets (a planted door: an accepted effect on E_Y and E_Z; E_X has
    none that clears the family-wise bar)."""
    root = tmp_path_factory.mktemp("report")
    data, out = door_dataset, root / "out"
    thermocomp("diagnose", f"data.path={data}", f"out={out}", "track=false", "diagnose.max_effects=1")
    folder = out / "diagnosis"
    targets = sorted(p.stem.removeprefix("diagnosis_") for p in folder.glob("diagnosis_*.json"))
    return folder, targets


@pytest.mark.slow
def test_one_page_holds_every_target_each_with_its_own_contents(report):
    folder, targets = report
    assert len(targets) == 3
    page = Page((folder / "report.html").read_text())
    assert sorted(page.h2[page.h2.index("Contents") + 1:][:3]) == targets
    assert len(page.ids) == len(set(page.ids)), "duplicate anchors"
    primary = json.loads((folder.parent / "diagnosis.json").read_text())["target"]
    assert page.h2[page.h2.index("Contents") + 1] == primary
    for t in targets:
        assert slug(t) in page.ids and f"#{slug(t)}" in page.hrefs
        for section in SECTIONS:   # the target's contents links to each of its sections
            anchor = f"{slug(t)}-{section}"
            assert anchor in page.ids and f"#{anchor}" in page.hrefs, anchor
        j = json.loads((folder / f"diagnosis_{t}.json").read_text())
        assert j["report"] == str(folder / "report.html")
        accepted = next((e for e in j["effects"] if e["accepted"]), None)
        if accepted is None:
            assert "Nothing cleared the bar" in (folder / "report.md").read_text()
            continue
        assert f"{accepted['kind']} | {accepted['column'] or '—'} | {accepted['transform']}" in \
            (folder / "report.md").read_text()
    assert not list(folder.glob("report_*")), "one report, not one per target"


@pytest.mark.slow
def test_figures_are_embedded_and_links_stay_inside_the_page(report):
    folder, targets = report
    page = Page((folder / "report.html").read_text())
    pngs = sorted((folder / "plots").glob("*.png"))
    accepted = sum(any(e["accepted"] for e in json.loads(
        (folder / f"diagnosis_{t}.json").read_text())["effects"]) for t in targets)
    assert accepted >= 2 and len(pngs) == len(targets) + accepted   # E_P95 per target + effects
    prefix = "data:image/png;base64,"
    assert all(src.startswith(prefix) for src in page.images)
    assert sorted(base64.b64decode(src[len(prefix):]) for src in page.images) == \
        sorted(p.read_bytes() for p in pngs)
    for href in page.hrefs:
        assert href.startswith(("http://", "https://")) or href.lstrip("#") in page.ids, href
    md = (folder / "report.md").read_text()
    assert ".md)" not in md and "](#" in md
    for rel in (line.split("](", 1)[1].rstrip(")") for line in md.splitlines() if line.startswith("![")):
        assert (folder / rel).is_file(), rel


class _Kept:
    """``save_figure`` stand-in: keeps the figure for inspection."""

    def __init__(self):
        self.figures = []

    def __call__(self, fig, path):
        self.figures.append(fig)
        return Path(path)


def _check_axes(fig):
    for ax in fig.axes:
        assert ax.get_legend() is not None, ax.get_title()
        assert "(µm)" in ax.get_ylabel() or "(°C)" in ax.get_ylabel(), ax.get_ylabel()


def test_diagnosis_figures_are_in_hours_with_legends_on_every_axes(monkeypatch, tmp_path):
    kept = _Kept()
    monkeypatch.setattr(diag_figures, "save_figure", kept)
    rng = np.random.default_rng(0)
    units = np.repeat(["K01", "K02", "K05"], 50)
    time_s = np.tile(np.arange(50) * 300.0, 3)
    signal = rng.normal(size=150)
    signal[units == "K05"] *= 3                  # K05: the campaign the effect explains most
    diag_figures.residual_vs_effect(signal + rng.normal(size=150), signal, units, "step 1", "E_Y",
                                    tmp_path / "a.png", time_s)
    diag_figures.e_p95_before_after([300, 3600, 14400], [1, 2, 3], [1, 1.5, 2], [0.5, 0.6, 0.7],
                                    "E_Y", "range", "mlr", tmp_path / "b.png")
    scatter, series = kept.figures[0].axes
    _check_axes(kept.figures[0])
    _check_axes(kept.figures[1])
    assert {"K01", "K02", "K05"} <= {t.get_text() for t in scatter.get_legend().get_texts()}
    assert series.get_xlabel() == "time since campaign start (h)"
    assert series.get_title().startswith("K05")
    assert series.lines[0].get_xdata().max() == pytest.approx(49 * 300 / 3600)
    assert kept.figures[1].axes[0].get_xlabel().endswith("(h)")


def test_residual_figure_has_hours_and_a_legend_on_both_axes(monkeypatch, tmp_path):
    from thermocomp.core.figures import plots
    kept = _Kept()
    monkeypatch.setattr(plots, "save_figure", kept)
    t = np.arange(100) * 60.0
    plots.residual_plot(t, np.sin(t / 3000), 0.9 * np.sin(t / 3000), "E_Z", "K03", tmp_path / "r.png")
    fig = kept.figures[0]
    _check_axes(fig)
    assert fig.axes[1].get_xlabel() == "time since campaign start (h)"
    assert fig.axes[1].lines[0].get_xdata().max() == pytest.approx(99 / 60)


# -- the page in a browser -------------------------------------------------------------------------

CHECK = """<script>
window.addEventListener("load", function () {
  var imgs = Array.prototype.slice.call(document.images);
  var links = Array.prototype.slice.call(document.querySelectorAll("a[href]"));
  var r = {images: imgs.length,
           broken_images: imgs.filter(function (i) { return !i.complete || i.naturalWidth === 0; }).length,
           links: links.length,
           broken_links: links.filter(function (a) {
             var h = a.getAttribute("href");
             if (h.charAt(0) === "#") { return !document.getElementById(decodeURIComponent(h.slice(1))); }
             return !/^https?:[/][/]/.test(h);
           }).length};
  document.title = "CHECK " + JSON.stringify(r);
});
</script>"""


def _chromium(profile: Path, *args: str) -> subprocess.CompletedProcess:
    if not CHROMIUM.exists():
        if os.environ.get("CI"):
            pytest.fail(f"{CHROMIUM} missing in CI: .ci/chromium should have installed it")
        pytest.skip(f"{CHROMIUM} not installed (Debian package `chromium`; .ci/chromium installs it)")
    proc = subprocess.run([str(CHROMIUM), *FLAGS, f"--user-data-dir={profile}", *args],
                          capture_output=True, text=True, timeout=180)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc


@pytest.mark.slow
def test_chromium_renders_the_copied_page_without_broken_images_or_links(report, tmp_path):
    folder, targets = report
    alone = tmp_path / "copy"                   # the page alone: no plots/ beside it
    alone.mkdir()
    page = (folder / "report.html").read_text()
    assert page.count("</body>") == 1
    (alone / "report.html").write_text(page)
    (alone / "checked.html").write_text(page.replace("</body>", CHECK + "</body>"))
    proc = _chromium(tmp_path / "profile-dom", "--virtual-time-budget=10000", "--dump-dom",
                     (alone / "checked.html").as_uri())
    title = proc.stdout.split("<title>", 1)[1].split("</title>", 1)[0]
    assert title.startswith("CHECK "), title
    result = json.loads(title.removeprefix("CHECK ").replace("&quot;", '"'))
    n_png = len(list((folder / "plots").glob("*.png")))
    assert result == {"images": n_png, "broken_images": 0, "links": result["links"], "broken_links": 0}
    assert result["links"] >= 5 * len(targets)

    shot = tmp_path / "shot.png"
    _chromium(tmp_path / "profile-shot", f"--screenshot={shot}", "--window-size=1280,4000",
              "--hide-scrollbars", (alone / "report.html").as_uri())
    from PIL import Image

    pixels = np.asarray(Image.open(shot).convert("RGB"), dtype=float)
    assert pixels.shape == (4000, 1280, 3)
    assert (pixels.min(axis=2) < 200).mean() > 0.02, "a blank page"
    # the figures are drawn: pixels of the "after" line colour, which no text or table uses
    after = np.array([int(AFTER[i:i + 2], 16) for i in (1, 3, 5)], float)
    assert (np.abs(pixels - after).max(axis=2) < 40).sum() > 200, "no figure on screen"
