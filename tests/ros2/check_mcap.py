#!/usr/bin/env python3
"""Read rover-terrain's `--mcap` output back with the Python `mcap` readers and check it.

    python3 tests/ros2/check_mcap.py OUT.mcap INSPECT_DIR

OUT.mcap is what `rover-terrain inspect INPUT --out INSPECT_DIR --mcap OUT.mcap`
wrote. Checks, failing with a message on the first miss:
- every documented channel is there with its schema, schema encoding and message
  encoding, and each has one message per frame inspected (the frame-* directories);
- the ROS 2 messages decode (mcap-ros2-support): 16UC1 depth images of the frame size
  with a CameraInfo whose K is a pinhole, in the configured camera frame;
- the verdicts are JSON objects with a verdict and the frame's number, in order;
- each frame's point cloud (foxglove.PointCloud, decoded with mcap-protobuf-support)
  holds exactly the points of that frame's cloud.pcd, in order, with the same colours;
- the grid has one cell per ground cell, the transform links base_link to the camera.

Needs: pip install mcap mcap-ros2-support mcap-protobuf-support
"""

import json
import os
import struct
import sys

from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory as ProtobufDecoders
from mcap_ros2.decoder import DecoderFactory as Ros2Decoders

CHANNELS = {
    "/camera/depth/image_raw": ("sensor_msgs/msg/Image", "ros2msg", "cdr"),
    "/camera/depth/camera_info": ("sensor_msgs/msg/CameraInfo", "ros2msg", "cdr"),
    "/rover_terrain/verdict": ("rover_terrain.Verdict", "jsonschema", "json"),
    "/rover_terrain/cloud": ("foxglove.PointCloud", "protobuf", "protobuf"),
    "/rover_terrain/grid": ("foxglove.Grid", "protobuf", "protobuf"),
    "/rover_terrain/scene": ("foxglove.SceneUpdate", "protobuf", "protobuf"),
    "/tf": ("foxglove.FrameTransform", "protobuf", "protobuf"),
}


def fail(why):
    sys.exit(f"check_mcap: {why}")


def read_pcd(path):
    """The points of a binary PCD with fields x y z rgb: [(x, y, z, (r, g, b))]."""
    with open(path, "rb") as f:
        data = f.read()
    head_end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
    header = data[:head_end].decode()
    n = int(next(l for l in header.splitlines() if l.startswith("POINTS")).split()[1])
    points = []
    for i in range(n):
        x, y, z, rgb = struct.unpack_from("<fffI", data, head_end + 16 * i)
        points.append((x, y, z, ((rgb >> 16) & 255, (rgb >> 8) & 255, rgb & 255)))
    return points


def cloud_points(msg):
    fields = {f.name: f.offset for f in msg.fields}
    for name, offset in [("x", 0), ("y", 4), ("z", 8), ("red", 12), ("green", 13), ("blue", 14)]:
        if fields.get(name) != offset:
            fail(f"point cloud field {name} at {fields.get(name)}, expected {offset}")
    data, stride = bytes(msg.data), msg.point_stride
    out = []
    for i in range(len(data) // stride):
        x, y, z = struct.unpack_from("<fff", data, i * stride)
        out.append((x, y, z, tuple(data[i * stride + 12 : i * stride + 15])))
    return out


def main():
    path, inspect_dir = sys.argv[1], sys.argv[2]
    frames = sorted(d for d in os.listdir(inspect_dir) if d.startswith("frame-"))
    if not frames:
        fail(f"no frame-* directories in {inspect_dir}")
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[Ros2Decoders(), ProtobufDecoders()])
        summary = reader.get_summary()
        by_topic = {c.topic: c for c in summary.channels.values()}
        if set(by_topic) != set(CHANNELS):
            fail(f"channels {sorted(by_topic)}, expected {sorted(CHANNELS)}")
        for topic, (schema, schema_enc, msg_enc) in CHANNELS.items():
            c = by_topic[topic]
            s = summary.schemas[c.schema_id]
            if (s.name, s.encoding, c.message_encoding) != (schema, schema_enc, msg_enc):
                fail(f"{topic}: {(s.name, s.encoding, c.message_encoding)}")
            count = summary.statistics.channel_message_counts[c.id]
            if count != len(frames):
                fail(f"{topic}: {count} messages, expected {len(frames)} (one per frame)")
        msgs = {t: [] for t in CHANNELS}
        for schema, channel, message, decoded in reader.iter_decoded_messages(
            topics=[t for t in CHANNELS if t != "/rover_terrain/verdict"]
        ):
            msgs[channel.topic].append(decoded)
        for _, channel, message in reader.iter_messages(topics=["/rover_terrain/verdict"]):
            msgs[channel.topic].append(json.loads(message.data))
    for i, (img, info) in enumerate(zip(msgs["/camera/depth/image_raw"], msgs["/camera/depth/camera_info"])):
        if img.encoding != "16UC1" or len(img.data) != img.height * img.step:
            fail(f"depth image {i}: {img.encoding} {img.width}x{img.height} step {img.step}")
        if (info.width, info.height) != (img.width, img.height) or not info.k[0] > 0:
            fail(f"camera info {i}: {info.width}x{info.height} K {list(info.k)}")
        if img.header.frame_id != info.header.frame_id:
            fail(f"frame ids differ: {img.header.frame_id} {info.header.frame_id}")
    for i, v in enumerate(msgs["/rover_terrain/verdict"]):
        if v.get("verdict") not in ("go", "stop", "unknown") or v.get("frame") != i:
            fail(f"verdict {i}: {v}")
    for i, (frame, cloud) in enumerate(zip(frames, msgs["/rover_terrain/cloud"])):
        want = read_pcd(os.path.join(inspect_dir, frame, "cloud.pcd"))
        got = cloud_points(cloud)
        if got != want:
            fail(f"{frame}: point cloud has {len(got)} points, cloud.pcd {len(want)}; "
                 f"first difference at {next((j for j, (a, b) in enumerate(zip(got, want)) if a != b), None)}")
    for i, g in enumerate(msgs["/rover_terrain/grid"]):
        if g.column_count == 0 or len(g.data) % g.row_stride or g.cell_stride * g.column_count != g.row_stride:
            fail(f"grid {i}: {g.column_count} columns, stride {g.row_stride}/{g.cell_stride}")
    for tf in msgs["/tf"]:
        if tf.parent_frame_id != "base_link" or tf.child_frame_id != img.header.frame_id:
            fail(f"transform {tf.parent_frame_id} -> {tf.child_frame_id}")
    for s in msgs["/rover_terrain/scene"]:
        if len(s.entities) != 1 or not s.entities[0].texts:
            fail(f"scene update without its entity: {s}")
    print(f"check_mcap: {path}: {len(frames)} frames, {len(CHANNELS)} channels, clouds equal to cloud.pcd")


if __name__ == "__main__":
    main()
