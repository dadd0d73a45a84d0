//! Clouds in every layout a driver publishes, and the rays without a return.

use super::*;
use glam::DVec3;
use shroud_ros2::{Header, PointField, Time};
use std::borrow::Cow;

const STAMP: Time = Time {
    sec: 1_700_000_000,
    nanosec: 250,
};

/// A cloud of `rows x columns` points, each `point_step` bytes from `write`.
fn cloud(
    fields: Vec<PointField>,
    point_step: u32,
    (rows, columns): (u32, u32),
    big_endian: bool,
    write: impl Fn(usize, &mut Vec<u8>),
) -> PointCloud2<'static> {
    let mut data = Vec::new();
    for i in 0..(rows * columns) as usize {
        let before = data.len();
        write(i, &mut data);
        data.resize(before + point_step as usize, 0);
    }
    PointCloud2 {
        header: Header {
            stamp: STAMP,
            frame_id: "cam".into(),
        },
        height: rows,
        width: columns,
        fields,
        is_bigendian: big_endian,
        point_step,
        row_step: point_step * columns,
        data: Cow::Owned(data),
        is_dense: false,
    }
}

fn xyz32() -> Vec<PointField> {
    vec![
        PointField::scalar("x", 0, PointField::FLOAT32),
        PointField::scalar("y", 4, PointField::FLOAT32),
        PointField::scalar("z", 8, PointField::FLOAT32),
    ]
}

fn sample(i: usize) -> [f64; 3] {
    [i as f64 * 0.5, -(i as f64), 2.0 + i as f64 * 0.25]
}

fn points_of(c: &PointCloud2<'_>, mount: &CloudMount) -> Vec<[f32; 3]> {
    let ros = cloud_from_ros(c, mount, "cam", 9).unwrap();
    assert_eq!(ros.message.stamp_ns, 1_700_000_000_000_000_250);
    assert_eq!(
        (ros.message.sequence, ros.message.source.as_str()),
        (9, "cam")
    );
    ros.message.point_array().unwrap()
}

fn expected(n: usize) -> Vec<[f32; 3]> {
    (0..n).map(|i| sample(i).map(|v| v as f32)).collect()
}

#[test]
fn float32_float64_and_big_endian_layouts_read_the_same_points() {
    let mount = CloudMount::default();
    let le32 = cloud(xyz32(), 12, (1, 5), false, |i, d| {
        sample(i)
            .iter()
            .for_each(|v| d.extend((*v as f32).to_le_bytes()))
    });
    let be32 = cloud(xyz32(), 12, (1, 5), true, |i, d| {
        sample(i)
            .iter()
            .for_each(|v| d.extend((*v as f32).to_be_bytes()))
    });
    let f64s = vec![
        PointField::scalar("x", 0, PointField::FLOAT64),
        PointField::scalar("y", 8, PointField::FLOAT64),
        PointField::scalar("z", 16, PointField::FLOAT64),
    ];
    let le64 = cloud(f64s, 24, (1, 5), false, |i, d| {
        sample(i).iter().for_each(|v| d.extend(v.to_le_bytes()))
    });
    for c in [&le32, &be32, &le64] {
        assert_eq!(points_of(c, &mount), expected(5));
    }
}

#[test]
fn padded_points_with_intensity_keep_their_intensity() {
    // PCL's PointXYZI: x, y, z, 4 bytes of padding, intensity, 12 more.
    let mut fields = xyz32();
    fields.push(PointField::scalar("intensity", 16, PointField::FLOAT32));
    let c = cloud(fields, 32, (1, 4), false, |i, d| {
        sample(i)
            .iter()
            .for_each(|v| d.extend((*v as f32).to_le_bytes()));
        d.extend([0xAB; 4]);
        let value = if i == 3 { f32::NAN } else { i as f32 * 10.0 };
        d.extend(value.to_le_bytes());
    });
    let ros = cloud_from_ros(&c, &CloudMount::default(), "cam", 0).unwrap();
    assert_eq!(ros.message.point_array().unwrap(), expected(4));
    let intensity = ros.message.intensity_array().unwrap().unwrap();
    assert_eq!(intensity, [0.0, 10.0, 20.0, 0.0]);
    assert_eq!(ros.nonfinite_intensity, 1);
}

#[test]
fn a_mount_places_points_in_the_world() {
    // Straight down from 3 m: optical +z is the world's -z, +y is -y.
    let mount = CloudMount {
        position: [1.0, 2.0, 3.0],
        orientation: [1.0, 0.0, 0.0, 0.0],
        camera: None,
    };
    let c = cloud(xyz32(), 12, (1, 1), false, |_, d| {
        [0.5f32, 0.25, 2.0]
            .iter()
            .for_each(|v| d.extend(v.to_le_bytes()))
    });
    assert_eq!(points_of(&c, &mount), [[1.5, 1.75, 1.0]]);
    let ros = cloud_from_ros(&c, &mount, "cam", 0).unwrap();
    assert_eq!(ros.message.pose.position, [1.0, 2.0, 3.0]);
}

fn camera_mount() -> CloudMount {
    CloudMount {
        position: [0.0, 0.0, 3.0],
        orientation: [1.0, 0.0, 0.0, 0.0],
        camera: Some(PinholeCamera {
            horizontal_fov: 90f64.to_radians(),
            vertical_fov: 70f64.to_radians(),
            max_range: 6.0,
        }),
    }
}

const ROWS: usize = 24;
const COLUMNS: usize = 32;

/// A camera's organised image of the floor, with no return in `dark`.
fn organised(dark: impl Fn(usize, usize) -> bool) -> PointCloud2<'static> {
    let camera = camera_mount().camera.unwrap();
    cloud(
        xyz32(),
        16,
        (ROWS as u32, COLUMNS as u32),
        false,
        move |i, d| {
            let (r, c) = (i / COLUMNS, i % COLUMNS);
            let ray = camera.ray(ROWS, COLUMNS, r, c);
            let p = if dark(r, c) {
                [f32::NAN; 3]
            } else {
                (ray * (3.0 / ray.z)).as_vec3().to_array()
            };
            p.iter().for_each(|v| d.extend(v.to_le_bytes()))
        },
    )
}

fn in_block(r: usize, c: usize) -> bool {
    (5..11).contains(&r) && (8..15).contains(&c)
}

#[test]
fn rays_without_a_return_become_cones_that_hold_every_direction_near_them() {
    let mount = camera_mount();
    let ros = cloud_from_ros(&organised(in_block), &mount, "cam", 0).unwrap();
    let dark = 6 * 7;
    assert_eq!(ros.empty_rays, dark);
    assert_eq!(
        ros.message.point_array().unwrap().len(),
        ROWS * COLUMNS - dark
    );
    let fov = ros.message.field_of_view.expect("a camera states its view");
    fov.validate().unwrap();
    let no_return = ros.message.no_return.expect("the dark block is stated");
    no_return.validate().unwrap();
    assert_eq!(no_return.apex, [0.0, 0.0, 3.0]);
    // Brute force: every direction through a dark pixel's footprint (its
    // rays at 7 x 7 sub-pixel offsets, out to the pixel's edges) lies in
    // some cone; an object there, at any depth, is stated unseen.
    let camera = mount.camera.unwrap();
    let rotation = mount.rotation();
    let (fine_rows, fine_columns) = (ROWS * 6, COLUMNS * 6);
    for r in 0..fine_rows {
        for c in 0..fine_columns {
            if !in_block(r / 6, c / 6) {
                continue;
            }
            let ray = rotation * camera.ray(fine_rows, fine_columns, r, c);
            let inside = no_return
                .cones
                .iter()
                .any(|cone| DVec3::from_array(cone.axis).angle_between(ray) <= cone.half_angle);
            assert!(
                inside,
                "sub-pixel ray ({r}, {c}) of a dark pixel is in no cone"
            );
        }
    }
}

#[test]
fn rays_without_a_return_that_cannot_be_placed_refuse_the_cloud() {
    let unplaced = CloudMount {
        camera: None,
        ..camera_mount()
    };
    let e = cloud_from_ros(&organised(in_block), &unplaced, "cam", 0).unwrap_err();
    assert!(
        matches!(e, CloudInError::EmptyRaysWithoutCamera { count: 42, .. }),
        "{e}"
    );
    let mut flat = organised(in_block);
    flat.width *= flat.height;
    flat.row_step *= flat.height;
    flat.height = 1;
    let e = cloud_from_ros(&flat, &camera_mount(), "cam", 0).unwrap_err();
    assert_eq!(e, CloudInError::UnplacedEmptyRays { count: 42 });
    // Every point returned: no cones, and a dense organised cloud needs no camera.
    let dense = cloud_from_ros(&organised(|_, _| false), &unplaced, "cam", 0).unwrap();
    assert_eq!((dense.empty_rays, dense.message.no_return), (0, None));
}

#[test]
fn bad_layouts_are_named_before_any_point_is_read() {
    let good = || {
        cloud(xyz32(), 12, (2, 3), false, |i, d| {
            sample(i)
                .iter()
                .for_each(|v| d.extend((*v as f32).to_le_bytes()))
        })
    };
    let check = |c: PointCloud2<'static>, needle: &str| {
        let e = cloud_from_ros(&c, &CloudMount::default(), "cam", 0).unwrap_err();
        assert!(e.to_string().contains(needle), "{e} lacks {needle:?}");
    };
    let mut c = good();
    c.fields.pop();
    check(c, "no field \"z\"");
    let mut c = good();
    c.fields[0].datatype = PointField::INT32;
    check(c, "not FLOAT32");
    let mut c = good();
    c.fields[2].offset = 10;
    check(c, "does not fit in point_step");
    let mut c = good();
    c.fields[1].datatype = 42;
    check(c, "datatype 42");
    let mut c = good();
    c.row_step = 20;
    check(c, "exceeds row_step");
    let mut c = good();
    c.point_step = 0;
    check(c, "point_step is 0");
    let mut c = good();
    c.data.to_mut().pop();
    check(c, "data is 71 bytes");
    let mut c = good();
    c.height = u32::MAX;
    c.width = u32::MAX;
    check(c, "exceeds row_step");
    let mut c = good();
    c.header.stamp.sec = -1;
    check(c, "not a time after the Unix epoch");
}

#[test]
fn a_camera_model_that_is_not_the_clouds_is_refused_before_it_places_rays() {
    // The cloud was taken with a 90 x 70 degree camera; a mount that says
    // 60 x 45 would place its dark rays where they are not.
    let mut narrow = camera_mount();
    narrow.camera = Some(PinholeCamera {
        horizontal_fov: 60f64.to_radians(),
        vertical_fov: 45f64.to_radians(),
        max_range: 6.0,
    });
    let e = cloud_from_ros(&organised(in_block), &narrow, "cam", 0).unwrap_err();
    assert!(matches!(e, CloudInError::CameraModel { .. }), "{e}");
    assert!(e.to_string().contains("optical frame"), "{e}");
}
