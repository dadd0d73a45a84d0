//! RadarConfiguration on connect: the frame, its confirmation, resends,
//! giving up, and a read-only bus.

use super::support::*;
use crate::ars408::{
    Ars408Config, Ars408Driver, Ars408Error, RadarOutput, RadarSettings, CONFIG_RESENDS,
};
use crate::can::CanFrame;
use crate::can_device::{CanDeviceDriver, CanDriverOutput};
use crate::dbc::{builtin, CanDatabase};
use crate::device::DeviceState;

fn configured() -> Ars408Config {
    Ars408Config {
        settings: Some(RadarSettings {
            max_distance_m: Some(200),
            send_quality: Some(true),
            ..RadarSettings::default()
        }),
        ..Ars408Config::default()
    }
}

/// By hand: byte 0 = MaxDistance_valid (bit 0) | OutputType_valid (bit 3) |
/// SendQuality_valid (bit 4) = 0x19; MaxDistance 15|10 raw 100 = 0b00011001_00
/// -> byte 1 = 0x19, byte 2 bits 7-6 = 0; OutputType 36|2 = 2 -> byte 4 bit 4
/// = 0x10; SendQuality 42|1 -> byte 5 bit 2 = 0x04.
const CONFIG_FRAME: [u8; 8] = [0x19, 0x19, 0x00, 0x00, 0x10, 0x04, 0x00, 0x00];

fn sends(out: &[CanDriverOutput]) -> Vec<CanFrame> {
    out.iter()
        .filter_map(|o| match o {
            CanDriverOutput::Send(f) => Some(*f),
            _ => None,
        })
        .collect()
}

fn asked_state() -> State {
    State {
        max_distance_m: 200,
        output_type: 2,
        quality: true,
        ..State::default()
    }
}

#[test]
fn connect_sends_the_configuration_and_a_matching_state_confirms_it() {
    let (mut d, out) = driver(configured());
    let sent = sends(&out);
    assert_eq!(sent.len(), 1);
    assert_eq!(sent[0].id, 0x200);
    assert!(!sent[0].extended);
    assert_eq!(sent[0].payload(), &CONFIG_FRAME);
    assert!(out.contains(&CanDriverOutput::State(DeviceState::Configuring)));
    assert_eq!(d.stats().commands, 1);
    // Clusters arriving while configuring are still assembled.
    let statuses = [cluster_status(0, 0, 0, 1), cluster_status(0, 0, 0, 2)];
    let c = clouds(&feed(&mut d, 10, &statuses));
    assert_eq!(c.len(), 1);
    assert_eq!(d.state(), &DeviceState::Configuring);
    // A state that does not match yet: still configuring.
    feed(&mut d, 20, &[radar_state(0, State::clusters(false))]);
    assert_eq!(d.state(), &DeviceState::Configuring);
    let out = feed(&mut d, 70, &[radar_state(0, asked_state())]);
    assert!(out.contains(&CanDriverOutput::State(DeviceState::Streaming)));
    assert_eq!(d.stats().notes("config_confirmed"), 1);
    // No resend after confirmation.
    let mut out = Vec::new();
    d.poll(host(5000), &mut out);
    assert!(sends(&out).is_empty());
}

#[test]
fn an_unconfirmed_configuration_is_resent_then_given_up() {
    let (mut d, _) = driver(configured());
    let wrong = State::clusters(false);
    let mut all = Vec::new();
    let mut t = 0;
    // A non-matching RadarState every 50 ms and a poll after each, for 5 s.
    while t <= 5000 {
        d.receive(&at(radar_state(0, wrong), t), &mut all);
        d.poll(host(t), &mut all);
        t += 50;
    }
    let sent = sends(&all);
    // The connect's own send is not in `all`.
    assert_eq!(sent.len(), CONFIG_RESENDS as usize);
    assert!(sent.iter().all(|f| f.payload() == CONFIG_FRAME));
    assert_eq!(d.stats().commands, 1 + u64::from(CONFIG_RESENDS));
    assert_eq!(d.stats().errors("config_not_confirmed"), 1);
    assert_eq!(d.state(), &DeviceState::Streaming);
    let health: Vec<_> = all
        .iter()
        .filter_map(|o| match o {
            CanDriverOutput::Health { ok, detail } => Some((*ok, detail.clone())),
            _ => None,
        })
        .collect();
    let (ok, detail) = health.last().unwrap();
    assert!(!ok);
    assert_eq!(
        detail,
        "configuration not confirmed: max distance 200 m (radar reports 196 m), \
         send quality true (radar reports false)"
    );
}

#[test]
fn resends_come_one_second_apart() {
    let (mut d, _) = driver(configured());
    let mut out = Vec::new();
    d.poll(host(999), &mut out);
    assert!(sends(&out).is_empty());
    d.poll(host(1000), &mut out);
    assert_eq!(sends(&out).len(), 1);
    d.poll(host(1999), &mut out);
    assert_eq!(sends(&out).len(), 1);
    d.poll(host(2000), &mut out);
    d.poll(host(3000), &mut out);
    assert_eq!(sends(&out).len(), CONFIG_RESENDS as usize);
    assert_eq!(d.stats().errors("config_not_confirmed"), 0);
    d.poll(host(4000), &mut out);
    assert_eq!(sends(&out).len(), CONFIG_RESENDS as usize);
    assert_eq!(d.stats().errors("config_not_confirmed"), 1);
    // No radar frame at all: health says so.
    assert!(out.contains(&CanDriverOutput::Health {
        ok: false,
        detail: "configuration not confirmed: no RadarState received".into()
    }));
}

#[test]
fn a_read_only_bus_sends_nothing_and_notes_it() {
    let mut d = Ars408Driver::new(configured(), builtin("ars408").unwrap()).unwrap();
    let mut out = Vec::new();
    d.connect(host(0), false, &mut out);
    assert!(sends(&out).is_empty());
    assert_eq!(d.stats().notes("config_not_sent"), 1);
    assert_eq!(d.state(), &DeviceState::Connecting);
    feed(&mut d, 1, &[radar_state(0, State::clusters(false))]);
    assert_eq!(d.state(), &DeviceState::Streaming);
    d.poll(host(5000), &mut out);
    assert!(sends(&out).is_empty());
    assert_eq!(d.stats().errors("config_not_confirmed"), 0);
}

#[test]
fn bad_settings_and_incomplete_databases_are_named() {
    let bad =
        |config: Ars408Config| Ars408Driver::new(config, builtin("ars408").unwrap()).unwrap_err();
    let e = bad(Ars408Config {
        sensor_id: 8,
        ..Ars408Config::default()
    });
    assert!(
        matches!(
            e,
            Ars408Error::BadSetting {
                name: "sensor_id",
                ..
            }
        ),
        "{e}"
    );
    let e = bad(Ars408Config {
        settings: Some(RadarSettings {
            max_distance_m: Some(201),
            ..RadarSettings::default()
        }),
        ..Ars408Config::default()
    });
    assert!(
        matches!(
            e,
            Ars408Error::BadSetting {
                name: "max_distance_m",
                ..
            }
        ),
        "{e}"
    );
    let e = bad(Ars408Config {
        settings: Some(RadarSettings {
            radar_power: Some(4),
            ..RadarSettings::default()
        }),
        ..Ars408Config::default()
    });
    assert!(
        matches!(
            e,
            Ars408Error::BadSetting {
                name: "radar_power",
                ..
            }
        ),
        "{e}"
    );
    // A database without the quality message.
    let text = "VERSION \"\"\n\nBS_:\n\nBU_: R\n\n\
        BO_ 513 RadarState: 8 R\n SG_ PersistentError : 21|1@0+ (1,0) [0|1] \"\" R\n";
    let db = CanDatabase::parse(text).unwrap();
    let e = Ars408Driver::new(Ars408Config::default(), db).unwrap_err();
    assert!(
        matches!(
            e,
            Ars408Error::MissingSignal { .. } | Ars408Error::MissingMessage(_)
        ),
        "{e}"
    );
    assert!(e.to_string().contains("RadarState"), "{e}");
}

#[test]
fn objects_output_type_is_asked_as_1() {
    let config = Ars408Config {
        output: RadarOutput::Objects,
        settings: Some(RadarSettings {
            send_ext_info: Some(true),
            ..RadarSettings::default()
        }),
        ..Ars408Config::default()
    };
    let (_, out) = driver(config);
    // OutputType_valid (bit 3) | SendExtInfo_valid (bit 5) = 0x28; OutputType
    // 1 -> byte 4 bit 3 = 0x08; SendExtInfo 43|1 -> byte 5 bit 3 = 0x08.
    assert_eq!(sends(&out)[0].payload(), &[0x28, 0, 0, 0, 0x08, 0x08, 0, 0]);
}

#[test]
fn a_radar_that_forgets_its_confirmed_configuration_is_configured_again() {
    let (mut d, _) = driver(configured());
    feed(&mut d, 10, &[radar_state(0, asked_state())]);
    assert_eq!(d.stats().notes("config_confirmed"), 1);
    // It restarts with its stored settings (objects, 196 m): configure again.
    let forgot = State {
        max_distance_m: 196,
        output_type: 1,
        ..State::default()
    };
    let out = feed(&mut d, 2000, &[radar_state(0, forgot)]);
    let sent = sends(&out);
    assert_eq!(sent.len(), 1, "{out:?}");
    assert_eq!(sent[0].payload(), &CONFIG_FRAME);
    assert_eq!(d.stats().errors("config_lost"), 1);
    // A state that matches again confirms again.
    feed(&mut d, 2100, &[radar_state(0, asked_state())]);
    assert_eq!(d.stats().notes("config_confirmed"), 2);
}

#[test]
fn a_radar_sending_the_other_list_is_unhealthy_even_unconfigured() {
    let (mut d, _) = driver(Ars408Config::default());
    let objects = State {
        output_type: 1,
        ..State::default()
    };
    let out = feed(&mut d, 10, &[radar_state(0, objects)]);
    let health = out.iter().find_map(|o| match o {
        CanDriverOutput::Health { ok, detail } => Some((*ok, detail.clone())),
        _ => None,
    });
    let (ok, detail) = health.expect("a health report");
    assert!(!ok);
    assert!(detail.contains("outputs objects"), "{detail}");
}
