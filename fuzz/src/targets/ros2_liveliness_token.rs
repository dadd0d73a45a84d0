//! rmw_zenoh liveliness tokens (shroud-ros2's `LivelinessToken::parse`): a
//! token that parses must write a key expression that parses to the same token.

use crate::check::named;
use shroud_ros2::LivelinessToken;

pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match LivelinessToken::parse(text) {
        Ok(token) => {
            let again =
                LivelinessToken::parse(&token.to_keyexpr()).expect("a written token parses");
            assert_eq!(token, again, "tokens after a round trip");
        }
        Err(e) => named(&e),
    }
}

/// A node token and a publisher token, as rmw_zenoh writes them.
pub fn seeds() -> Vec<Vec<u8>> {
    let node = "@ros2_lv/0/aabbccddeeff00112233445566778899/0/0/NN/%/%/shroud_bridge";
    let publisher = format!(
        "{}/%shroud%cloud/sensor_msgs::msg::dds_::PointCloud2_/{}/2:2:1,5:,:,:,,",
        node.replace("/0/0/NN/", "/0/1/MP/"),
        "RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5"
    );
    vec![node.as_bytes().to_vec(), publisher.into_bytes()]
}
