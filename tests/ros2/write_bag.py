#!/usr/bin/env python3
"""Write a rosbag2 recording (mcap storage, cdr serialisation) of the peer's scene.

    write_bag.py OUT_DIR --plane-z Z --seconds S [--mcap-only]

Holds /points (sensor_msgs/msg/PointCloud2, xyz32 layout, frame camera_optical) at
10 Hz and /joint_states (sensor_msgs/msg/JointState) at 50 Hz for S seconds of log
time, with the same content rmw_peer.py publishes (its message builders are reused).
Log time starts at --start-ns (default a fixed 1_700_000_000 s, so bags are
reproducible); each message's header stamp equals its log time.

With --mcap-only the bag is written to a temporary directory and only its .mcap file
is copied out, as OUT_DIR.mcap (no metadata.yaml).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
from pathlib import Path

sys.dont_write_bytecode = True  # importing rmw_peer must leave no __pycache__ in the repo
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from rosbags.rosbag2 import StoragePlugin, Writer  # noqa: E402

import rmw_peer  # noqa: E402  (same folder; message builders and type names)

BAG_VERSION = 9  # rosbags 0.11 Writer supports rosbag2 format versions 8 and 9
DEFAULT_START_NS = 1_700_000_000_000_000_000


def write_bag(out_dir: Path, plane_z: float, seconds: float, start_ns: int,
              joints: list[str], extra_joint: str | None) -> int:
    ts = rmw_peer.TYPESTORE
    count = 0
    with Writer(out_dir, version=BAG_VERSION, storage_plugin=StoragePlugin.MCAP) as writer:
        points = writer.add_connection("/points", "sensor_msgs/msg/PointCloud2", typestore=ts,
                                       serialization_format="cdr")
        joint_states = writer.add_connection("/joint_states", "sensor_msgs/msg/JointState",
                                             typestore=ts, serialization_format="cdr")
        end_ns = start_ns + int(seconds * 1e9)
        events = []
        t = start_ns
        while t < end_ns:
            events.append((t, "points"))
            t += 100_000_000  # 10 Hz
        t = start_ns
        while t < end_ns:
            events.append((t, "joints"))
            t += 20_000_000  # 50 Hz
        events.sort()
        for stamp, kind in events:
            if kind == "points":
                msg = rmw_peer.cloud_message("xyz32", plane_z, stamp_ns=stamp)
                data = ts.serialize_cdr(msg, "sensor_msgs/msg/PointCloud2")
                writer.write(points, stamp, data)
            else:
                msg = rmw_peer.joint_message(joints, extra_joint, stamp_ns=stamp)
                data = ts.serialize_cdr(msg, "sensor_msgs/msg/JointState")
                writer.write(joint_states, stamp, data)
            count += 1
    return count


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description="Write a rosbag2 (mcap) recording of the scene.")
    ap.add_argument("out_dir", metavar="OUT_DIR")
    ap.add_argument("--plane-z", type=float, default=0.0)
    ap.add_argument("--seconds", type=float, required=True)
    ap.add_argument("--mcap-only", action="store_true",
                    help="copy out just the .mcap file as OUT_DIR.mcap")
    ap.add_argument("--start-ns", type=int, default=DEFAULT_START_NS)
    ap.add_argument("--joints", default=rmw_peer.ARM_JOINTS_DEFAULT)
    ap.add_argument("--extra-joint", default="gripper_finger")
    args = ap.parse_args(argv)

    out_dir = Path(args.out_dir)
    joints = [j for j in args.joints.split(",") if j]
    if not args.mcap_only:
        n = write_bag(out_dir, args.plane_z, args.seconds, args.start_ns, joints,
                      args.extra_joint)
        print(f"wrote {n} messages to {out_dir}")
        return 0

    target = Path(str(out_dir).rstrip("/") + ".mcap")
    if target.exists():
        print(f"{target} exists already, not overwriting", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        bag = Path(tmp) / out_dir.name
        n = write_bag(bag, args.plane_z, args.seconds, args.start_ns, joints, args.extra_joint)
        mcaps = sorted(bag.glob("*.mcap"))
        if len(mcaps) != 1:
            print(f"expected one .mcap in {bag}, found {mcaps}", file=sys.stderr)
            return 1
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(mcaps[0], target)
    print(f"wrote {n} messages to {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
