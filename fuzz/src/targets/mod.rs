//! The registry of fuzz targets. To add one: write `<name>.rs` here with
//! `pub fn run(data: &[u8])` (the checks) and `pub fn seeds() -> Vec<Vec<u8>>`
//! (valid inputs from fixtures or encoders), add `<name>` to the list below,
//! its `bin` line to fuzz/Cargo.toml and its binary `fuzz_targets/<name>.rs`
//! (a copy of any other: one macro call), then write its seeds to
//! `fuzz/corpus/<name>/` (`cargo test -p shroud-fuzz --test corpus -- --ignored`).
//! tests/corpus.rs fails until all of them agree.

/// One fuzz target.
pub struct Target {
    /// The name of its binary and of its corpus folder.
    pub name: &'static str,
    /// Decodes one input and checks its properties; panics on a violation.
    pub run: fn(&[u8]),
    /// Valid inputs that start its corpus.
    pub seeds: fn() -> Vec<Vec<u8>>,
}

macro_rules! targets {
    ($($name:ident),* $(,)?) => {
        $(pub mod $name;)*

        /// Every target, in the order `fuzz/run.sh` runs them.
        pub const TARGETS: &[Target] = &[$(Target {
            name: stringify!($name),
            run: $name::run,
            seeds: $name::seeds,
        }),*];
    };
}

targets! {
    ply,
    pcd,
    xyz,
    mesh,
    quad_obj,
    surrogate_json,
    surrogate_binary,
    msg_cloud,
    msg_surrogate,
    msg_smooth,
    msg_joints,
    msg_collision,
    msg_status,
    msg_blend_command,
    launch_file,
    arm_file,
    urdf,
    dashboard_frame,
    dashboard_command,
    foxglove_blend_request,
    mcap_recording,
    serial,
    slcan,
    candump,
    can_scan,
    dbc,
    scip_replies,
    benewake_frames,
    rplidar_answers,
    rplidar_scans,
    driver_scip,
    driver_rplidar,
    driver_benewake,
    driver_ars408,
    driver_benewake_can,
    ros2_point_cloud2,
    ros2_joint_state,
    ros2_marker_array,
    ros2_messages,
    ros2_liveliness_token,
    ros2_attachment,
    zenoh_metrics,
}
