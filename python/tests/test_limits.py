"""Each limit reads the same from the command line and from Python (issue 25,
"limits are written once"): both front ends take the bound and its message from
the request layer's `limits` module, so the two messages may differ only in how
each front end spells the setting (`--max-depth` there, `max_depth` here).

The other tests hold each front end to the text on its own; this one puts the
two side by side, so a front end that words a limit itself fails here even when
its own test was updated with it."""

import subprocess

import pytest

import lamplight

# (what is checked, command-line flags, Python keywords): every limit of
# `lamplight_scene::request::limits` a render takes, below and above its range.
CASES = [
    ("spp below", ["--spp", "0"], dict(spp=0)),
    ("spp above", ["--spp", "1048577"], dict(spp=1048577)),
    ("spp beyond u32", ["--spp", "4294967295"], dict(spp=4294967295)),
    ("depth below", ["--max-depth", "0"], dict(max_depth=0)),
    ("depth above", ["--max-depth", "65"], dict(max_depth=65)),
    ("threads above", ["--threads", "1025"], dict(threads=1025)),
    ("pixels", ["--width", "100000", "--height", "100000"], dict(width=100000, height=100000)),
]

FLAG_NAMES = {"--spp": "spp", "--max-depth": "max_depth", "--threads": "threads"}


def command_line_message(cli, folder, flags):
    out = subprocess.run([cli, "render", "spheres", "-o", str(folder / "x.png"), *flags], capture_output=True, text=True)
    assert out.returncode == 2, out.stderr
    prefix = "lamplight: error: "
    assert out.stderr.startswith(prefix) and out.stderr.count("\n") == 1, out.stderr
    return out.stderr[len(prefix) :].rstrip("\n")


@pytest.mark.parametrize("flags, keywords", [(f, k) for _, f, k in CASES], ids=[name for name, _, _ in CASES])
def test_each_limit_reads_alike_from_the_command_line_and_python(cli, tmp_path, flags, keywords):
    from_cli = command_line_message(cli, tmp_path, flags)
    with pytest.raises(ValueError) as raised:
        lamplight.render("spheres", progress=False, **keywords)
    from_python = str(raised.value)
    spelled_as_python = from_cli
    for flag, keyword in FLAG_NAMES.items():
        spelled_as_python = spelled_as_python.replace(flag, keyword)
    assert spelled_as_python == from_python, f"command line: {from_cli}\npython:       {from_python}"
    assert not (tmp_path / "x.png").exists(), "a refused render writes nothing"
