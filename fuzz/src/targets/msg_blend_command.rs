//! Blend command messages (`BlendCommandMessage::from_bytes`) and the
//! command they carry: a valid command rebuilt into a message is the same.

use crate::check::{named, same};
use crate::round_trip;
use glam::DVec3;
use shroud_shapes::blend::{BlendCommand, LocalAdjust};
use shroud_msg::BlendCommandMessage;

pub fn run(data: &[u8]) {
    let message = match BlendCommandMessage::from_bytes(data) {
        Ok(message) => message,
        Err(e) => return named(&e),
    };
    round_trip::message(
        &message,
        BlendCommandMessage::to_bytes,
        BlendCommandMessage::from_bytes,
    );
    if let Err(e) = message.check_part() {
        named(&e);
    }
    match message.command() {
        Ok(command) => {
            let rebuilt = BlendCommandMessage::new(message.stamp_ns, message.sequence, &command);
            same(
                &Ok::<_, ()>(command),
                &rebuilt.command().map_err(|_| ()),
                "commands",
            );
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let commands = [
        BlendCommand::Drop {
            at: DVec3::new(0.1, 0.2, 0.3),
            normal: Some(DVec3::Z),
        },
        BlendCommand::Adjust(LocalAdjust {
            lift: 0.01,
            spin: 0.5,
            tilt: [0.1, -0.1],
        }),
        BlendCommand::Clear,
        BlendCommand::Commit,
    ];
    commands
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let message = BlendCommandMessage::new(1, i as u64, c).with_part("bracket");
            message.to_bytes().expect("the seed message encodes")
        })
        .collect()
}
