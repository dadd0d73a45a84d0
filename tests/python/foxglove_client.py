"""A Foxglove WebSocket client, written from the protocol's documentation
(foxglove/ws-protocol docs/spec.md): it connects to `shroud node foxglove`,
subscribes to a cloud, a surrogate and a status channel, decodes their
messages with the schemas the server advertises, then publishes on
/shroud/blend: first malformed JSON, then a drop at a point of the cloud.

Usage: foxglove_client.py URL CLOUD_TOPIC SURROGATE_TOPIC STATUS_TOPIC
Prints one JSON line of what it decoded; exits non-zero on any failure.
"""

import base64
import json
import math
import struct
import sys
import time

from google.protobuf import descriptor_pb2, descriptor_pool, message_factory
from websockets.sync.client import connect

SUBPROTOCOL = "foxglove.sdk.v1"
DEADLINE_S = 15.0


def message_class(channel):
    """The protobuf class of a channel, built from its advertised schema (a
    base64 FileDescriptorSet)."""
    assert channel["encoding"] == "protobuf", channel
    assert channel["schemaEncoding"] == "protobuf", channel
    files = descriptor_pb2.FileDescriptorSet.FromString(base64.b64decode(channel["schema"]))
    pool = descriptor_pool.DescriptorPool()
    for f in files.file:
        pool.Add(f)
    return message_factory.GetMessageClass(pool.FindMessageTypeByName(channel["schemaName"]))


def message_data(frame):
    """(subscription id, log time, payload) of a binary server message."""
    assert frame[0] == 0x01, f"opcode {frame[0]}"
    sub, log_time = struct.unpack_from("<IQ", frame, 1)
    return sub, log_time, frame[13:]


def decode_cloud(cloud):
    fields = {f.name: f.offset for f in cloud.fields}
    assert fields.get("x") == 0 and fields.get("y") == 4 and fields.get("z") == 8, fields
    stride = cloud.point_stride
    n = len(cloud.data) // stride
    assert n * stride == len(cloud.data), "data is not whole points"
    points = [struct.unpack_from("<fff", cloud.data, i * stride) for i in range(n)]
    assert all(math.isfinite(c) for p in points for c in p), "a non-finite coordinate"
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return {
        "points": n,
        "stride": stride,
        "fields": sorted(fields),
        "frame_id": cloud.frame_id,
        "min": lo,
        "max": hi,
        "middle": list(points[n // 2]),
    }


def decode_scene(update):
    entities = {}
    for e in update.entities:
        triangles = sum(len(t.indices) // 3 for t in e.triangles)
        vertices = sum(len(t.points) for t in e.triangles)
        in_range = all(i < len(t.points) for t in e.triangles for i in t.indices)
        entities[e.id] = {"triangles": triangles, "vertices": vertices, "indices_in_range": in_range}
    return entities


def main():
    url, cloud_topic, surrogate_topic, status_topic = sys.argv[1:5]
    wanted = [cloud_topic, surrogate_topic, status_topic]
    out = {}
    with connect(url, subprotocols=[SUBPROTOCOL], max_size=None, open_timeout=10) as ws:
        out["subprotocol"] = ws.subprotocol
        channels, subs, decoded = {}, {}, {}
        deadline = time.monotonic() + DEADLINE_S
        while len(decoded) < len(wanted):
            assert time.monotonic() < deadline, f"decoded only {sorted(decoded)} of {wanted}; advertised {sorted(channels)}"
            frame = ws.recv(timeout=deadline - time.monotonic())
            if isinstance(frame, str):
                msg = json.loads(frame)
                if msg["op"] == "serverInfo":
                    out["capabilities"] = msg["capabilities"]
                    out["supportedEncodings"] = msg.get("supportedEncodings", [])
                elif msg["op"] == "advertise":
                    for ch in msg["channels"]:
                        channels[ch["topic"]] = ch
                        if ch["topic"] in wanted and ch["topic"] not in subs.values():
                            sub_id = len(subs)
                            subs[sub_id] = ch["topic"]
                            ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": sub_id, "channelId": ch["id"]}]}))
                continue
            sub, _, payload = message_data(frame)
            topic = subs[sub]
            ch = channels[topic]
            if topic == cloud_topic:
                decoded[topic] = decode_cloud(message_class(ch).FromString(payload))
                decoded[topic]["schemaName"] = ch["schemaName"]
            elif topic == surrogate_topic:
                decoded[topic] = {"schemaName": ch["schemaName"], "entities": decode_scene(message_class(ch).FromString(payload))}
            else:
                assert ch["encoding"] == "json", ch
                decoded[topic] = {"schemaEncoding": ch["schemaEncoding"], "message": json.loads(payload)}
        out["decoded"] = decoded
        # Publish: advertise a client channel, send bad JSON, then a drop.
        ws.send(json.dumps({"op": "advertise", "channels": [{"id": 7, "topic": "/shroud/blend", "encoding": "json", "schemaName": "shroud.BlendRequest"}]}))
        ws.send(struct.pack("<BI", 0x01, 7) + b"{not json")
        drop = {"command": "drop", "at": decoded[cloud_topic]["middle"]}
        ws.send(struct.pack("<BI", 0x01, 7) + json.dumps(drop).encode())
        out["published"] = drop
        # Keep the connection until the server has read what was sent.
        time.sleep(0.5)
    print(json.dumps(out), flush=True)


if __name__ == "__main__":
    main()
