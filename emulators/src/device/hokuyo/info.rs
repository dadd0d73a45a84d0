//! The texts of the VV, PP and II replies (spec §8.11-8.13, pp. 20-22).
//! Key names are the real ones; values are a plausible identity for each
//! model (URG-04LX texts after the examples on the URG Network wiki page
//! "scip_status_en"; UTM-30LX product and firmware strings as urg_node /
//! hokuyo_node users report them).

use super::codec::Reply;
use super::model::{HokuyoModel, ModelSpec};

/// What II reports about the sensor's state.
pub(crate) struct SensorState {
    pub(crate) laser_on: bool,
    pub(crate) streaming: bool,
    pub(crate) abnormal: bool,
    /// The RS-232 bit rate setting, if the model has RS-232.
    pub(crate) bit_rate: Option<u32>,
    pub(crate) clock_ms: u32,
}

/// Appends the VV lines: VEND, PROD, FIRM, PROT, SERI.
pub(crate) fn write_version(reply: &mut Reply, model: HokuyoModel) {
    let (product, firmware, serial) = match model {
        HokuyoModel::Urg04lx => (
            "SOKUIKI Sensor URG-04LX",
            "3.1.00(18/Jan./2007)",
            "H0614967",
        ),
        HokuyoModel::Utm30lx => (
            "SOKUIKI Sensor TOP-URG UTM-30LX",
            "1.20.02(16/Jul./2013)",
            "H1012345",
        ),
    };
    reply.key_value("VEND", "Hokuyo Automatic Co.,Ltd.");
    reply.key_value("PROD", product);
    reply.key_value("FIRM", firmware);
    reply.key_value("PROT", "SCIP 2.0");
    reply.key_value("SERI", serial);
}

/// The MODL text shared by PP and II.
fn model_text(model: HokuyoModel) -> &'static str {
    match model {
        HokuyoModel::Urg04lx => "URG-04LX(Hokuyo Automatic Co.,Ltd.)",
        HokuyoModel::Utm30lx => "UTM-30LX",
    }
}

/// Appends the PP lines: MODL, DMIN, DMAX, ARES, AMIN, AMAX, AFRT, SCAN.
pub(crate) fn write_parameters(reply: &mut Reply, model: HokuyoModel, spec: &ModelSpec) {
    reply.key_value("MODL", model_text(model));
    let numbers = [
        ("DMIN", spec.dmin),
        ("DMAX", spec.dmax),
        ("ARES", spec.ares),
        ("AMIN", spec.amin),
        ("AMAX", spec.amax),
        ("AFRT", spec.afrt),
        ("SCAN", spec.scan_rpm),
    ];
    for (key, value) in numbers {
        reply.key_value(key, &value.to_string());
    }
}

/// Appends the II lines: MODL, LASR, SCSP, MESM, SBPS, TIME, STAT. TIME is
/// the 24-bit clock as 6 hex digits (never a ';', unlike a 4-character
/// encoding could be).
pub(crate) fn write_info(
    reply: &mut Reply,
    model: HokuyoModel,
    spec: &ModelSpec,
    state: &SensorState,
) {
    reply.key_value("MODL", model_text(model));
    reply.key_value("LASR", if state.laser_on { "ON" } else { "OFF" });
    reply.key_value("SCSP", &motor_text(model, spec));
    reply.key_value("MESM", measuring_text(model, state));
    reply.key_value("SBPS", &bit_rate_text(spec, state.bit_rate));
    reply.key_value("TIME", &format!("{:06x}", state.clock_ms));
    reply.key_value("STAT", status_text(model, state.abnormal));
}

fn motor_text(model: HokuyoModel, spec: &ModelSpec) -> String {
    match model {
        HokuyoModel::Urg04lx => format!("Initial({}[rpm])<-Default setting by user", spec.scan_rpm),
        HokuyoModel::Utm30lx => format!("{}[rpm]", spec.scan_rpm),
    }
}

fn measuring_text(model: HokuyoModel, state: &SensorState) -> &'static str {
    match (model, state.streaming, state.laser_on) {
        (HokuyoModel::Urg04lx, true, _) => "MEASURING",
        (HokuyoModel::Urg04lx, false, _) => "IDLE",
        (HokuyoModel::Utm30lx, true, _) => "004 Multi_scan",
        (HokuyoModel::Utm30lx, false, true) => "003 Single_scan",
        (HokuyoModel::Utm30lx, false, false) => "000 Idle",
    }
}

fn bit_rate_text(spec: &ModelSpec, bit_rate: Option<u32>) -> String {
    match bit_rate {
        Some(rate) if rate == spec.default_bit_rate => {
            format!("{rate}[bps]<-Default setting by user")
        }
        Some(rate) => format!("{rate}[bps]"),
        None => "USB only".to_string(),
    }
}

fn status_text(model: HokuyoModel, abnormal: bool) -> &'static str {
    match (model, abnormal) {
        (HokuyoModel::Urg04lx, false) => "Sensor works well.",
        (HokuyoModel::Urg04lx, true) => "Sensor is in abnormal state.",
        (HokuyoModel::Utm30lx, false) => "Stable 000 no error.",
        (HokuyoModel::Utm30lx, true) => "Abnormal 0L error.",
    }
}
