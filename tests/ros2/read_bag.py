#!/usr/bin/env python3
"""Read a rosbag2 directory or a bare .mcap file with rosbags and print JSON.

    read_bag.py PATH

Prints {"path", "kind", "connections": [{"topic", "msgtype", "count", "first": summary}]},
decoding the first message of each connection (summaries as in rmw_peer.py). Exits 2
with a message on stderr if the file cannot be read.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

sys.dont_write_bytecode = True  # importing rmw_peer must leave no __pycache__ in the repo
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from rosbags.highlevel import AnyReader  # noqa: E402
from rosbags.typesys import Stores, get_typestore  # noqa: E402

import rmw_peer  # noqa: E402  (summaries only)


def read(path: Path) -> dict:
    kind = "rosbag2 directory" if path.is_dir() else "file"
    # AnyReader opens rosbag2 directories, bare .mcap files and ROS 1 bags; the typestore
    # covers bags without embedded message definitions.
    with AnyReader([path], default_typestore=get_typestore(Stores.ROS2_JAZZY)) as reader:
        out = []
        for conn in reader.connections:
            first = None
            count = 0
            for _c, timestamp, raw in reader.messages(connections=[conn]):
                if first is None:
                    msg = reader.deserialize(raw, conn.msgtype)
                    first = dict(rmw_peer.summarise(conn.msgtype, msg), log_time_ns=timestamp)
                count += 1
            out.append({"topic": conn.topic, "msgtype": conn.msgtype, "count": count,
                        "first": first})
        return {"path": str(path), "kind": kind, "connections": out,
                "start_ns": reader.start_time, "end_ns": reader.end_time}


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        print(__doc__, file=sys.stderr)
        return 2
    path = Path(argv[0])
    if not path.exists():
        print(f"read_bag: {path}: no such file or directory", file=sys.stderr)
        return 2
    try:
        result = read(path)
    except Exception as err:  # noqa: BLE001 - any failure to read is the answer
        print(f"read_bag: cannot read {path}: {type(err).__name__}: {err}", file=sys.stderr)
        return 2
    print(json.dumps(result, indent=2, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())
