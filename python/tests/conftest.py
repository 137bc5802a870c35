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


@pytest.fixture(scope="session")
def oidn() -> None:
    """For tests that need Intel Open Image Denoise: skips them, saying why, where
    it is missing, except under CI, where ``scripts/test.sh`` installs it (pyoidn)
    and a missing library fails them."""
    import numpy as np

    import lamplight

    try:
        lamplight.denoise(np.zeros((1, 1, 3), dtype=np.float32))
    except ValueError as e:
        if os.environ.get("CI"):
            pytest.fail(f"CI must denoise (scripts/test.sh installs pyoidn): {e}")
        pytest.skip(f"Open Image Denoise is not installed: {e}")


@pytest.fixture(scope="session")
def client():
    """A Dask client of a LocalCluster of two one-thread worker processes,
    shared by the Dask tests (test_dask.py, test_dask_frames.py): starting one
    takes seconds of the suite's time."""
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()
