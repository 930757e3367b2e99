#!/usr/bin/env bash
# Build the PCL peer program against Debian's PCL:
#   apt-get install -y --no-install-recommends libpcl-dev g++ pkg-config
# PCL's voxel filter templates are compiled here (PCL_NO_PRECOMPILE) with -O3
# -march=native, as our own code is, so the comparison is not against a generic
# x86-64 build of libpcl_filters.
set -euo pipefail
cd "$(dirname "$0")"
mods=()
for m in pcl_filters pcl_common; do
  if pkg-config --exists "$m"; then mods+=("$m")
  elif pkg-config --exists "$m-1.13"; then mods+=("$m-1.13")
  else echo "build.sh: pkg-config cannot find $m (apt-get install libpcl-dev)" >&2; exit 1
  fi
done
# EIGEN_MAX_ALIGN_BYTES=16 keeps Eigen's allocation ABI the same as Debian's generic
# libpcl_* build (with -march=native Eigen would align to 32 and free() would crash
# on buffers allocated inside the library).
# shellcheck disable=SC2046
${CXX:-g++} -std=c++17 -O3 -march=native -DNDEBUG -DPCL_NO_PRECOMPILE \
  -DEIGEN_MAX_ALIGN_BYTES=16 -DEIGEN_MALLOC_ALREADY_ALIGNED=1 -Wall -Wno-deprecated-declarations \
  -o pcl_voxel pcl_voxel.cpp $(pkg-config --cflags --libs "${mods[@]}")
echo "built $(pwd)/pcl_voxel (PCL $(pkg-config --modversion "${mods[0]}"))"
