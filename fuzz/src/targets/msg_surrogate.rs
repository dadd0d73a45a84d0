//! Surrogate messages (`SurrogateMessage::from_bytes`): decoded and validated
//! into a `Surrogate`; both must survive a round trip.

use shroud_surrogate::SurrogateWire;
use crate::check::{named, same};
use crate::round_trip;
use shroud_msg::SurrogateMessage;

pub fn run(data: &[u8]) {
    match SurrogateMessage::from_bytes(data) {
        Ok((message, surrogate)) => {
            let (again, surrogate_again) = round_trip::message(
                &(message, surrogate),
                |(m, _)| m.to_bytes(),
                SurrogateMessage::from_bytes,
            );
            let rebuilt = again.to_surrogate().expect("a decoded message converts");
            same(&surrogate_again, &rebuilt, "surrogates of the same message");
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let message = SurrogateMessage::from_surrogate(&crate::seeds::surrogate(), 5, 2, "lidar", 1000);
    vec![message.to_bytes().expect("the seed message encodes")]
}
