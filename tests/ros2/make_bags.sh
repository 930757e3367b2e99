#!/usr/bin/env bash
# Write the test bags tests/ros2_bag.rs reads into DIR (default: tests/ros2), with the
# Python mcap tools (pip install mcap mcap-ros2-support zstandard lz4 pypng).
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-tests/ros2}"
mkdir -p "$out"
frames=(fixtures/scenes/flat.png fixtures/scenes/step_15cm.png fixtures/scenes/uphill_straight.png)
python3 tests/ros2/make_bag.py "$out/depth-zstd.mcap" "${frames[@]}"
python3 tests/ros2/make_bag.py "$out/depth-lz4.mcap" --compression lz4 --bad-frame 1 "${frames[@]}"
