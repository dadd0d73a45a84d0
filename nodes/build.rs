//! Rebuilds the crate when a file of the dashboard's page is added or changed
//! (the page is embedded with `include_dir!`, which cannot tell cargo about new
//! files by itself).

fn main() {
    println!("cargo:rerun-if-changed=src/node/dashboard/assets");
}
