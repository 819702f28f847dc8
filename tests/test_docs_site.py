"""The docs site (mkdocs.yml over docs/) builds with warnings as errors, holds every page, and the
README stays what a newcomer reads first."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from conftest import ROOT
from test_readme import pages

README_MAX_LINES = 300


def test_the_docs_site_builds_with_warnings_as_errors(tmp_path):
    mkdocs = Path(sys.executable).parent / "mkdocs"
    done = subprocess.run([str(mkdocs), "build", "--strict", "--site-dir", str(tmp_path / "site")],
                          cwd=ROOT, capture_output=True, text=True,
                          env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "site" / "cli" / "index.html").is_file()


def test_every_docs_page_is_in_the_nav():
    listed = {p.name for p in pages()[1:]}
    assert not sorted(p.name for p in (ROOT / "docs").glob("*.md") if p.name not in listed)


def test_the_readme_is_short_and_points_at_every_guide_page():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= README_MAX_LINES
    assert not [p.name for p in pages()[1:] if p.name != "index.md" and f"(docs/{p.name})" not in readme]
