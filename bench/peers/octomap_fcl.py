"""OctoMap + FCL on one cloud, for `shroud-bench peers` (issue 27).

Reads the files the benchmark wrote into DIR (`points.npy`, N x 3 f32, the
cloud; `origin.npy`, 3 f64, the sensor's origin; `spheres.npy`, M x 4 f64,
the test spheres as x, y, z, radius) and prints one JSON object: what it
read (counts and sums, which the benchmark checks against what it wrote),
and per insertion mode ("rays": `insertPointCloud` from the origin, the
cells along each ray marked free and its end occupied, as MoveIt's occupancy
map monitor does; "endpoints": only the end cells marked occupied) and
resolution: the build time (median of the runs, at least one, at most
--max-runs while the runs so far took less than --budget seconds), the
octree's memory (`memoryUsage`, bytes), the time to hand the tree to FCL
(binary serialisation, apart from the build), the time of each --batch
spheres' FCL collision queries (median over the batches), and per sphere
whether FCL finds it colliding with an occupied voxel ("1") or not ("0";
free and unknown space are both free to it). Threads: one for all (the
octomap-python wheel links no OpenMP runtime).
"""

import argparse
import importlib.metadata
import json
import os
import statistics
import time

import fcl
import numpy as np
import octomap


def build(points, origin, resolution, mode):
    tree = octomap.OcTree(resolution)
    start = time.perf_counter()
    if mode == "rays":
        tree.insertPointCloud(points, origin)
    else:
        tree.updateNodes(points, True)
    return tree, (time.perf_counter() - start) * 1e3


def to_fcl(tree, resolution):
    """The tree as FCL's OcTree: python-fcl reads OctoMap's binary data
    (without the file header) as signed chars."""
    data = tree.writeBinary()
    raw = np.frombuffer(data[data.index(b"data\n") + 5 :], dtype=np.int8)
    return fcl.CollisionObject(fcl.OcTree(resolution, raw.tolist()), fcl.Transform())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dir")
    parser.add_argument("--resolutions", default="0.01,0.02,0.05")
    parser.add_argument("--modes", default="rays,endpoints")
    parser.add_argument("--batch", type=int, default=50)
    parser.add_argument("--max-runs", type=int, default=5)
    parser.add_argument("--budget", type=float, default=10.0)
    args = parser.parse_args()

    points32 = np.load(os.path.join(args.dir, "points.npy"))
    origin = np.load(os.path.join(args.dir, "origin.npy")).astype(np.float64)
    spheres = np.load(os.path.join(args.dir, "spheres.npy"))
    points = points32.astype(np.float64)
    objects = [
        fcl.CollisionObject(fcl.Sphere(float(s[3])), fcl.Transform(s[:3].astype(np.float64)))
        for s in spheres
    ]
    request = fcl.CollisionRequest()
    out = {
        "read": {
            "points": int(points.shape[0]),
            "point_sum": float(points.sum()),
            "origin": origin.tolist(),
            "spheres": int(spheres.shape[0]),
            "sphere_sum": float(spheres.sum()),
        },
        "octomap": "octomap-python " + importlib.metadata.version("octomap-python"),
        "fcl": "python-fcl " + importlib.metadata.version("python-fcl"),
        "results": [],
    }
    for mode in args.modes.split(","):
        for resolution in [float(r) for r in args.resolutions.split(",")]:
            times = []
            while len(times) < max(args.max_runs, 1) and (not times or sum(times) < args.budget * 1e3):
                tree, ms = build(points, origin, resolution, mode)
                times.append(ms)
            start = time.perf_counter()
            octree = to_fcl(tree, resolution)
            convert_ms = (time.perf_counter() - start) * 1e3
            blocked = []
            batches = []
            for first in range(0, len(objects), args.batch):
                chunk = objects[first : first + args.batch]
                start = time.perf_counter()
                hits = [fcl.collide(s, octree, request, fcl.CollisionResult()) > 0 for s in chunk]
                if len(chunk) == args.batch:
                    batches.append((time.perf_counter() - start) * 1e3)
                blocked.extend(hits)
            out["results"].append(
                {
                    "mode": mode,
                    "resolution": resolution,
                    "build_ms": statistics.median(times),
                    "build_runs": len(times),
                    "memory_bytes": int(tree.memoryUsage()),
                    "leaves": int(tree.getNumLeafNodes()),
                    "fcl_convert_ms": convert_ms,
                    "query_ms": statistics.median(batches) if batches else None,
                    "blocked": "".join("1" if b else "0" for b in blocked),
                }
            )
    print(json.dumps(out))


if __name__ == "__main__":
    main()
