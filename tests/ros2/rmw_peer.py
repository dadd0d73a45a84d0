#!/usr/bin/env python3
"""A ROS 2 node speaking rmw_zenoh's wire contract, without ROS.

Plays the ROS side of shroud's `ros2` bridge node: it publishes PointCloud2 on
/points and JointState on /joint_states, subscribes to shroud's outputs, decodes
what arrives with rosbags, and queries the liveliness graph the way
rmw_zenoh's graph cache reads it. Writes a JSON report.

Nothing here is imported from shroud. Every key, token, QoS string and type hash
is a literal copied from the rmw_zenoh sources (ros2/rmw_zenoh, files and commits
cited beside each) or computed once with rosbags 0.11.9 `Typestore.hash_rihs01`
and pasted. The pinned packages are in requirements.txt next to this file.
"""

from __future__ import annotations

import argparse
import functools
import hashlib
import json
import math
import os
import struct
import sys
import threading
import time
import traceback
from typing import Any

import numpy as np
import zenoh
import zenoh.ext
from rosbags.typesys import Stores, get_typestore

# ---------------------------------------------------------------------------
# Literals (sources cited)
# ---------------------------------------------------------------------------

# rmw_zenoh_cpp/src/detail/liveliness_utils.cpp@3411fdec: ADMIN_SPACE, entity strings,
# SLASH_REPLACEMENT '%', QOS_DELIMITER ':', QOS_COMPONENT_DELIMITER ','.
ADMIN_SPACE = "@ros2_lv"
KIND_NODE, KIND_PUB, KIND_SUB, KIND_SRV, KIND_CLI = "NN", "MP", "MS", "SS", "SC"
KINDS = {KIND_NODE, KIND_PUB, KIND_SUB, KIND_SRV, KIND_CLI}

# DDS type names as rmw_zenoh's MessageTypeSupport::get_name() gives them
# ("<pkg>::msg::dds_::<Type>_"; docs/design.md@99a6a2bd, ros2.md).
DDS_NAME = {
    "sensor_msgs/msg/PointCloud2": "sensor_msgs::msg::dds_::PointCloud2_",
    "sensor_msgs/msg/JointState": "sensor_msgs::msg::dds_::JointState_",
    "visualization_msgs/msg/MarkerArray": "visualization_msgs::msg::dds_::MarkerArray_",
    "diagnostic_msgs/msg/DiagnosticStatus": "diagnostic_msgs::msg::dds_::DiagnosticStatus_",
    "std_msgs/msg/Float64": "std_msgs::msg::dds_::Float64_",
    "tf2_msgs/msg/TFMessage": "tf2_msgs::msg::dds_::TFMessage_",
}

# RIHS01 type hashes: rosbags 0.11.9 `get_typestore(Stores.ROS2_JAZZY).hash_rihs01(name)`
# (identical for the HUMBLE and KILTED stores). PointCloud2, JointState, TFMessage and
# Float64 also appear verbatim in `ros2 topic info -v` output / generated code in public
# repositories; DiagnosticStatus and MarkerArray were matched by one other project each.
TYPE_HASH = {
    "sensor_msgs/msg/PointCloud2":
        "RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5",
    "sensor_msgs/msg/JointState":
        "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e",
    "visualization_msgs/msg/MarkerArray":
        "RIHS01_86cb8800b6fb05b5eff1abd7a56f62a5641d3ae9a1c29e78e67e704f1d067dcf",
    "diagnostic_msgs/msg/DiagnosticStatus":
        "RIHS01_b0e3e692ea2d54a8af2f4ef1930e81556a2db55216b771f8a7d2724ed47bf0e4",
    "std_msgs/msg/Float64":
        "RIHS01_705ba9c3d1a09df43737eb67095534de36fd426c0587779bda2bc51fe790182a",
    "tf2_msgs/msg/TFMessage":
        "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087",
}

# QoS segments, format of qos_to_keyexpr() (liveliness_utils.cpp@3411fdec):
#   <reliability>:<durability>:<history>,<depth>:<deadline s>,<ns>:<lifespan s>,<ns>:<liveliness>,<lease s>,<ns>
# rmw enums (rmw/types.h): reliability RELIABLE=1 BEST_EFFORT=2; durability
# TRANSIENT_LOCAL=1 VOLATILE=2; history KEEP_LAST=1 KEEP_ALL=2. An empty field means
# "rmw_zenoh's default" (qos.cpp@7efeee2b: deadline/lifespan/lease infinite, liveliness
# AUTOMATIC), which rmw_zenoh itself writes for those. Reliability, durability, history
# and depth are written explicitly because the default durability changed
# (TRANSIENT_LOCAL before rmw_zenoh #521, VOLATILE after).
QOS_SENSOR = "2:2:1,5:,:,:,,"          # rclcpp SensorDataQoS: best effort, volatile, keep last 5
QOS_RELIABLE = "1:2:1,10:,:,:,,"       # rclcpp default QoS: reliable, volatile, keep last 10
QOS_TF_STATIC = "1:1:1,100:,:,:,,"     # tf2_ros StaticListenerQoS: reliable, transient local, 100

NODE_NAME = "rmw_peer"

# Attachment (attachment_helpers.cpp@534747dc, AttachmentData::serialize_to_zbytes):
# zenoh-ext serialisation of (int64 sequence_number, int64 source_timestamp,
# std::array<uint8_t,16> gid): i64 LE | i64 LE | LEB128 length 0x10 | 16 bytes = 33 bytes.
ATTACHMENT_LEN = 33
ATTACHMENT_GID_LEN_BYTE = 0x10

ARM_JOINTS_DEFAULT = "shoulder_pan,shoulder_lift,elbow,wrist_1,wrist_2,wrist_3"

# PointField datatypes (sensor_msgs/msg/PointField).
PF_FLOAT32 = 7
PF_FLOAT64 = 8

# Scene / camera.
# Dense enough for shroud's 20 x 20 fit of the plane: a trimmed surrogate
# keeps only triangles that hold a point, so points must be closer than about
# a third of a cell (4 m / 20 / 3.4 = 0.058 m); 128 x 96 rays at 3 m are
# 0.047 m apart.
CAM_W, CAM_H = 128, 96
CAM_HEIGHT = 3.0
HFOV_HALF_TAN = math.tan(math.radians(45.0))
VFOV_HALF_TAN = math.tan(math.radians(35.0))
PLANE_HALF_SIDE = 2.0
# A block of rays without a return, in a corner of the image: a black object
# off to the side of the arm (which hangs on the optical axis).
NAN_ROWS = range(70, 90)
NAN_COLS = range(90, 120)

# Infinite duration (RMW_DURATION_INFINITE, rmw/time.h): rmw_zenoh's default for
# deadline, lifespan and liveliness lease (qos.cpp@7efeee2b).
DURATION_INFINITE = (9223372036, 854775807)


def topic_key(domain: int, topic: str, ros_type: str) -> str:
    """`<domain>/<topic without leading/trailing '/'>/<dds type>/<type hash>`.

    liveliness_utils.cpp@3411fdec, TopicInfo::TopicInfo (strip_slashes strips one
    leading and one trailing '/').
    """
    name = topic
    if name.startswith("/"):
        name = name[1:]
    if name.endswith("/"):
        name = name[:-1]
    return f"{domain}/{name}/{DDS_NAME[ros_type]}/{TYPE_HASH[ros_type]}"


def mangle(name: str) -> str:
    """liveliness_utils.cpp@3411fdec mangle_name(): every '/' becomes '%'."""
    return name.replace("/", "%")


def demangle(name: str) -> str:
    """liveliness_utils.cpp@3411fdec demangle_name(): every '%' becomes '/'."""
    return name.replace("%", "/")


def node_token(domain: int, zid: str, node_id: int) -> str:
    # <ADMIN>/<domain>/<zid>/<nid>/<id>/NN/<enclave>/<namespace>/<node>; a node's entity
    # id is its node id (rmw_node_data.cpp@3411fdec); enclave "/" and namespace "/"
    # both mangle to "%".
    return f"{ADMIN_SPACE}/{domain}/{zid}/{node_id}/{node_id}/{KIND_NODE}/%/%/{NODE_NAME}"


def endpoint_token(domain: int, zid: str, node_id: int, entity_id: int, kind: str,
                   topic: str, ros_type: str, qos: str) -> str:
    return (f"{ADMIN_SPACE}/{domain}/{zid}/{node_id}/{entity_id}/{kind}/%/%/{NODE_NAME}/"
            f"{mangle(topic)}/{mangle(DDS_NAME[ros_type])}/{mangle(TYPE_HASH[ros_type])}/{qos}")


def gid_for(token: str) -> bytes:
    """A stable 16-byte gid per entity. rmw_zenoh uses XXH3-128 of the token
    (liveliness_utils.cpp@3411fdec, Entity::Entity); subscribers only use the gid as a
    map key (rmw_subscription_data.cpp@a72659a6), so any stable 16 bytes do."""
    return hashlib.sha256(token.encode()).digest()[:16]


def make_attachment(seq: int, ts_ns: int, gid: bytes) -> bytes:
    assert len(gid) == 16
    return struct.pack("<qq", seq, ts_ns) + bytes([ATTACHMENT_GID_LEN_BYTE]) + gid


def parse_attachment(raw: bytes | None) -> tuple[dict | None, str | None]:
    if raw is None:
        return None, "missing"
    if len(raw) != ATTACHMENT_LEN:
        return None, f"length {len(raw)} != 33"
    if raw[16] != ATTACHMENT_GID_LEN_BYTE:
        return None, f"byte 16 is 0x{raw[16]:02x}, not 0x10"
    seq, ts = struct.unpack_from("<qq", raw, 0)
    return {"seq": seq, "ts": ts, "gid": raw[17:33].hex()}, None


# ---------------------------------------------------------------------------
# Liveliness token parsing: a port of rmw_zenoh's Entity::make(const std::string&)
# and keyexpr_to_qos() (rmw_zenoh_cpp/src/detail/liveliness_utils.cpp@3411fdec), used by
# GraphCache::parse_put (graph_cache.cpp@49db0109), which drops a token Entity::make rejects.
# ---------------------------------------------------------------------------

# KeyexprIndex enum: AdminSpace 0, DomainId 1, Zid 2, Nid 3, Id 4, EntityStr 5,
# Enclave 6, Namespace 7, NodeName 8, TopicName 9, TopicType 10, TopicTypeHash 11, TopicQoS 12.
IDX_NODE_NAME = 8
IDX_TOPIC_QOS = 12

# str_to_qos_* maps (only these strings are accepted; rmw/types.h enum values).
QOS_HISTORY = {"0": "system_default", "1": "keep_last", "2": "keep_all", "3": "unknown"}
QOS_RELIABILITY = {"0": "system_default", "1": "reliable", "2": "best_effort", "3": "unknown"}
QOS_DURABILITY = {"0": "system_default", "1": "transient_local", "2": "volatile", "3": "unknown"}
QOS_LIVELINESS = {"0": "system_default", "1": "automatic", "3": "manual_by_topic",
                  "4": "unknown", "5": "best_available"}
# Defaults (qos.cpp@7efeee2b; durability default is VOLATILE since rmw_zenoh #521).
QOS_DEFAULTS = {"history": "keep_last", "depth": 42, "reliability": "reliable",
                "durability": "volatile", "liveliness": "automatic"}


def _str_to_size_t(text: str, default: int) -> int | None:
    """str_to_size_t(): empty -> default; otherwise strtoul must consume every char."""
    if text == "":
        return default
    body = text.lstrip(" \t\n\r\f\v")
    if body[:1] in "+-":
        body = body[1:]
    if not body.isdigit() or not body.isascii():
        return None
    value = int(text.strip())
    if value < 0:  # strtoul wraps a negative number
        value &= (1 << 64) - 1
    if value >= 1 << 64:
        return None  # ERANGE
    return value


def keyexpr_to_qos(segment: str) -> tuple[dict | None, str | None]:
    parts = segment.split(":")
    if len(parts) < 6:
        return None, f"qos has {len(parts)} ':' parts, needs 6"
    history = parts[2].split(",")
    if len(history) < 2:
        return None, "qos history needs 2 ',' parts"
    deadline = parts[3].split(",")
    if len(deadline) < 2:
        return None, "qos deadline needs 2 ',' parts"
    lifespan = parts[4].split(",")
    if len(lifespan) < 2:
        return None, "qos lifespan needs 2 ',' parts"
    liveliness = parts[5].split(",")
    if len(liveliness) < 3:
        return None, "qos liveliness needs 3 ',' parts"
    try:
        qos: dict[str, Any] = {
            "history": QOS_DEFAULTS["history"] if history[0] == "" else QOS_HISTORY[history[0]],
            "reliability": QOS_DEFAULTS["reliability"] if parts[0] == ""
            else QOS_RELIABILITY[parts[0]],
            "durability": QOS_DEFAULTS["durability"] if parts[1] == ""
            else QOS_DURABILITY[parts[1]],
            "liveliness": QOS_DEFAULTS["liveliness"] if liveliness[0] == ""
            else QOS_LIVELINESS[liveliness[0]],
        }
    except KeyError as err:
        return None, f"qos value {err} not in rmw_zenoh's map"
    numbers = {
        "depth": _str_to_size_t(history[1], QOS_DEFAULTS["depth"]),
        "deadline_s": _str_to_size_t(deadline[0], DURATION_INFINITE[0]),
        "deadline_ns": _str_to_size_t(deadline[1], DURATION_INFINITE[1]),
        "lifespan_s": _str_to_size_t(lifespan[0], DURATION_INFINITE[0]),
        "lifespan_ns": _str_to_size_t(lifespan[1], DURATION_INFINITE[1]),
        "lease_s": _str_to_size_t(liveliness[1], DURATION_INFINITE[0]),
        "lease_ns": _str_to_size_t(liveliness[2], DURATION_INFINITE[1]),
    }
    for key, value in numbers.items():
        if value is None:
            return None, f"qos {key} is not a number"
    qos.update(numbers)
    return qos, None


def demangle_if_ros_type(dds_type: str) -> str:
    """graph_cache.cpp: `_demangle_if_ros_type` reports `pkg::msg::dds_::Type_` as
    `pkg/msg/Type`."""
    marker = "::dds_::"
    pos = dds_type.find(marker)
    if pos < 0 or not dds_type.endswith("_"):
        return dds_type
    prefix = dds_type[:pos].replace("::", "/")
    name = dds_type[pos + len(marker):-1]
    return f"{prefix}/{name}"


def parse_token(keyexpr: str) -> tuple[dict | None, str | None]:
    parts = keyexpr.split("/")
    if len(parts) < IDX_NODE_NAME + 1:
        return None, f"{len(parts)}/{IDX_NODE_NAME + 1} parts"
    if any(p == "" for p in parts):
        return None, "empty part"
    if parts[0] != ADMIN_SPACE:
        return None, "invalid admin space"
    kind = parts[5]
    if kind not in KINDS:
        return None, f"invalid entity {kind}"
    try:
        domain = int(parts[1])  # std::stoul; a non-number throws in rmw_zenoh
    except ValueError:
        return None, "domain id is not a number (std::stoul would throw)"
    entity: dict[str, Any] = {
        "kind": kind, "domain": domain, "zid": parts[2], "nid": parts[3], "id": parts[4],
        "enclave": demangle(parts[6]), "namespace": demangle(parts[7]),
        "node": demangle(parts[8]),
    }
    if kind != KIND_NODE:
        if len(parts) < IDX_TOPIC_QOS + 1:
            return None, "non-node entity without required parameters (needs 13 parts)"
        qos, why = keyexpr_to_qos(parts[IDX_TOPIC_QOS])
        if qos is None:
            return None, f"invalid qos keyexpr: {why}"
        dds_type = demangle(parts[10])
        entity.update({
            "topic": demangle(parts[9]), "dds_type": dds_type,
            "type": demangle_if_ros_type(dds_type), "type_hash": demangle(parts[11]),
            "qos": qos, "qos_segment": parts[IDX_TOPIC_QOS],
        })
    return entity, None


def build_graph(keys: list[str]) -> dict:
    nodes: dict[tuple, dict] = {}
    publishers, subscriptions, services, clients, rejected = [], [], [], [], []
    for key in sorted(set(keys)):
        entity, why = parse_token(key)
        if entity is None:
            rejected.append({"token": key, "reason": why})
            continue
        # GraphCache::parse_put: any entity's token puts its node in the graph; nodes
        # are told apart by (namespace, name, zid, nid).
        node_key = (entity["domain"], entity["namespace"], entity["node"], entity["zid"],
                    entity["nid"])
        node = nodes.setdefault(node_key, {
            "name": entity["node"], "namespace": entity["namespace"],
            "enclave": entity["enclave"], "zid": entity["zid"], "nid": entity["nid"],
            "domain": entity["domain"], "has_NN_token": False,
        })
        if entity["kind"] == KIND_NODE:
            node["has_NN_token"] = True
            continue
        row = {k: entity[k] for k in ("topic", "type", "dds_type", "type_hash", "qos_segment",
                                      "qos", "node", "namespace", "zid", "nid", "id")}
        {KIND_PUB: publishers, KIND_SUB: subscriptions, KIND_SRV: services,
         KIND_CLI: clients}[entity["kind"]].append(row)
    return {"nodes": list(nodes.values()), "publishers": publishers,
            "subscriptions": subscriptions, "services": services, "clients": clients,
            "rejected": rejected, "tokens": sorted(set(keys))}


# ---------------------------------------------------------------------------
# Messages
# ---------------------------------------------------------------------------

TYPESTORE = get_typestore(Stores.ROS2_JAZZY)
Time = TYPESTORE.types["builtin_interfaces/msg/Time"]
Header = TYPESTORE.types["std_msgs/msg/Header"]
PointField = TYPESTORE.types["sensor_msgs/msg/PointField"]
PointCloud2 = TYPESTORE.types["sensor_msgs/msg/PointCloud2"]
JointState = TYPESTORE.types["sensor_msgs/msg/JointState"]


def stamp_now(now_ns: int | None = None) -> Any:
    now = time.time_ns() if now_ns is None else now_ns
    return Time(sec=now // 1_000_000_000, nanosec=now % 1_000_000_000)


def scene_points(plane_z: float) -> list[list[tuple[float, float, float] | None]]:
    """Per pixel (row, col) the plane point in the camera's optical frame, or None.

    Camera at world (0, 0, CAM_HEIGHT); optical frame = world rotated 180 deg about x
    (quaternion x=1, y=0, z=0, w=0), so an optical direction (dx, dy, 1) is the world
    direction (dx, -dy, -1).
    """
    grid: list[list[tuple[float, float, float] | None]] = []
    depth = CAM_HEIGHT - plane_z  # distance along the optical axis to the plane
    for r in range(CAM_H):
        row: list[tuple[float, float, float] | None] = []
        dy = (r + 0.5 - CAM_H / 2) / (CAM_H / 2) * VFOV_HALF_TAN
        for c in range(CAM_W):
            dx = (c + 0.5 - CAM_W / 2) / (CAM_W / 2) * HFOV_HALF_TAN
            if depth <= 0:
                row.append(None)
                continue
            wx, wy = depth * dx, -depth * dy
            if abs(wx) > PLANE_HALF_SIDE or abs(wy) > PLANE_HALF_SIDE:
                row.append(None)
                continue
            row.append((depth * dx, depth * dy, depth))
        grid.append(row)
    return grid


def cloud_message(layout: str, plane_z: float, frame_id: str = "camera_optical",
                  stamp_ns: int | None = None) -> Any:
    fields, step, data, height, width, big_endian, dense = cloud_body(layout, plane_z)
    return PointCloud2(
        header=Header(stamp=stamp_now(stamp_ns), frame_id=frame_id),
        height=height, width=width, fields=fields, is_bigendian=big_endian,
        point_step=step, row_step=step * width,
        data=np.frombuffer(data, dtype=np.uint8), is_dense=dense)


@functools.lru_cache(maxsize=16)
def cloud_body(layout: str, plane_z: float) -> tuple:
    """Everything of a cloud but its header, built once per layout and plane."""
    grid = scene_points(plane_z)
    f32 = lambda name, off: PointField(name=name, offset=off, datatype=PF_FLOAT32, count=1)  # noqa: E731
    big_endian = False
    dense = True
    if layout in ("xyz32", "big_endian"):
        fields = [f32("x", 0), f32("y", 4), f32("z", 8)]
        step = 12
        big_endian = layout == "big_endian"
        fmt = (">" if big_endian else "<") + "fff"
        pts = [p for row in grid for p in row if p is not None]
        data = b"".join(struct.pack(fmt, *p) for p in pts)
        height, width = 1, len(pts)
    elif layout == "xyzi_padded":
        # PCL PointXYZI: x y z at 0 4 8, padding 12..16, intensity at 16, padded to 32.
        fields = [f32("x", 0), f32("y", 4), f32("z", 8), f32("intensity", 16)]
        step = 32
        pts = [p for row in grid for p in row if p is not None]
        data = b"".join(struct.pack("<fff4xf12x", *p, 100.0) for p in pts)
        height, width = 1, len(pts)
    elif layout == "xyz64":
        fields = [PointField(name=n, offset=o, datatype=PF_FLOAT64, count=1)
                  for n, o in (("x", 0), ("y", 8), ("z", 16))]
        step = 24
        pts = [p for row in grid for p in row if p is not None]
        data = b"".join(struct.pack("<ddd", *p) for p in pts)
        height, width = 1, len(pts)
    elif layout == "organised_nan":
        fields = [f32("x", 0), f32("y", 4), f32("z", 8)]
        step = 12
        dense = False
        nan = (math.nan, math.nan, math.nan)
        out = []
        for r in range(CAM_H):
            for c in range(CAM_W):
                p = grid[r][c]
                if p is None or (r in NAN_ROWS and c in NAN_COLS):
                    p = nan
                out.append(struct.pack("<fff", *p))
        data = b"".join(out)
        height, width = CAM_H, CAM_W
    else:
        raise ValueError(f"unknown layout {layout}")
    return fields, step, data, height, width, big_endian, dense


def joint_message(names: list[str], extra: str | None, stamp_ns: int | None = None) -> Any:
    out_names = list(reversed(names))
    positions = [0.0] * len(out_names)
    if extra:
        out_names.append(extra)
        positions.append(0.01)
    return JointState(
        header=Header(stamp=stamp_now(stamp_ns), frame_id=""), name=out_names,
        position=np.array(positions, dtype=np.float64),
        velocity=np.zeros(len(out_names), dtype=np.float64),
        effort=np.zeros(0, dtype=np.float64))


def serialize(msg: Any, ros_type: str) -> bytes:
    return bytes(TYPESTORE.serialize_cdr(msg, ros_type))


# ---------------------------------------------------------------------------
# Summaries of received messages
# ---------------------------------------------------------------------------

def _frame(header: Any) -> str:
    return header.frame_id


def summarise(ros_type: str, msg: Any) -> dict:
    if ros_type == "sensor_msgs/msg/PointCloud2":
        summary = {
            "frame_id": _frame(msg.header), "width": msg.width, "height": msg.height,
            "fields": [{"name": f.name, "offset": f.offset, "datatype": f.datatype,
                        "count": f.count} for f in msg.fields],
            "point_step": msg.point_step, "row_step": msg.row_step,
            "is_bigendian": bool(msg.is_bigendian), "is_dense": bool(msg.is_dense),
            "point_count": msg.width * msg.height, "data_len": len(msg.data),
        }
        summary.update(_cloud_finiteness(msg))
        return summary
    if ros_type == "visualization_msgs/msg/MarkerArray":
        return {"markers": [{
            "ns": m.ns, "id": m.id, "type": m.type, "action": m.action,
            "frame_id": _frame(m.header), "points": len(m.points), "colors": len(m.colors),
        } for m in msg.markers]}
    if ros_type == "diagnostic_msgs/msg/DiagnosticStatus":
        level = msg.level
        if isinstance(level, (bytes, bytearray)):
            level = level[0]
        return {"level": int(level), "name": msg.name, "message": msg.message,
                "hardware_id": msg.hardware_id,
                "values": {kv.key: kv.value for kv in msg.values}}
    if ros_type == "std_msgs/msg/Float64":
        return {"data": float(msg.data)}
    if ros_type == "tf2_msgs/msg/TFMessage":
        return {"frames": [f"{t.header.frame_id}->{t.child_frame_id}" for t in msg.transforms]}
    if ros_type == "sensor_msgs/msg/JointState":
        return {"names": list(msg.name), "position": [float(x) for x in msg.position]}
    return {}


def _cloud_finiteness(msg: Any) -> dict:
    offs = {f.name: (f.offset, f.datatype) for f in msg.fields}
    if not all(k in offs for k in ("x", "y", "z")):
        return {"finite_points": None, "note": "no x/y/z fields"}
    n = msg.width * msg.height
    step = msg.point_step
    data = bytes(msg.data)
    if len(data) < n * step or step == 0:
        return {"finite_points": None, "note": "data shorter than width*height*point_step"}
    endian = ">" if msg.is_bigendian else "<"
    finite = 0
    for i in range(n):
        base = i * step
        ok = True
        for k in ("x", "y", "z"):
            off, dt = offs[k]
            if dt == PF_FLOAT32:
                v = struct.unpack_from(endian + "f", data, base + off)[0]
            elif dt == PF_FLOAT64:
                v = struct.unpack_from(endian + "d", data, base + off)[0]
            else:
                return {"finite_points": None, "note": f"datatype {dt}"}
            ok = ok and math.isfinite(v)
        finite += ok
    return {"finite_points": finite, "all_finite": finite == n}


# ---------------------------------------------------------------------------
# The node
# ---------------------------------------------------------------------------

SUBSCRIBED = [
    ("/shroud/cloud/camera", "sensor_msgs/msg/PointCloud2", QOS_SENSOR),
    ("/shroud/surrogates", "visualization_msgs/msg/MarkerArray", QOS_RELIABLE),
    ("/shroud/arm_clearance", "visualization_msgs/msg/MarkerArray", QOS_RELIABLE),
    ("/shroud/verdict", "diagnostic_msgs/msg/DiagnosticStatus", QOS_RELIABLE),
    ("/shroud/speed_scale", "std_msgs/msg/Float64", QOS_RELIABLE),
    ("/tf_static", "tf2_msgs/msg/TFMessage", QOS_TF_STATIC),
]


class TopicStats:
    def __init__(self, ros_type: str) -> None:
        self.ros_type = ros_type
        self.count = 0
        self.bad_attachment = 0
        self.bad_attachment_reasons: dict[str, int] = {}
        self.out_of_order = 0
        self.undecodable = 0
        self.last_seq: dict[str, int] = {}
        self.first: list[dict] = []
        self.last: list[dict] = []

    def to_json(self) -> dict:
        samples = self.first + [s for s in self.last if s not in self.first]
        return {"type": self.ros_type, "count": self.count,
                "bad_attachment": self.bad_attachment,
                "bad_attachment_reasons": self.bad_attachment_reasons,
                "sequence_not_increasing": self.out_of_order,
                "undecodable": self.undecodable, "samples": samples}


class Peer:
    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.domain = args.domain
        self.lock = threading.Lock()
        self.stats = {topic: TopicStats(t) for topic, t, _ in SUBSCRIBED}
        self.exact_keys = {topic_key(self.domain, topic, t): topic for topic, t, _ in SUBSCRIBED}
        self.other_hash = 0
        self.other_keys: dict[str, int] = {}
        self.published: dict[str, int] = {"/points": 0, "/joint_states": 0}
        self.malformed: dict[str, int] = {}
        self.errors: list[str] = []

        conf = zenoh.Config()
        conf.insert_json5("mode", json.dumps("peer"))
        conf.insert_json5("connect/endpoints", json.dumps(list(args.connect)))
        conf.insert_json5("listen/endpoints", json.dumps(list(args.listen)))
        conf.insert_json5("scouting/multicast/enabled", "false")
        self.session = zenoh.open(conf)
        self.zid = str(self.session.zid())

    # -- declarations -------------------------------------------------------
    def declare(self) -> None:
        s, d, z = self.session, self.domain, self.zid
        self.tokens = [s.liveliness().declare_token(node_token(d, z, 0))]
        # Publishers. Mapping as rmw_publisher_data.cpp@3e19ec73: reliability from QoS,
        # congestion control DROP unless RELIABLE + KEEP_ALL.
        self.pubs: dict[str, dict] = {}
        plan = [("/points", "sensor_msgs/msg/PointCloud2", QOS_SENSOR,
                 zenoh.Reliability.BEST_EFFORT),
                ("/joint_states", "sensor_msgs/msg/JointState", QOS_RELIABLE,
                 zenoh.Reliability.RELIABLE)]
        entity_id = 1
        for topic, ros_type, qos, rel in plan:
            token = endpoint_token(d, z, 0, entity_id, KIND_PUB, topic, ros_type, qos)
            pub = s.declare_publisher(topic_key(d, topic, ros_type), reliability=rel,
                                      congestion_control=zenoh.CongestionControl.DROP)
            self.tokens.append(s.liveliness().declare_token(token))
            self.pubs[topic] = {"pub": pub, "type": ros_type, "gid": gid_for(token), "seq": 1,
                                "key": topic_key(d, topic, ros_type), "token": token}
            entity_id += 1
        # Subscriptions on the exact keys (rmw_subscription_data.cpp@a72659a6 subscribes to
        # topic_keyexpr_, no wildcard), plus a catch-all to count other hashes.
        self.subs = []
        for topic, ros_type, qos in SUBSCRIBED:
            key = topic_key(d, topic, ros_type)
            token = endpoint_token(d, z, 0, entity_id, KIND_SUB, topic, ros_type, qos)
            cb = self._make_callback(topic, ros_type)
            if qos == QOS_TF_STATIC:
                # TRANSIENT_LOCAL subscription: an AdvancedSubscriber that detects late
                # publishers and queries their cache, as rmw_zenoh does.
                sub = zenoh.ext.declare_advanced_subscriber(
                    s, key, cb,
                    history=zenoh.ext.HistoryConfig(detect_late_publishers=True,
                                                    max_samples=100),
                    subscriber_detection=True)
            else:
                sub = s.declare_subscriber(key, cb)
            self.subs.append(sub)
            self.tokens.append(s.liveliness().declare_token(token))
            entity_id += 1
        for wild in (f"{d}/shroud/**", f"{d}/tf_static/**"):
            self.subs.append(s.declare_subscriber(wild, self._on_any))

    def _on_any(self, sample: zenoh.Sample) -> None:
        key = str(sample.key_expr)
        if key in self.exact_keys:
            return
        with self.lock:
            self.other_hash += 1
            self.other_keys[key] = self.other_keys.get(key, 0) + 1

    def _make_callback(self, topic: str, ros_type: str):
        def on_sample(sample: zenoh.Sample) -> None:
            try:
                self._on_sample(topic, ros_type, sample)
            except Exception:  # noqa: BLE001 - a callback must not die silently
                with self.lock:
                    self.errors.append(traceback.format_exc())
        return on_sample

    def _on_sample(self, topic: str, ros_type: str, sample: zenoh.Sample) -> None:
        raw_att = sample.attachment.to_bytes() if sample.attachment is not None else None
        payload = sample.payload.to_bytes()
        att, why = parse_attachment(raw_att)
        try:
            msg = TYPESTORE.deserialize_cdr(payload, ros_type)
            summary: dict | None = summarise(ros_type, msg)
        except Exception as err:  # noqa: BLE001
            summary = None
            decode_error = f"{type(err).__name__}: {err}"
        with self.lock:
            st = self.stats[topic]
            st.count += 1
            if att is None:
                st.bad_attachment += 1
                st.bad_attachment_reasons[why] = st.bad_attachment_reasons.get(why, 0) + 1
            else:
                last = st.last_seq.get(att["gid"])
                if last is not None and att["seq"] <= last:
                    st.out_of_order += 1
                st.last_seq[att["gid"]] = att["seq"]
            if summary is None:
                st.undecodable += 1
                entry = {"undecodable": decode_error, "payload_len": len(payload)}
            else:
                entry = summary
            if att is not None:
                entry = dict(entry, seq=att["seq"], gid=att["gid"])
            if len(st.first) < 3:
                st.first.append(entry)
            st.last = (st.last + [entry])[-3:]

    # -- publishing -----------------------------------------------------------
    def _put(self, topic: str, payload: bytes, attachment: str = "valid") -> None:
        p = self.pubs[topic]
        if attachment == "valid":
            att: bytes | None = make_attachment(p["seq"], time.time_ns(), p["gid"])
            p["seq"] += 1
        elif attachment == "none":
            att = None
        else:  # "short"
            att = make_attachment(p["seq"], time.time_ns(), p["gid"])[:10]
        if att is None:
            p["pub"].put(payload)
        else:
            p["pub"].put(payload, attachment=att)

    def publish_cloud(self) -> None:
        msg = cloud_message(self.args.layout, self.args.plane_z)
        self._put("/points", serialize(msg, "sensor_msgs/msg/PointCloud2"))
        self.published["/points"] += 1

    def publish_joints(self) -> None:
        msg = joint_message(self.joints, self.args.extra_joint)
        self._put("/joint_states", serialize(msg, "sensor_msgs/msg/JointState"))
        self.published["/joint_states"] += 1

    def publish_malformed(self) -> None:
        good = serialize(cloud_message("xyz32", self.args.plane_z), "sensor_msgs/msg/PointCloud2")
        self._put("/points", good[: len(good) // 2])
        self.malformed["points_truncated_half"] = 1
        self._put("/points", good, attachment="none")
        self.malformed["points_no_attachment"] = 1
        self._put("/points", good, attachment="short")
        self.malformed["points_attachment_10_bytes"] = 1
        no_elbow = [j for j in self.joints if j != "elbow"]
        self._put("/joint_states",
                  serialize(joint_message(no_elbow, self.args.extra_joint),
                            "sensor_msgs/msg/JointState"))
        self.malformed["joint_states_without_elbow"] = 1
        self._put("/joint_states", os.urandom(8))
        self.malformed["joint_states_8_random_bytes"] = 1

    def run(self) -> None:
        self.joints = [j for j in self.args.joints.split(",") if j]
        self.declare()
        start = time.monotonic()
        end = start + self.args.seconds
        next_cloud = next_joint = start
        malformed_at = start + 2.0 if self.args.malformed else None
        while True:
            now = time.monotonic()
            if now >= end:
                break
            if not self.args.no_clouds and now >= next_cloud:
                self.publish_cloud()
                next_cloud += 0.1
            if not self.args.no_joints and now >= next_joint:
                self.publish_joints()
                next_joint += 0.02
            if malformed_at is not None and now >= malformed_at:
                self.publish_malformed()
                malformed_at = None
            wake = min(end, next_cloud if not self.args.no_clouds else end,
                       next_joint if not self.args.no_joints else end)
            time.sleep(max(0.0, min(0.02, wake - time.monotonic())))

    def query_graph(self) -> dict:
        keys = []
        replies = self.session.liveliness().get(f"{ADMIN_SPACE}/{self.domain}/**",
                                                timeout=3.0)
        for reply in replies:
            if reply.ok is not None:
                keys.append(str(reply.ok.key_expr))
        return build_graph(keys)

    def report(self) -> dict:
        graph = self.query_graph()
        with self.lock:
            return {
                "zid": self.zid,
                "published": dict(self.published),
                "published_keys": {t: p["key"] for t, p in self.pubs.items()},
                "received": {t: s.to_json() for t, s in self.stats.items()},
                "subscribed_keys": {t: k for k, t in self.exact_keys.items()},
                "other_hash": self.other_hash,
                "other_keys": dict(self.other_keys),
                "graph": graph,
                "own_tokens": [p["token"] for p in self.pubs.values()],
                "malformed_sent": dict(self.malformed),
                "callback_errors": list(self.errors),
            }

    def close(self) -> None:
        for tok in getattr(self, "tokens", []):
            try:
                tok.undeclare()
            except Exception:  # noqa: BLE001
                pass
        self.session.close()


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--connect", action="append", required=True, metavar="ENDPOINT",
                    help="zenoh endpoint to connect to, e.g. tcp/127.0.0.1:7447 (repeatable)")
    ap.add_argument("--listen", action="append", default=None, metavar="ENDPOINT",
                    help="zenoh endpoint to listen on (default: none)")
    ap.add_argument("--domain", type=int, default=0)
    ap.add_argument("--seconds", type=float, required=True)
    ap.add_argument("--report", required=True, metavar="OUT.json")
    ap.add_argument("--layout", default="xyz32",
                    choices=["xyz32", "xyzi_padded", "xyz64", "big_endian", "organised_nan"])
    ap.add_argument("--plane-z", type=float, default=0.0)
    ap.add_argument("--joints", default=ARM_JOINTS_DEFAULT)
    ap.add_argument("--extra-joint", default="gripper_finger")
    ap.add_argument("--malformed", action="store_true")
    ap.add_argument("--no-clouds", action="store_true")
    ap.add_argument("--no-joints", action="store_true")
    args = ap.parse_args(argv)
    if args.listen is None:
        args.listen = []
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    peer = Peer(args)
    try:
        peer.run()
        time.sleep(0.3)  # let in-flight samples land
        report = peer.report()
    finally:
        peer.close()
    with open(args.report, "w", encoding="utf-8") as fh:
        json.dump(report, fh, indent=2, sort_keys=False, default=str)
    return 0


if __name__ == "__main__":
    sys.exit(main())
