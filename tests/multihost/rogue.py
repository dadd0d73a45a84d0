"""A rogue zenoh peer for tests/multihost_netns.rs: it tries to steer an arm
it has no business steering, from a network namespace of its own.

It opens one session per --endpoint (mutual TLS with --cert/--key, or with no
certificate at all), listens to the arm's joint states and the fitted
surrogates like any subscriber may, and forges what only other hosts may
publish:

- a `clear` verdict (the --template collision message, MessagePack, with the
  sequence and stamp of each joint state it hears patched in, so that the
  arm's deadman would take it if it arrived);
- a joint state of the arm (the last one heard, moved and renumbered);
- a surrogate (the last one heard, replayed as is).

Every forged sample carries the attachment `rogue:<name>`, so that whoever
receives one can tell. It forges only while the --armed file exists (all the
time without --armed), and prints JSON lines: one `open` per endpoint, then a
`stats` line per endpoint every 0.5 s until --seconds have passed.
"""

import argparse
import json
import os
import sys
import threading
import time

import msgpack
import zenoh


def config(args, endpoint):
    conf = zenoh.Config()
    settings = {
        "mode": json.dumps(args.mode),
        "connect/endpoints": json.dumps([endpoint]),
        "scouting/multicast/enabled": "false",
        "scouting/gossip/enabled": "false",
        "transport/link/tls/root_ca_certificate": json.dumps(args.ca),
    }
    if args.mode == "peer":
        # A peer keeps retrying instead of failing: say so in the report.
        settings["connect/exit_on_failure"] = "false"
    if args.cert:
        settings["transport/link/tls/connect_certificate"] = json.dumps(args.cert)
        settings["transport/link/tls/connect_private_key"] = json.dumps(args.key)
        settings["transport/link/tls/enable_mtls"] = "true"
    for key, value in settings.items():
        conf.insert_json5(key, value)
    return conf


class Forger:
    def __init__(self, args, endpoint, session):
        self.args = args
        self.endpoint = endpoint
        self.session = session
        self.lock = threading.Lock()
        self.counts = {"joints_heard": 0, "surrogates_heard": 0,
                       "collision": 0, "joints": 0, "surrogate": 0, "errors": 0}
        self.last_joints = None
        self.last_surrogate = None
        self.template = msgpack.unpackb(bytes.fromhex(args.template)) if args.template else None
        self.attachment = ("rogue:" + args.name).encode()
        root = "shroud/%s" % args.ns
        self.keys = {
            "collision": "%s/collision/%s" % (root, args.arm),
            "joints": "%s/joints/%s" % (root, args.arm),
            "surrogate": "%s/surrogate/%s" % (root, args.surrogate),
        }
        self.subscribers = [
            session.declare_subscriber(self.keys["joints"], self.on_joints),
            session.declare_subscriber(self.keys["surrogate"], self.on_surrogate),
        ]

    def armed(self):
        return self.args.armed is None or os.path.exists(self.args.armed)

    def put(self, what, payload):
        try:
            self.session.put(self.keys[what], payload, attachment=self.attachment)
            with self.lock:
                self.counts[what] += 1
        except Exception:  # a rogue does not give up
            with self.lock:
                self.counts["errors"] += 1

    def on_joints(self, sample):
        if sample.attachment is not None:
            return  # our own (or another rogue's) forgery
        try:
            state = msgpack.unpackb(sample.payload.to_bytes())
        except Exception:
            return
        with self.lock:
            self.counts["joints_heard"] += 1
            self.last_joints = state
        # Answer at once, as the guard would: the deadman takes a clear only
        # for one of its recent joint states, within its deadline.
        if "collision" in self.args.forge and self.template is not None and self.armed():
            verdict = dict(self.template)
            verdict["joints_sequence"] = state["sequence"]
            verdict["joints_stamp_ns"] = state["stamp_ns"]
            verdict["check_ns"] = time.time_ns()
            self.put("collision", msgpack.packb(verdict))

    def on_surrogate(self, sample):
        if sample.attachment is not None:
            return
        with self.lock:
            self.counts["surrogates_heard"] += 1
            self.last_surrogate = sample.payload.to_bytes()

    def tick(self):
        """The slower forgeries: a joint state and a surrogate."""
        if not self.armed():
            return
        with self.lock:
            joints, surrogate = self.last_joints, self.last_surrogate
        if "joints" in self.args.forge and joints is not None:
            forged = dict(joints)
            forged["sequence"] = joints["sequence"] + 1_000_000_000
            forged["stamp_ns"] = time.time_ns()
            forged["positions"] = [p + 0.5 for p in joints["positions"]]
            self.put("joints", msgpack.packb(forged))
        if "surrogate" in self.args.forge:
            self.put("surrogate", surrogate if surrogate is not None else b"forged surrogate")

    def stats(self):
        with self.lock:
            counts = dict(self.counts)
        return {"event": "stats", "name": self.args.name, "endpoint": self.endpoint,
                "armed": self.armed(), **counts}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--name", required=True)
    parser.add_argument("--mode", default="client", choices=["client", "peer"])
    parser.add_argument("--endpoint", action="append", required=True)
    parser.add_argument("--ca", required=True)
    parser.add_argument("--cert")
    parser.add_argument("--key")
    parser.add_argument("--ns", required=True)
    parser.add_argument("--arm", required=True)
    parser.add_argument("--surrogate", required=True)
    parser.add_argument("--template", help="a clear collision message, hex")
    parser.add_argument("--forge", default="collision,joints,surrogate")
    parser.add_argument("--armed", help="forge only while this file exists")
    parser.add_argument("--seconds", type=float, default=60.0)
    args = parser.parse_args()
    args.forge = args.forge.split(",")

    def say(line):
        print(json.dumps(line), flush=True)

    forgers = []
    for endpoint in args.endpoint:
        started = time.monotonic()
        try:
            session = zenoh.open(config(args, endpoint))
        except Exception as e:  # zenoh.ZError
            say({"event": "open", "name": args.name, "endpoint": endpoint, "ok": False,
                 "error": str(e), "seconds": round(time.monotonic() - started, 3)})
            continue
        info = session.info
        say({"event": "open", "name": args.name, "endpoint": endpoint, "ok": True,
             "routers": len(list(info.routers_zid())), "peers": len(list(info.peers_zid())),
             "seconds": round(time.monotonic() - started, 3)})
        forgers.append(Forger(args, endpoint, session))

    deadline = time.monotonic() + args.seconds
    next_stats = 0.0
    while time.monotonic() < deadline:
        for forger in forgers:
            forger.tick()
        now = time.monotonic()
        if now >= next_stats:
            for forger in forgers:
                say(forger.stats())
            next_stats = now + 0.5
        time.sleep(0.05)
    for forger in forgers:
        say(forger.stats())
        forger.session.close()
    say({"event": "done", "name": args.name})
    return 0


if __name__ == "__main__":
    sys.exit(main())
