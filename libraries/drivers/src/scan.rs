//! A decoded scan: the sensor's sequence number and stamp, and its points in metres.

use shroud_msg::{
    check_point_channels, CloudMessage, CloudView, MessageError, PointChannel, SensorPose,
};

/// One complete sensor scan, as every ingest decoder returns it and every encoder
/// takes it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Scan {
    /// The sensor's scan counter (wraps; CAN carries only its low 16 bits).
    pub sequence: u32,
    /// Acquisition time of the scan, nanoseconds since the Unix epoch.
    pub stamp_ns: u64,
    /// Points in metres, in the sensor's frame.
    pub points: Vec<[f32; 3]>,
    /// One raw return strength per point, when the sensor sends it.
    pub intensity: Option<Vec<f32>>,
    /// Further values per point by name (a radar's velocities and RCS), each
    /// with one value per point; empty for most sensors.
    pub channels: Vec<PointChannel>,
}

impl Scan {
    pub fn new(sequence: u32, stamp_ns: u64, points: Vec<[f32; 3]>) -> Self {
        Self {
            sequence,
            stamp_ns,
            points,
            intensity: None,
            channels: Vec::new(),
        }
    }

    /// The wire message of this scan: its stamp, `sequence` (the caller's
    /// counter, since the sensor's wraps), `source` name, the sensor's `pose`,
    /// its points and intensity.
    pub fn to_message(&self, sequence: u64, source: &str, pose: SensorPose) -> CloudMessage {
        let message = CloudMessage::new(self.stamp_ns, sequence, source, pose, &self.points)
            .with_channels(&self.channels);
        match &self.intensity {
            Some(intensity) => message.with_intensity(intensity),
            None => message,
        }
    }
}

impl Scan {
    /// [`Scan::to_message`] without copies, padded so that a subscriber on the
    /// same machine can read the points in place ([`CloudView::aligned`]).
    /// Fails on channels that are not one value per point or share a name.
    pub fn to_view<'a>(
        &'a self,
        sequence: u64,
        source: &'a str,
        pose: SensorPose,
    ) -> Result<CloudView<'a>, MessageError> {
        check_point_channels(&self.channels, self.points.len())?;
        let view = CloudView::new(self.stamp_ns, sequence, source, pose, &self.points)
            .with_channels(&self.channels);
        match &self.intensity {
            Some(intensity) => view.with_intensity(intensity),
            None => view,
        }
        .aligned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scan_becomes_a_valid_cloud_message() {
        let mut scan = Scan::new(3, 42, vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
        scan.intensity = Some(vec![7.0, 8.0]);
        scan.channels = vec![PointChannel::new("rcs", vec![1.5, -0.5])];
        let message = scan.to_message(9, "serial:/dev/ttyUSB0", SensorPose::default());
        let back = CloudMessage::from_bytes(&message.to_bytes().unwrap()).unwrap();
        assert_eq!(back.stamp_ns, 42);
        assert_eq!(back.sequence, 9);
        assert_eq!(back.point_array().unwrap(), scan.points);
        assert_eq!(back.intensity_array().unwrap(), scan.intensity);
        assert_eq!(back.channel_arrays().unwrap(), scan.channels);
        // The padded view decodes to the same message.
        let view = scan
            .to_view(9, "serial:/dev/ttyUSB0", SensorPose::default())
            .unwrap();
        let bytes = view.to_bytes().unwrap();
        assert_eq!(bytes.len() % 4, 0);
        assert_eq!(CloudMessage::from_bytes(&bytes).unwrap(), back);
    }
}
