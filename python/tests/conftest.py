"""Shared fixtures: the repository's paths and the command-line binary."""

import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="session")
def cli() -> str:
    """The `lamplight` binary: $LAMPLIGHT_CLI, else one built in target/, else built now."""
    candidates = [os.environ.get("LAMPLIGHT_CLI")] + [str(ROOT / "target" / p / "lamplight") for p in ("release", "debug")]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    if shutil.which("cargo") is None:
        pytest.fail("no lamplight binary: set LAMPLIGHT_CLI or build it with `cargo build -p lamplight-cli`")
    subprocess.run(["cargo", "build", "--locked", "-p", "lamplight-cli"], cwd=ROOT, check=True)
    return str(ROOT / "target" / "debug" / "lamplight")
