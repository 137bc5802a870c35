"""The tutorial's scene examples (docs/python.md) run as written."""

import re

from conftest import ROOT


def blocks():
    text = (ROOT / "docs" / "python.md").read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_the_dict_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)
    runnable = [b for b in blocks() if "tomllib.load" in b or "ll.scene(" in b]
    assert len(runnable) == 2
    for block in runnable:
        names = {}
        exec(compile(block, "docs/python.md", "exec"), names)
        image = names["image"]
        assert image.ndim == 3 and image.shape[2] == 3 and image.max() > 0
