"""The Python in the README and docs/python.md runs as written."""
import re

import pytest

from conftest import SOURCE_DIR


@pytest.mark.parametrize("document", ["README.md", "docs/python.md"])
def test_the_documents_python_runs(document, monkeypatch):
    monkeypatch.chdir(SOURCE_DIR)  # as a reader runs it, from the repository's root
    text = (SOURCE_DIR / document).read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    for block in blocks:
        exec(compile(block, document, "exec"), {})
