//! The two emulated models and their fixed properties: geometry (the PP
//! values), accuracy, error codes and RS-232 bit rates.

/// A Hokuyo lidar model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HokuyoModel {
    /// URG-04LX: 5.6 m, 240°, 10 Hz, USB or RS-232.
    Urg04lx,
    /// UTM-30LX (TOP-URG): 30 m (PP reports 60 m), 270°, 40 Hz, USB, with
    /// intensity (ME/GE) and multi-echo (HD/ND/HE/NE).
    Utm30lx,
}

impl HokuyoModel {
    /// The model's name: `urg-04lx` or `utm-30lx`.
    pub fn name(self) -> &'static str {
        match self {
            HokuyoModel::Urg04lx => "urg-04lx",
            HokuyoModel::Utm30lx => "utm-30lx",
        }
    }

    /// The model called `name` (ASCII case ignored), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        [HokuyoModel::Urg04lx, HokuyoModel::Utm30lx]
            .into_iter()
            .find(|model| model.name().eq_ignore_ascii_case(name))
    }

    pub(crate) fn spec(self) -> &'static ModelSpec {
        match self {
            HokuyoModel::Urg04lx => &URG_04LX,
            HokuyoModel::Utm30lx => &UTM_30LX,
        }
    }
}

/// Range error codes a model reports in place of a distance (values below
/// DMIN are error codes, spec p. 12 tables 3 and 4).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ErrorCodes {
    /// Nothing reflected within range.
    pub(crate) no_return: u32,
    /// A surface closer than DMIN.
    pub(crate) too_near: u32,
    /// A ray lost to the emulated dropout.
    pub(crate) dropout: u32,
}

/// Range accuracy: `near_mm` up to `near_limit_mm`, then either a fixed
/// `far_mm` or `far_fraction` of the range (datasheet values, emulated as
/// the 2-sigma bound of Gaussian noise).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Accuracy {
    pub(crate) near_limit_mm: f64,
    pub(crate) near_mm: f64,
    pub(crate) far_mm: f64,
    pub(crate) far_fraction: f64,
}

impl Accuracy {
    /// The standard deviation of the range noise at `range_mm`.
    pub(crate) fn sigma_mm(&self, range_mm: f64) -> f64 {
        let bound = if range_mm <= self.near_limit_mm {
            self.near_mm
        } else {
            self.far_mm.max(self.far_fraction * range_mm)
        };
        bound / 2.0
    }
}

/// Everything fixed about a model.
#[derive(Debug)]
pub(crate) struct ModelSpec {
    /// PP `DMIN`/`DMAX` (mm).
    pub(crate) dmin: u32,
    pub(crate) dmax: u32,
    /// PP `ARES`: steps per revolution.
    pub(crate) ares: u32,
    /// PP `AMIN`/`AMAX`: first and last measured step.
    pub(crate) amin: u32,
    pub(crate) amax: u32,
    /// PP `AFRT`: the step on the sensor's +x axis.
    pub(crate) afrt: u32,
    /// PP `SCAN`: motor speed (rpm).
    pub(crate) scan_rpm: u32,
    /// Whether ME/GE (range + intensity) exist.
    pub(crate) has_intensity: bool,
    /// Whether the multi-echo commands HD/ND (and, with intensity, HE/NE)
    /// exist.
    pub(crate) has_multi_echo: bool,
    /// SS bit rates the RS-232 port accepts; empty = no RS-232 (SS → 04).
    pub(crate) bit_rates: &'static [u32],
    /// The RS-232 bit rate a USB-connected sensor reports and SS compares
    /// against (the factory default).
    pub(crate) default_bit_rate: u32,
    pub(crate) errors: ErrorCodes,
    pub(crate) accuracy: Accuracy,
}

impl ModelSpec {
    /// Seconds per revolution.
    pub(crate) fn period(&self) -> f64 {
        60.0 / f64::from(self.scan_rpm)
    }
}

/// URG-04LX. Geometry: spec §8.12 example (p. 21): DMIN 20, DMAX 5600,
/// ARES 1024, AMIN 44, AMAX 725, AFRT 384, SCAN 600. Bit rates: spec §4
/// (p. 4): 19.2, 57.6, 115.2, 250, 500, 750 kbps (38.4 "not compatible with
/// URG-04LX"). Accuracy: URG-04LX datasheet, ±10 mm for 60-1000 mm, ±1 % of
/// the range beyond. Error codes: spec table 3 (1 = low reflected
/// intensity, 6 = others).
static URG_04LX: ModelSpec = ModelSpec {
    dmin: 20,
    dmax: 5600,
    ares: 1024,
    amin: 44,
    amax: 725,
    afrt: 384,
    scan_rpm: 600,
    has_intensity: false,
    has_multi_echo: false,
    bit_rates: &[19_200, 57_600, 115_200, 250_000, 500_000, 750_000],
    default_bit_rate: 19_200,
    errors: ErrorCodes {
        no_return: 1,
        too_near: 6,
        dropout: 6,
    },
    accuracy: Accuracy {
        near_limit_mm: 1000.0,
        near_mm: 10.0,
        far_mm: 0.0,
        far_fraction: 0.01,
    },
};

/// UTM-30LX. Geometry as its PP reply reads (DMIN 23, DMAX 60000, ARES
/// 1440, AMIN 0, AMAX 1080, AFRT 540, SCAN 2400): a PP log of a UTM-30LX-EW
/// quoted in a Hokuyo SCIP sample (C# `URGLogRead`, stored code index), the
/// spec's §5 table (p. 5: steps 0/540/1080 of 1440, 270°) and
/// urg_stamped's `urg_sim` (DMIN 23, DMAX 60000). USB only: urg_c's
/// `change_sensor_baudrate()` accepts status 04 to SS. Accuracy: datasheet
/// ±30 mm for 0.1-10 m, ±50 mm for 10-30 m. Error codes: spec table 4
/// (1 = no object in range, 3 = measurement error, 4 = out of range at the
/// near end).
static UTM_30LX: ModelSpec = ModelSpec {
    dmin: 23,
    dmax: 60_000,
    ares: 1440,
    amin: 0,
    amax: 1080,
    afrt: 540,
    scan_rpm: 2400,
    has_intensity: true,
    has_multi_echo: true,
    bit_rates: &[],
    default_bit_rate: 115_200,
    errors: ErrorCodes {
        no_return: 1,
        too_near: 4,
        dropout: 3,
    },
    accuracy: Accuracy {
        near_limit_mm: 10_000.0,
        near_mm: 30.0,
        far_mm: 50.0,
        far_fraction: 0.0,
    },
};
