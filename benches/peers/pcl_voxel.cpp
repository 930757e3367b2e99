// pcl_voxel: what a user would otherwise write with PCL, timed on the same depth frame
// rover-terrain's `bench` reads (benches/peers/compare.sh runs both).
//
// Reads a 16-bit binary PGM depth image (millimetres, 0 = no return), projects every
// valid pixel with the FOV model rover-terrain uses by default
//   X = (u/W - 0.5) * Z * 2 tan(hfov/2),  Y = (0.5 - v/H) * Z * 2 tan(vfov/2)
// into a pcl::PointCloud<pcl::PointXYZ>, and reduces it with
// pcl::ApproximateVoxelGrid (and, for reference, pcl::VoxelGrid) at a 0.05 m leaf.
// Times projection + filter together, from the decoded depth buffer to the filtered
// cloud, after a warm-up; prints one JSON line of microseconds (median, p99).
//
// Usage: pcl_voxel DEPTH.pgm [--reps 200] [--warmup 10] [--hfov 57] [--vfov 43] [--leaf 0.05]

#include <pcl/filters/approximate_voxel_grid.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

namespace {

[[noreturn]] void die(const std::string& msg) {
  std::fprintf(stderr, "pcl_voxel: %s\n", msg.c_str());
  std::exit(2);
}

struct Depth {
  int w = 0, h = 0;
  std::vector<uint16_t> mm;
};

// A binary PGM, 16-bit big-endian samples, header without comments (what
// rover-terrain writes).
Depth read_pgm(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) die("cannot open " + path);
  std::string magic;
  int maxval = 0;
  Depth d;
  f >> magic >> d.w >> d.h >> maxval;
  if (magic != "P5" || d.w <= 0 || d.h <= 0 || maxval <= 255 || maxval > 65535)
    die(path + ": not a 16-bit binary PGM");
  f.get();  // the one whitespace byte before the raster
  std::vector<unsigned char> raw((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const size_t n = size_t(d.w) * size_t(d.h);
  if (raw.size() < 2 * n) die(path + ": truncated raster");
  d.mm.resize(n);
  for (size_t i = 0; i < n; ++i) d.mm[i] = uint16_t(raw[2 * i] << 8 | raw[2 * i + 1]);
  return d;
}

Cloud::Ptr project(const Depth& d, float hfov_deg, float vfov_deg) {
  const float rad = float(M_PI / 180.0);
  const float tx = 2.0f * std::tan(0.5f * hfov_deg * rad);
  const float ty = 2.0f * std::tan(0.5f * vfov_deg * rad);
  Cloud::Ptr cloud(new Cloud);
  cloud->points.reserve(d.mm.size());
  for (int v = 0; v < d.h; ++v) {
    const float fy = (0.5f - float(v) / float(d.h)) * ty;
    for (int u = 0; u < d.w; ++u) {
      const uint16_t mm = d.mm[size_t(v) * size_t(d.w) + size_t(u)];
      if (mm == 0) continue;
      const float z = float(mm) * 0.001f;
      cloud->points.emplace_back((float(u) / float(d.w) - 0.5f) * tx * z, fy * z, z);
    }
  }
  cloud->width = uint32_t(cloud->points.size());
  cloud->height = 1;
  return cloud;
}

template <class Filter>
size_t reduce(const Cloud::Ptr& in, float leaf, Cloud& out) {
  Filter f;
  f.setLeafSize(leaf, leaf, leaf);
  f.setInputCloud(in);
  f.filter(out);
  return out.size();
}

// Median and p99 (nearest rank) of `reps` timed runs of `fn`, microseconds.
template <class F>
std::pair<double, double> time_it(int warmup, int reps, F&& fn) {
  for (int i = 0; i < warmup; ++i) fn();
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  const size_t r = std::max<size_t>(1, size_t(std::ceil(0.99 * double(t.size()))));
  return {t[t.size() / 2], t[std::min(t.size(), r) - 1]};
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  int reps = 200, warmup = 10;
  float hfov = 57.0f, vfov = 43.0f, leaf = 0.05f;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) die("missing value for " + a);
      return argv[++i];
    };
    if (a == "--reps") reps = std::atoi(value().c_str());
    else if (a == "--warmup") warmup = std::atoi(value().c_str());
    else if (a == "--hfov") hfov = std::strtof(value().c_str(), nullptr);
    else if (a == "--vfov") vfov = std::strtof(value().c_str(), nullptr);
    else if (a == "--leaf") leaf = std::strtof(value().c_str(), nullptr);
    else if (!a.empty() && a[0] == '-') die("unknown option " + a);
    else path = a;
  }
  if (path.empty()) die("usage: pcl_voxel DEPTH.pgm [--reps N] [--warmup N] [--hfov DEG] [--vfov DEG] [--leaf M]");
  if (reps < 1 || warmup < 0 || !(leaf > 0.0f)) die("bad --reps, --warmup or --leaf");
  const Depth d = read_pgm(path);
  size_t points = 0, approx = 0, exact = 0;
  const auto a = time_it(warmup, reps, [&] {
    Cloud::Ptr c = project(d, hfov, vfov);
    Cloud out;
    points = c->size();
    approx = reduce<pcl::ApproximateVoxelGrid<pcl::PointXYZ>>(c, leaf, out);
  });
  const auto v = time_it(warmup, reps, [&] {
    Cloud::Ptr c = project(d, hfov, vfov);
    Cloud out;
    exact = reduce<pcl::VoxelGrid<pcl::PointXYZ>>(c, leaf, out);
  });
  std::printf(
      "{\"impl\":\"pcl\",\"pcl_version\":\"%s\",\"width\":%d,\"height\":%d,\"reps\":%d,"
      "\"points_in\":%zu,\"voxels_approx\":%zu,\"voxels_exact\":%zu,"
      "\"project_approx_voxel_us\":{\"median\":%.1f,\"p99\":%.1f},"
      "\"project_voxel_us\":{\"median\":%.1f,\"p99\":%.1f}}\n",
      PCL_VERSION_PRETTY, d.w, d.h, reps, points, approx, exact, a.first, a.second, v.first, v.second);
  return 0;
}
