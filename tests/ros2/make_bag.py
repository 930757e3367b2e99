#!/usr/bin/env python3
"""Write a small ROS 2 bag (MCAP, CDR) of depth frames with independent tools.

The bag is written by the Python `mcap` and `mcap-ros2-support` packages, not by
rover-terrain, so that reading it tests our reader against what ROS 2 tooling writes:

    python3 tests/ros2/make_bag.py OUT.mcap [--compression zstd|lz4|none] \
        [--bad-frame N] FRAME.png...

Each 16-bit PNG (millimetres) becomes one message on each of two depth topics,
`/camera/depth/image_raw` as 16UC1 (millimetres) and `/camera/depth/image_float` as
32FC1 (metres), with a `sensor_msgs/msg/CameraInfo` beside each (pinhole K of the
Kinect-like default camera: 640x480, 57 x 43 degrees). A `/camera/color/image_raw` rgb8
topic is there too, as a real camera driver would publish one. `--bad-frame N` makes
the N-th 16UC1 message's data one row short (its header still says the full height).

Needs: pip install mcap mcap-ros2-support zstandard lz4 pypng
"""

import argparse
import math
import struct
import sys

import png
from mcap.writer import CompressionType
from mcap_ros2.writer import Writer

HEADER = """
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""

IMAGE = """std_msgs/Header header
uint32 height
uint32 width
string encoding
uint8 is_bigendian
uint32 step
uint8[] data
""" + HEADER

CAMERA_INFO = """std_msgs/Header header
uint32 height
uint32 width
string distortion_model
float64[] d
float64[9] k
float64[9] r
float64[12] p
uint32 binning_x
uint32 binning_y
sensor_msgs/RegionOfInterest roi
""" + HEADER + """================================================================================
MSG: sensor_msgs/RegionOfInterest
uint32 x_offset
uint32 y_offset
uint32 height
uint32 width
bool do_rectify
"""

FRAME_ID = "camera_depth_optical_frame"
START_NS = 1_700_000_000 * 1_000_000_000
PERIOD_NS = 33_333_333


def read_depth_png(path):
    """A 16-bit greyscale PNG as (width, height, rows of millimetres)."""
    width, height, rows, info = png.Reader(filename=path).read()
    if info["bitdepth"] != 16 or not info["greyscale"] or info.get("alpha"):
        sys.exit(f"{path}: not a 16-bit greyscale depth image")
    return width, height, [list(r) for r in rows]


def pinhole(width, height, hfov_deg=57.0, vfov_deg=43.0):
    """fx, fy, cx, cy of a pinhole camera with these fields of view."""
    fx = (width / 2) / math.tan(math.radians(hfov_deg) / 2)
    fy = (height / 2) / math.tan(math.radians(vfov_deg) / 2)
    # Our FOV model is this pinhole with the principal point at (w/2, h/2).
    return fx, fy, width / 2, height / 2


def header(ns):
    return {
        "stamp": {"sec": ns // 1_000_000_000, "nanosec": ns % 1_000_000_000},
        "frame_id": FRAME_ID,
    }


def camera_info(ns, width, height):
    fx, fy, cx, cy = pinhole(width, height)
    return {
        "header": header(ns),
        "height": height,
        "width": width,
        "distortion_model": "plumb_bob",
        "d": [0.0] * 5,
        "k": [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0],
        "r": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        "p": [fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
        "binning_x": 0,
        "binning_y": 0,
        "roi": {"x_offset": 0, "y_offset": 0, "height": 0, "width": 0, "do_rectify": False},
    }


def image(ns, width, height, encoding, step, data):
    return {
        "header": header(ns),
        "height": height,
        "width": width,
        "encoding": encoding,
        "is_bigendian": 0,
        "step": step,
        "data": data,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("frames", nargs="+")
    ap.add_argument("--compression", choices=["zstd", "lz4", "none"], default="zstd")
    ap.add_argument("--bad-frame", type=int, default=None)
    args = ap.parse_args()
    compression = {
        "zstd": CompressionType.ZSTD,
        "lz4": CompressionType.LZ4,
        "none": CompressionType.NONE,
    }[args.compression]
    with open(args.out, "wb") as f:
        # Small chunks: every frame's messages span chunks of their own.
        w = Writer(f, chunk_size=256 * 1024, compression=compression)
        image_schema = w.register_msgdef("sensor_msgs/msg/Image", IMAGE)
        info_schema = w.register_msgdef("sensor_msgs/msg/CameraInfo", CAMERA_INFO)
        for i, path in enumerate(args.frames):
            width, height, rows = read_depth_png(path)
            ns = START_NS + i * PERIOD_NS
            mm = [v for row in rows for v in row]
            raw = struct.pack(f"<{len(mm)}H", *mm)
            if args.bad_frame == i:
                raw = raw[: -2 * width]
            metres = struct.pack(f"<{len(mm)}f", *(v / 1000.0 for v in mm))
            colour = bytes(3 * width * height)
            for topic, encoding, step, data in [
                ("/camera/depth/image_raw", "16UC1", 2 * width, raw),
                ("/camera/depth/image_float", "32FC1", 4 * width, metres),
                ("/camera/color/image_raw", "rgb8", 3 * width, colour),
            ]:
                msg = image(ns, width, height, encoding, step, data)
                w.write_message(topic, image_schema, msg, log_time=ns, publish_time=ns)
            for topic in ["/camera/depth/camera_info", "/camera/color/camera_info"]:
                w.write_message(
                    topic, info_schema, camera_info(ns, width, height), log_time=ns, publish_time=ns
                )
        w.finish()


if __name__ == "__main__":
    main()
