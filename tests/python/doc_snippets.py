"""Runs every ```python snippet of a Markdown page in order, in one namespace, in a folder.

    doc_snippets.py docs/python.md docs/      # what the page's figures come from

tests/python/test_docs.py runs the page's snippets the same way in a temporary folder.
"""
import os
import re
import sys

SNIPPET = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def snippets(md_path):
    with open(md_path, encoding="utf-8") as f:
        return SNIPPET.findall(f.read())


def run_snippets(md_path, cwd):
    namespace = {"__name__": "__doc__"}
    old = os.getcwd()
    os.chdir(cwd)
    try:
        for i, code in enumerate(snippets(md_path)):
            exec(compile(code, f"{md_path}:snippet{i + 1}", "exec"), namespace)
    finally:
        os.chdir(old)
    return namespace


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: doc_snippets.py PAGE.md FOLDER")
    import matplotlib
    matplotlib.use("Agg")
    run_snippets(os.path.abspath(sys.argv[1]), sys.argv[2])
