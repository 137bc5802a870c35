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


def test_the_quoted_dict_error_is_the_one_the_code_raises():
    import lamplight as ll

    text = (ROOT / "docs" / "python.md").read_text()
    quoted = re.search(r"`(scene dict: objects\[1\]\.radius: [^`]*)`", text).group(1)
    scene = ll.scene(
        camera=ll.camera(eye=[0, 0, 5], look_at=[0, 0, 0]),
        objects=[ll.point_light([0, 4, 0], 10), ll.sphere([0, 0, 0], "big")],
    )
    try:
        ll.render(scene, width=8, height=8)
    except ll.SceneError as e:
        assert str(e) == quoted
    else:
        raise AssertionError("a sphere of radius 'big' rendered")


def test_every_example_file_is_listed_in_the_docs():
    listed = set(re.findall(r"`examples/([\w-]+\.toml)`", (ROOT / "docs" / "examples.md").read_text()))
    assert listed == {p.name for p in (ROOT / "examples").glob("*.toml")}


def test_the_install_instructions_say_what_pip_install_needs_and_how_long_it_takes():
    # Issue 27: `pip install .` ran silently for about 2 minutes and needed
    # Rust, and the README said neither.
    for doc in ["README.md", "docs/python.md"]:
        text = (ROOT / doc).read_text()
        at = text.index("pip install -v .")
        around = text[max(0, at - 300) : at + 900]
        assert "Rust 1.85 or newer" in around, doc
        assert "about 2\nminutes" in around or "about 2 minutes" in around, doc
        assert "`-v`" in around and "progress" in around, doc
