#!/usr/bin/env bash
# Runs every lamplight test on a fresh machine: installs what is missing, then
# checks formatting and lints, runs the Rust test suites, then the Python package's tests.
set -euo pipefail
cd "$(dirname "$0")/.."

need_apt=()
command -v cc >/dev/null 2>&1 || need_apt+=(gcc libc6-dev)
# Headless Chromium for the `lamplight view` browser tests (python/tests/test_view_browser.py).
command -v chromium >/dev/null 2>&1 || need_apt+=(chromium)
command -v chromedriver >/dev/null 2>&1 || need_apt+=(chromium-driver)
if [ ${#need_apt[@]} -gt 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "== installing Debian packages: ${need_apt[*]}"
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need_apt[@]}") ||
    echo "warning: could not install ${need_apt[*]}; tests that need them use stored references or skip"
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "error: cargo not found: install Rust from https://rustup.rs (stable, 1.85 or newer)" >&2
  exit 1
fi
rustup component add rustfmt clippy >/dev/null 2>&1 || true

echo "== cargo fmt --check"
cargo fmt --all --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets --locked -- -D warnings
echo "== cargo test"
cargo test --workspace --locked
echo "== cargo doc"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --quiet

# The Python package: a virtual environment with what pytest needs, the
# extension built into it (the dev profile, which reuses the build above), and
# the Python tests (scene dicts, renders against the binary's EXR output, ray
# queries, Dask on a LocalCluster, a killed worker).
echo "== python: .venv with maturin, numpy, pytest, dask[distributed], tqdm, selenium"
python=${PYTHON:-python3}
if ! command -v "$python" >/dev/null 2>&1; then
  echo "error: $python not found: install Python 3.9 or newer" >&2
  exit 1
fi
if [ ! -x .venv/bin/python ]; then
  "$python" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check "maturin>=1.5,<2" numpy pytest "dask[distributed]" tqdm
# Selenium drives Chromium in the viewer's browser tests; without it they skip.
.venv/bin/python -m pip install --quiet --disable-pip-version-check selenium ||
  echo "warning: could not install selenium; the viewer's browser tests skip"
echo "== python: maturin develop"
VIRTUAL_ENV="$PWD/.venv" PATH="$PWD/.venv/bin:$PATH" .venv/bin/maturin develop --locked --quiet
echo "== pytest"
cargo build --locked --quiet -p lamplight-cli
LAMPLIGHT_CLI="$PWD/target/debug/lamplight" .venv/bin/python -m pytest python/tests -q -p no:cacheprovider
