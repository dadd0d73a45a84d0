//! The soak's 30-second version (`shroud-bench soak --check`): the demo graph
//! at 300K points and 30 Hz; every cloud the scanner published is accounted
//! for at the fit node (taken, dropped by its backlog policy, or missing from
//! its sequence), and no node's memory grows between the first and the last
//! ten seconds beyond a small bound. The table it prints is in the test log.

mod common;

#[test]
fn a_thirty_second_soak_accounts_for_every_cloud_and_memory_stays_flat() {
    let out = common::bench::shroud_bench()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["soak", "--points", "300000", "--rate", "30"])
        .args([
            "--minutes",
            "0.5",
            "--window",
            "10",
            "--check",
            "--max-growth-mb",
            "16",
        ])
        .output()
        .expect("the shroud-bench binary runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    eprintln!("{stdout}");
    assert!(
        out.status.success(),
        "soak check failed:\n{stdout}\n{stderr}"
    );
    assert!(stdout.contains("check passed"), "{stdout}");
    assert_eq!(
        stdout.matches("\n| 10 |").count()
            + stdout.matches("\n| 20 |").count()
            + stdout.matches("\n| 30 |").count(),
        3,
        "three windows: {stdout}"
    );
}
