"""Writes the golden CDR payloads and type hashes of shroud-ros2's tests.

Provenance: every byte here comes from rosbags (an independent pure-Python
implementation of ROS 2's CDR and of REP-2011's RIHS01 type hashes), never
from shroud's code. Run with rosbags==0.11.9 and xxhash==4.1.0:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install rosbags==0.11.9 xxhash==4.1.0
    /tmp/venv/bin/python libraries/ros2/tests/golden/generate.py

Outputs, beside this script: `<case>.hex` (one payload as lowercase hex,
header included), `type_hashes.txt` (`<type> <RIHS01 hash>` per line, from
rosbags' `hash_rihs01` on the ROS 2 Jazzy store) and `gids.txt` (`<gid hex>
<token>` per line: XXH3-128 of a liveliness token, low 64 bits first in
little endian as rmw_zenoh's liveliness_utils.cpp@3411fdec copies them).
The Rust tests (tests/golden.rs) build the same values by hand and compare.
"""

from pathlib import Path

import numpy as np
import xxhash
from rosbags.typesys import Stores, get_typestore

HERE = Path(__file__).parent
ts = get_typestore(Stores.ROS2_JAZZY)
T = ts.types


def time(sec=0, nanosec=0):
    return T['builtin_interfaces/msg/Time'](sec=sec, nanosec=nanosec)


def duration(sec=0, nanosec=0):
    return T['builtin_interfaces/msg/Duration'](sec=sec, nanosec=nanosec)


def header(frame_id='map', sec=1, nanosec=2):
    return T['std_msgs/msg/Header'](stamp=time(sec, nanosec), frame_id=frame_id)


def field(name, offset, datatype, count=1):
    return T['sensor_msgs/msg/PointField'](name=name, offset=offset, datatype=datatype, count=count)


def cloud(fields, point_step, data, width, is_bigendian=False, frame_id='map'):
    return T['sensor_msgs/msg/PointCloud2'](
        header=header(frame_id), height=1, width=width, fields=fields,
        is_bigendian=is_bigendian, point_step=point_step, row_step=point_step * width,
        data=np.frombuffer(bytes(data), dtype=np.uint8), is_dense=True)


def xyz(datatype, size):
    return [field(n, i * size, datatype) for i, n in enumerate('xyz')]


def point(x, y, z):
    return T['geometry_msgs/msg/Point'](x=x, y=y, z=z)


def vector3(x, y, z):
    return T['geometry_msgs/msg/Vector3'](x=x, y=y, z=z)


def quaternion(x=0.0, y=0.0, z=0.0, w=1.0):
    return T['geometry_msgs/msg/Quaternion'](x=x, y=y, z=z, w=w)


def pose():
    return T['geometry_msgs/msg/Pose'](position=point(1.0, 2.0, 3.0), orientation=quaternion())


def color(r, g, b, a=1.0):
    return T['std_msgs/msg/ColorRGBA'](r=r, g=g, b=b, a=a)


def f64s(values):
    return np.array(values, dtype=np.float64)


def u8s(values):
    return np.array(values, dtype=np.uint8)


def joint_state(velocity, effort):
    return T['sensor_msgs/msg/JointState'](
        header=header('', 10, 4), name=['shoulder', 'elbow'], position=f64s([0.5, -1.25]),
        velocity=f64s(velocity), effort=f64s(effort))


def compressed_image(fmt='', data=()):
    return T['sensor_msgs/msg/CompressedImage'](header=header('', 0, 0), format=fmt, data=u8s(data))


def mesh_file(filename='', data=()):
    return T['visualization_msgs/msg/MeshFile'](filename=filename, data=u8s(data))


def uv(u, v):
    return T['visualization_msgs/msg/UVCoordinate'](u=u, v=v)


def marker(**overrides):
    values = dict(
        header=header('map', 5, 6), ns='shroud', id=7, type=11, action=0, pose=pose(),
        scale=vector3(1.0, 1.0, 1.0), color=color(1.0, 0.5, 0.25), lifetime=duration(),
        frame_locked=False,
        points=[point(0.0, 0.0, 0.0), point(1.0, 0.0, 0.0), point(0.0, 1.0, 0.0)],
        colors=[color(1.0, 0.0, 0.0), color(0.0, 1.0, 0.0), color(0.0, 0.0, 1.0)],
        texture_resource='', texture=compressed_image(), uv_coordinates=[], text='',
        mesh_resource='', mesh_file=mesh_file(), mesh_use_embedded_materials=False)
    values.update(overrides)
    return T['visualization_msgs/msg/Marker'](**values)


def key_value(key, value):
    return T['diagnostic_msgs/msg/KeyValue'](key=key, value=value)


def transform():
    return T['geometry_msgs/msg/Transform'](
        translation=vector3(1.0, -2.0, 0.5), rotation=quaternion(0.0, 0.0, 0.7071067811865476, 0.7071067811865476))


def transform_stamped():
    return T['geometry_msgs/msg/TransformStamped'](
        header=header('world', 3, 500), child_frame_id='base_link', transform=transform())


XYZ_F32 = np.array([1.0, 2.0, 3.0, -1.5, 0.25, 8.0], dtype='<f4').tobytes()
XYZI_PADDED = np.array([1.0, 2.0, 3.0, 0.0, 9.5, 0.0, 0.0, 0.0,
                        4.0, 5.0, 6.0, 0.0, 7.25, 0.0, 0.0, 0.0], dtype='<f4').tobytes()
XYZ_F64 = np.array([1.5, -2.5, 1e-3], dtype='<f8').tobytes()
XYZ_F32_BE = np.array([1.0, 2.0, 3.0], dtype='>f4').tobytes()

CASES = {
    'point_cloud2_xyz': (cloud(xyz(7, 4), 12, XYZ_F32, 2), 'sensor_msgs/msg/PointCloud2'),
    'point_cloud2_xyzi_padded': (
        cloud(xyz(7, 4) + [field('intensity', 16, 7)], 32, XYZI_PADDED, 2),
        'sensor_msgs/msg/PointCloud2'),
    'point_cloud2_float64': (cloud(xyz(8, 8), 24, XYZ_F64, 1), 'sensor_msgs/msg/PointCloud2'),
    'point_cloud2_bigendian_data': (
        cloud(xyz(7, 4), 12, XYZ_F32_BE, 1, is_bigendian=True), 'sensor_msgs/msg/PointCloud2'),
    'joint_state_positions': (joint_state([], []), 'sensor_msgs/msg/JointState'),
    'joint_state_velocities': (joint_state([0.75, -0.2], [1.0, 2.0]), 'sensor_msgs/msg/JointState'),
    'marker_array_triangle_list': (
        T['visualization_msgs/msg/MarkerArray'](markers=[marker()]), 'visualization_msgs/msg/MarkerArray'),
    'marker_array_empty': (T['visualization_msgs/msg/MarkerArray'](markers=[]), 'visualization_msgs/msg/MarkerArray'),
    'marker_every_field': (marker(
        type=2, action=0, lifetime=duration(1, 500), frame_locked=True, points=[], colors=[],
        texture_resource='file:///t.png', texture=compressed_image('png', [1, 2, 3]),
        uv_coordinates=[uv(0.5, 0.25)], text='hi', mesh_resource='package://m.dae',
        mesh_file=mesh_file('m.dae', [9, 8]), mesh_use_embedded_materials=True),
        'visualization_msgs/msg/Marker'),
    'float64': (T['std_msgs/msg/Float64'](data=-12.5), 'std_msgs/msg/Float64'),
    'diagnostic_status': (T['diagnostic_msgs/msg/DiagnosticStatus'](
        level=1, name='shroud: lidar', message='late', hardware_id='scip0',
        values=[key_value('rate', '9.5'), key_value('expected', '10')]),
        'diagnostic_msgs/msg/DiagnosticStatus'),
    'tf_message': (T['tf2_msgs/msg/TFMessage'](transforms=[transform_stamped()]), 'tf2_msgs/msg/TFMessage'),
    'time': (time(-3, 999999999), 'builtin_interfaces/msg/Time'),
    'duration': (duration(7, 1), 'builtin_interfaces/msg/Duration'),
    'header': (header('base_link', 1700000000, 123), 'std_msgs/msg/Header'),
    'color_rgba': (color(0.1, 0.2, 0.3, 0.4), 'std_msgs/msg/ColorRGBA'),
    'point_field': (field('rgb', 12, 6), 'sensor_msgs/msg/PointField'),
    'compressed_image': (compressed_image('jpeg', [255, 216, 255]), 'sensor_msgs/msg/CompressedImage'),
    'point': (point(1.0, -2.0, 3.5), 'geometry_msgs/msg/Point'),
    'vector3': (vector3(0.5, 0.25, -0.125), 'geometry_msgs/msg/Vector3'),
    'quaternion': (quaternion(0.0, 0.0, 0.7071067811865476, 0.7071067811865476), 'geometry_msgs/msg/Quaternion'),
    'pose': (pose(), 'geometry_msgs/msg/Pose'),
    'transform': (transform(), 'geometry_msgs/msg/Transform'),
    'transform_stamped': (transform_stamped(), 'geometry_msgs/msg/TransformStamped'),
    'uv_coordinate': (uv(0.5, 0.75), 'visualization_msgs/msg/UVCoordinate'),
    'mesh_file': (mesh_file('m.stl', [1, 2, 3, 4]), 'visualization_msgs/msg/MeshFile'),
    'key_value': (key_value('k', 'v'), 'diagnostic_msgs/msg/KeyValue'),
}

# Big-endian encapsulations (CDR_BE, header 00 00 00 00) of some cases: rmw
# writes little endian, but a decoder must read both.
BIG_ENDIAN = ['point_cloud2_xyz', 'joint_state_velocities', 'marker_array_triangle_list', 'tf_message']

TYPES = sorted({typename for _, typename in CASES.values()})

TOKENS = [
    '@ros2_lv/0/aabbccddeeff00112233445566778899/0/0/NN/%/%/shroud_bridge',
    '@ros2_lv/0/aabbccddeeff00112233445566778899/0/1/MP/%/%/shroud_bridge/%shroud%cloud/'
    'sensor_msgs::msg::dds_::PointCloud2_/'
    'RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5/2:2:1,5:,:,:,,',
]


def write(name, text):
    (HERE / name).write_text(text)


def main():
    for name, (message, typename) in CASES.items():
        write(f'{name}.hex', bytes(ts.serialize_cdr(message, typename)).hex() + '\n')
        decoded = ts.deserialize_cdr(bytes(ts.serialize_cdr(message, typename)), typename)
        assert type(decoded).__name__ == type(message).__name__
    for name in BIG_ENDIAN:
        message, typename = CASES[name]
        write(f'{name}_be.hex', bytes(ts.serialize_cdr(message, typename, little_endian=False)).hex() + '\n')
    write('type_hashes.txt', ''.join(f'{t} {ts.hash_rihs01(t)}\n' for t in TYPES))
    write('gids.txt', ''.join(
        f'{xxhash.xxh3_128_intdigest(t.encode()).to_bytes(16, "little").hex()} {t}\n' for t in TOKENS))


if __name__ == '__main__':
    main()
