//! The sensor clock: 24-bit unwrap, TM1 offset, stamp guard, first-ray delay.

use crate::device::{DeviceStats, HostTime};
use crate::scip::*;

#[test]
fn unwrap_follows_the_24_bit_wrap() {
    let mut clock = DeviceClock::default();
    assert_eq!(clock.unwrap(0xFF_FFF0), 0xFF_FFF0);
    assert_eq!(clock.unwrap(0xFF_FFFF), 0xFF_FFFF);
    assert_eq!(clock.unwrap(0x00_0005), WRAP_MS + 5);
    assert_eq!(clock.unwrap(0x00_0100), WRAP_MS + 0x100);
    // A slightly older reading goes back, not forward by a whole wrap.
    assert_eq!(clock.unwrap(0xFF_FFFE), WRAP_MS - 2);
    assert_eq!(clock.unwrap(0x00_0200), WRAP_MS + 0x200);
    // Bits above 24 are ignored.
    assert_eq!(clock.unwrap(0x0100_0300), WRAP_MS + 0x300);
    clock.reset();
    assert_eq!(clock.unwrap(7), 7);
}

#[test]
fn unwrap_survives_many_wraps() {
    let mut clock = DeviceClock::default();
    let step = 3_000_000u64; // ms, less than half the wrap
    let mut t = 0u64;
    for _ in 0..40 {
        t += step;
        assert_eq!(clock.unwrap((t % (1 << 24)) as u32), t as i64);
    }
}

#[test]
fn sync_takes_the_fastest_round_trip_midpoint() {
    let mut sync = ClockSync::default();
    let at = |ms: u64| HostTime::new(ms * 1_000_000, 1_000_000_000_000 + ms * 1_000_000);
    // Sensor ms 500 read at host ms 12 in a 4 ms trip: offset from midpoint.
    sync.add(500, at(10), at(14));
    assert_eq!(
        sync.offset_ns(),
        Some(1_000_000_000_000 + 12_000_000 - 500_000_000)
    );
    // A slower trip does not replace it.
    sync.add(600, at(100), at(120));
    assert_eq!(sync.best_rtt_ns(), Some(4_000_000));
    // A faster one does.
    sync.add(700, at(200), at(202));
    assert_eq!(sync.best_rtt_ns(), Some(2_000_000));
    assert_eq!(
        sync.offset_ns(),
        Some(1_000_000_000_000 + 201_000_000 - 700_000_000)
    );
}

#[test]
fn stamp_maps_device_time_and_adds_the_first_ray_delay() {
    let mut stamper = ScanStamper::default();
    let mut stats = DeviceStats::default();
    stamper.set_offset(Some(1_000_000_000_000));
    let timing = ScanTiming {
        device_ms: 2_000,
        first_ray_delay_ns: 16_000_000,
        sweep_ns: 66_000_000,
        transfer_ns: 0,
        held_ns: 0,
        // The last ray 16 + 66 ms after the stamp, its bytes 10 ms later.
        arrival: HostTime::new(0, 1_000_000_000_000 + 2_000_000_000 + 92_000_000),
    };
    let stamp = stamper.stamp(&timing, &mut stats);
    assert_eq!(stamp, 1_000_000_000_000 + 2_000_000_000 + 16_000_000);
    assert_eq!(stats.errors("clock_mismatch"), 0);
    assert!(!stamper.is_fallen_back());
}

#[test]
fn implausible_stamp_falls_back_until_the_next_sync() {
    let mut stamper = ScanStamper::default();
    let mut stats = DeviceStats::default();
    stamper.set_offset(Some(0));
    let arrival = HostTime::new(0, 10_000_000_000);
    let future = ScanTiming {
        device_ms: 10_500,
        first_ray_delay_ns: 0,
        sweep_ns: 70_000_000,
        transfer_ns: 0,
        held_ns: 0,
        arrival,
    };
    assert_eq!(
        stamper.stamp(&future, &mut stats),
        10_000_000_000 - 70_000_000
    );
    assert_eq!(stats.errors("clock_mismatch"), 1);
    // Now plausible, but the driver keeps arrival stamps until a new sync.
    let fine = ScanTiming {
        device_ms: 9_900,
        ..future
    };
    assert_eq!(
        stamper.stamp(&fine, &mut stats),
        10_000_000_000 - 70_000_000
    );
    assert_eq!(stats.errors("clock_mismatch"), 1);
    stamper.set_offset(Some(0));
    assert_eq!(stamper.stamp(&fine, &mut stats), 9_900_000_000);
    // Too old (the last ray more than 100 ms before the arrival) is a
    // mismatch too: a sensor clock drifted or reset.
    let stale = ScanTiming {
        device_ms: 9_820,
        ..future
    };
    assert_eq!(
        stamper.stamp(&stale, &mut stats),
        10_000_000_000 - 70_000_000
    );
    assert_eq!(stats.errors("clock_mismatch"), 2);
    // So is a last ray after its own bytes arrived (beyond the 5 ms slack).
    stamper.set_offset(Some(0));
    let early = ScanTiming {
        device_ms: 9_936,
        ..future
    };
    assert_eq!(
        stamper.stamp(&early, &mut stats),
        10_000_000_000 - 70_000_000
    );
    assert_eq!(stats.errors("clock_mismatch"), 3);
    // A polled scan may have waited a revolution in the sensor.
    stamper.set_offset(Some(0));
    let held = ScanTiming {
        device_ms: 9_780,
        held_ns: 100_000_000,
        ..future
    };
    assert_eq!(stamper.stamp(&held, &mut stats), 9_780_000_000);
    assert_eq!(stats.errors("clock_mismatch"), 3);
    // Drift since the sync widens the window: 100 ppm of 10 s is 1 ms, so the
    // first ray that was 1 ms too late above is plausible now.
    stamper.set_sync(Some(0), 0, 0);
    let drifted = ScanTiming {
        device_ms: 9_936,
        ..future
    };
    assert_eq!(stamper.stamp(&drifted, &mut stats), 9_936_000_000);
    assert_eq!(stats.errors("clock_mismatch"), 3);
    // On a slow line the reply's transfer time widens the window by itself.
    stamper.set_offset(Some(0));
    let slow = ScanTiming {
        device_ms: 8_900,
        transfer_ns: 1_100_000_000,
        ..future
    };
    assert_eq!(stamper.stamp(&slow, &mut stats), 8_900_000_000);
    assert_eq!(stats.errors("clock_mismatch"), 3);
}

#[test]
fn first_ray_delay_counts_steps_from_the_rear_centre() {
    let urg = ScipGeometry {
        dmin_mm: 20,
        dmax_mm: 5600,
        ares: 1024,
        amin: 44,
        amax: 725,
        afrt: 384,
        scan_rpm: 600,
    };
    // Rear centre = step 384 - 512 = -128; step 44 is 172 steps later.
    assert_eq!(
        first_ray_delay_ns(&urg, 44),
        (172.0 * 100e6 / 1024.0f64).round() as u64
    );
    // The front step is half a revolution after the rear.
    assert_eq!(first_ray_delay_ns(&urg, 384), 50_000_000);
    // Step 896 is the rear itself.
    assert_eq!(first_ray_delay_ns(&urg, 896), 0);
}
