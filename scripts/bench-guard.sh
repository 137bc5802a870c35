#!/usr/bin/env bash
# The instruction-count guard (issue 24): counts the instructions of a fixed set of
# small single-threaded renders under valgrind (cachegrind, no cache simulation),
# compares them with bench/guard/baseline.toml, and fails when a case grew by more
# than 3 % without the baseline recording why. Run it before every commit that
# touches crates/lamplight-core.
#
#   scripts/bench-guard.sh                      # measure and compare (exit 1 on a slowdown)
#   scripts/bench-guard.sh --accept "REASON"    # write the new counts and REASON into the baseline
#   scripts/bench-guard.sh --only spheres,luxo  # some cases only (with --accept: only theirs)
#   scripts/bench-guard.sh --once               # one run per case instead of two (no repeat check)
#
# Builds the binary it measures (`cargo build --release --locked -p lamplight-cli`,
# in $CARGO_TARGET_DIR or target/). The raycast case needs the Stanford bunny of
# ../shared/data and is skipped with a message without it (or set LAMPLIGHT_BUNNY).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
}

args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --accept)
      if [ $# -lt 2 ] || [ -z "${2// /}" ]; then
        echo "error: --accept needs a reason: scripts/bench-guard.sh --accept \"why the counts changed\"" >&2
        exit 2
      fi
      args+=(--accept "$2"); shift 2 ;;
    --only)
      if [ $# -lt 2 ]; then echo "error: --only needs case names, e.g. --only spheres,luxo" >&2; exit 2; fi
      args+=(--only "$2"); shift 2 ;;
    --once) args+=(--once); shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "error: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

if ! command -v valgrind >/dev/null 2>&1; then
  if command -v apt-get >/dev/null 2>&1; then
    echo "== installing valgrind"
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq valgrind) ||
      { echo "error: could not install valgrind; install it (apt-get install valgrind) and run again" >&2; exit 2; }
  else
    echo "error: valgrind not found: install it (e.g. apt-get install valgrind) and run again" >&2
    exit 2
  fi
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "error: cargo not found: install Rust from https://rustup.rs (stable, 1.85 or newer)" >&2
  exit 2
fi
python=${PYTHON:-python3}

start=$(date +%s)
echo "== cargo build --release --locked -p lamplight-cli"
cargo build --release --locked --quiet -p lamplight-cli
target_dir=${CARGO_TARGET_DIR:-target}
bin="$(cd "$target_dir" && pwd)/release/lamplight"
if [ ! -x "$bin" ]; then
  echo "error: the build did not leave $bin" >&2
  exit 2
fi

bunny=${LAMPLIGHT_BUNNY:-../shared/data/meshes/stanford-bunny.obj}
inputs=$(mktemp -d "${TMPDIR:-/tmp}/lamplight-guard-inputs.XXXXXX")
trap 'rm -rf "$inputs"' EXIT
if [ -f "$bunny" ]; then
  bunny=$(cd "$(dirname "$bunny")" && pwd)/$(basename "$bunny")
  "$python" bench/guard/make_inputs.py "$inputs" --bunny "$bunny"
else
  "$python" bench/guard/make_inputs.py "$inputs"  # guard.py skips the raycast case and says why
fi

echo "== counting instructions (valgrind --tool=cachegrind --cache-sim=no)"
status=0
"$python" bench/guard/guard.py --bin "$bin" --inputs "$inputs" --bunny "$bunny" --jobs "$(nproc)" "${args[@]}" || status=$?
echo "== bench-guard took $(($(date +%s) - start)) s (build included)"
exit $status
