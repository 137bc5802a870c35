#!/bin/sh
# Builds the native Embree harness (needs Debian's libembree-dev, Embree 3.13).
set -e
cd "$(dirname "$0")"
mkdir -p "${OUT_DIR:-/tmp/lamplight-embree}"
cc -O2 -std=c11 -Wall -o "${OUT_DIR:-/tmp/lamplight-embree}/harness" harness.c -lembree3 -lpthread -lm
echo "${OUT_DIR:-/tmp/lamplight-embree}/harness"
