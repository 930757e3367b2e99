#!/usr/bin/env bash
# rover-terrain against PCL on the same depth frame, interleaved, on this machine:
# prints each run's medians and the ratio. Machines are shared and noisy: compare the
# ratio, not the times, and run it more than once.
#   benches/peers/compare.sh [RUNS]        (default 3)
# Needs libpcl-dev, g++ and pkg-config (see build.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${1:-3}
frame=target/peers/flat_640x480.pgm
mkdir -p target/peers
cargo build --release -q
cargo run --release -q --example peer_frame -- "$frame"
benches/peers/build.sh > /dev/null
for i in $(seq "$runs"); do
  ours=$(target/release/rover-terrain bench --iterations 1000 "$frame" \
    | sed -E 's/.*"total":\{"median":([0-9.]+).*/\1/')
  pcl=$(benches/peers/pcl_voxel "$frame" --reps 200 \
    | sed -E 's/.*"project_approx_voxel_us":\{"median":([0-9.]+).*/\1/')
  awk -v o="$ours" -v p="$pcl" -v i="$i" 'BEGIN {
    printf "run %d: rover-terrain whole pipeline %.0f us, PCL projection + ApproximateVoxelGrid %.0f us: %.1fx\n", i, o, p, p / o }'
done
