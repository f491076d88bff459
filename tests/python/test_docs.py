"""Every snippet of docs/python.md runs, in order, and produces what the page says."""
import os

import matplotlib

matplotlib.use("Agg")

from doc_snippets import run_snippets, snippets  # noqa: E402


def test_python_page_snippets_run(source_dir, tmp_path):
    page = os.path.join(source_dir, "docs", "python.md")
    assert len(snippets(page)) >= 4
    ns = run_snippets(page, tmp_path)
    for png in ("python_point_mass.png", "python_arm.png"):
        assert (tmp_path / png).stat().st_size > 1000
    # the page's claims: MGE covers more of the point mass's reach than RGE
    assert ns["coverage"]["MGE"] > ns["coverage"]["RGE"]
