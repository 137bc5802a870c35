"""Every `lamplight` command of the README's and the docs' shell blocks runs as
written, and the README's usage synopsis names only flags the program has
(issue 27: documented flags had drifted from the program).

The commands run in a scratch folder that holds what they name: the
repository's `examples/`, a small Mitsuba scene (`scene.xml`, with `$spp` and
`$res` defaults as the docs' `-D` line expects), a mesh file (`model.obj`) and
an EXR to denoise (`in.exr`). Each must exit 0 and write the file it names
(the scene's name as a PNG when it names none)."""

import re
import shlex
import subprocess
from pathlib import Path

import pytest

from conftest import ROOT

DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

SCENE_XML = """<scene version="3.0.0">
    <default name="spp" value="4"/>
    <default name="res" value="32"/>
    <integrator type="path"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"/></shape>
    <emitter type="constant"/>
</scene>
"""

MODEL_OBJ = """v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
"""


def shell_commands():
    """(document, line) for each `lamplight ...` command of a ```sh block; a
    line `A && lamplight ...` gives its lamplight part, comments are dropped."""
    found = []
    for doc in DOCS:
        for block in re.findall(r"```sh\n(.*?)```", doc.read_text(), flags=re.S):
            for line in block.splitlines():
                line = re.sub(r"\s+#.*$", "", line).strip()
                command = line.split("&&")[-1].strip()
                if command.startswith("lamplight "):
                    found.append((doc.relative_to(ROOT).as_posix(), command))
    return found


def test_the_docs_have_shell_commands_to_run():
    # README's first command and the docs' examples (mitsuba, scene format, denoising).
    docs = {doc for doc, _ in shell_commands()}
    assert {"README.md", "docs/mitsuba.md", "docs/scene-format.md", "docs/denoise.md"} <= docs, docs
    assert len(shell_commands()) >= 10


@pytest.fixture
def scratch(tmp_path, cli):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    (tmp_path / "scene.xml").write_text(SCENE_XML)
    (tmp_path / "model.obj").write_text(MODEL_OBJ)
    subprocess.run([cli, "render", "cornell-box", "--spp", "2", "--width", "16", "--height", "16", "-q", "-o", "in.exr"],
                   cwd=tmp_path, check=True)
    return tmp_path


@pytest.mark.parametrize("doc,command", shell_commands(), ids=[f"{d}: {c}" for d, c in shell_commands()])
def test_a_documented_command_runs_as_written(doc, command, cli, scratch, request):
    args = shlex.split(command)
    if "--denoise" in args or args[1] == "denoise":
        request.getfixturevalue("oidn")
    out = subprocess.run([cli, *args[1:]], cwd=scratch, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, f"{doc}: `{command}` exited {out.returncode}: {out.stderr}"
    written = args[args.index("-o") + 1] if "-o" in args else default_output(args)
    assert (scratch / written).is_file(), f"{doc}: `{command}` wrote no {written}"


def default_output(args):
    """What `lamplight render` writes without `-o`: the scene's name as a PNG,
    `luxo.png` with no scene."""
    scene = next((a for a in args[2:] if not a.startswith("-")), None)
    return f"{Path(scene).stem}.png" if scene else "luxo.png"


def usage_lines():
    """The README's usage synopsis, one `lamplight SUB ...` line with its continuation lines."""
    text = (ROOT / "README.md").read_text()
    block = re.search(r"## Using it\n\n```text\n(.*?)```", text, flags=re.S).group(1)
    lines = []
    for line in block.splitlines():
        if line.startswith("lamplight "):
            lines.append(line)
        else:
            lines[-1] += " " + line.strip()
    return lines


def test_the_usage_synopsis_names_only_flags_the_program_has(cli):
    lines = usage_lines()
    assert len(lines) >= 8
    for line in lines:
        sub = line.split()[1]
        helptext = subprocess.run([cli, sub, "--help"], capture_output=True, text=True, check=True).stdout
        for flag in sorted(set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", line))):
            assert re.search(rf"(?<![\w-]){flag}(?![\w-])", helptext), f"README: `lamplight {sub}` has no {flag}"
