//! A parsed and checked CAN database: DBC text in (parsed by `can-dbc`), our
//! [`MessageSpec`]s out, indexed by CAN id for decoding. Everything the codec
//! relies on is checked here once, so decoding never has to.

use std::collections::BTreeMap;

use can_dbc::{
    ByteOrder as DbcOrder, Dbc, MessageId, MultiplexIndicator, NumericValue,
    SignalExtendedValueType, ValueType,
};

use super::{ByteOrder, DbcError, DecodedMessage, MessageSpec, Multiplex, SignalSpec};
use crate::can::{CanFrame, MAX_EXTENDED_ID, MAX_STANDARD_ID};

/// Largest DBC text accepted (the vendor files of big vehicles are ~1 MB).
pub const MAX_DBC_BYTES: usize = 4 << 20;
/// Most messages one database may define.
pub const MAX_MESSAGES: usize = 4096;

/// The pseudo-message Vector tools put unassigned signals in; not a frame.
const INDEPENDENT_SIGNALS: &str = "VECTOR__INDEPENDENT_SIG_MSG";
/// DBC marks an extended id by setting bit 31 of the written number.
const EXTENDED_FLAG: u64 = 1 << 31;

/// The messages of a DBC file and an index by `(id, extended)`.
#[derive(Debug, Clone, PartialEq)]
pub struct CanDatabase {
    messages: Vec<MessageSpec>,
    by_id: BTreeMap<(u32, bool), usize>,
}

impl CanDatabase {
    /// Parses and checks DBC text: size first, then syntax, then every message
    /// and signal (see [`DbcError`] for what is refused).
    pub fn parse(text: &str) -> Result<Self, DbcError> {
        if text.len() > MAX_DBC_BYTES {
            return Err(DbcError::TooLarge {
                bytes: text.len(),
                limit: MAX_DBC_BYTES,
            });
        }
        let dbc = Dbc::try_from(text).map_err(|e| DbcError::Parse(e.to_string()))?;
        let parsed: Vec<_> = dbc
            .messages
            .iter()
            .filter(|m| m.name != INDEPENDENT_SIGNALS)
            .collect();
        if parsed.len() > MAX_MESSAGES {
            return Err(DbcError::TooManyMessages {
                found: parsed.len(),
                limit: MAX_MESSAGES,
            });
        }
        refuse_unsupported(&dbc)?;
        let written = written_ids(text);
        let messages = parsed
            .into_iter()
            .map(|m| convert_message(m, &written))
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_messages(messages)
    }

    pub fn messages(&self) -> &[MessageSpec] {
        &self.messages
    }

    pub fn message(&self, name: &str) -> Option<&MessageSpec> {
        self.messages.iter().find(|m| m.name == name)
    }

    pub fn message_by_id(&self, id: u32, extended: bool) -> Option<&MessageSpec> {
        self.by_id
            .get(&(id, extended))
            .and_then(|&i| self.messages.get(i))
    }

    /// `None`: the frame's id is not in the database (another device's frame).
    pub fn decode(&self, frame: &CanFrame) -> Option<Result<DecodedMessage<'_>, DbcError>> {
        self.message_by_id(frame.id, frame.extended)
            .map(|m| m.decode(frame))
    }

    /// Encodes the message named (see [`MessageSpec::encode`]).
    pub fn encode(&self, message: &str, values: &[(&str, f64)]) -> Result<CanFrame, DbcError> {
        self.message(message)
            .ok_or_else(|| DbcError::UnknownMessage(message.to_string()))?
            .encode(values)
    }

    /// The same database with every message's id moved by `delta` (the
    /// ARS408's sensor-ID offset, n * 0x10: research note §2.2); `BadId` when
    /// a moved id leaves its format's range.
    pub fn with_id_offset(&self, delta: u32) -> Result<Self, DbcError> {
        let mut messages = self.messages.clone();
        for m in &mut messages {
            let max = if m.extended {
                MAX_EXTENDED_ID
            } else {
                MAX_STANDARD_ID
            };
            m.id =
                m.id.checked_add(delta)
                    .filter(|&id| id <= max)
                    .ok_or_else(|| DbcError::BadId {
                        message: m.name.clone(),
                        id: m.id.saturating_add(delta),
                    })?;
        }
        Self::from_messages(messages)
    }

    /// Indexes checked messages, refusing shared names and ids.
    fn from_messages(messages: Vec<MessageSpec>) -> Result<Self, DbcError> {
        let mut by_id = BTreeMap::new();
        let mut names = BTreeMap::new();
        for (i, m) in messages.iter().enumerate() {
            if names.insert(m.name.as_str(), i).is_some() {
                return Err(DbcError::DuplicateMessage(m.name.clone()));
            }
            if let Some(first) = by_id.insert((m.id, m.extended), i) {
                return Err(DbcError::DuplicateId {
                    id: m.id,
                    extended: m.extended,
                    first: messages
                        .get(first)
                        .map(|f| f.name.clone())
                        .unwrap_or_default(),
                    second: m.name.clone(),
                });
            }
        }
        Ok(Self { messages, by_id })
    }
}

/// IEEE float signals (`SIG_VALTYPE_`) and extended multiplexing
/// (`SG_MUL_VAL_`) are outside this codec; refuse rather than misdecode.
fn refuse_unsupported(dbc: &Dbc) -> Result<(), DbcError> {
    let message_name = |id: MessageId| {
        dbc.messages
            .iter()
            .find(|m| m.id == id)
            .map_or_else(|| format!("{:#x}", id.raw()), |m| m.name.clone())
    };
    for v in &dbc.signal_extended_value_type_list {
        if v.signal_extended_value_type != SignalExtendedValueType::SignedOrUnsignedInteger {
            return Err(DbcError::BadSignal {
                message: message_name(v.message_id),
                signal: v.signal_name.clone(),
                reason: "IEEE float signals (SIG_VALTYPE_) are not supported".into(),
            });
        }
    }
    if let Some(x) = dbc.extended_multiplex.first() {
        return Err(DbcError::BadSignal {
            message: message_name(x.message_id),
            signal: x.signal_name.clone(),
            reason: "extended multiplexing (SG_MUL_VAL_) is not supported".into(),
        });
    }
    Ok(())
}

/// The ids as written on the `BO_ <id> <name>:` lines, by message name.
/// `can-dbc` keeps only the low 16 bits of a standard id and the low 29 of an
/// extended one, so an id too large for its format would otherwise pass as
/// some other, valid id.
fn written_ids(text: &str) -> BTreeMap<&str, Vec<u64>> {
    let mut ids = BTreeMap::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        if words.next() != Some("BO_") {
            continue;
        }
        let (Some(id), Some(name)) = (words.next(), words.next()) else {
            continue;
        };
        let name = name.split(':').next().unwrap_or(name);
        if let Ok(id) = id.parse::<u64>() {
            ids.entry(name).or_insert_with(Vec::new).push(id);
        }
    }
    ids
}

fn convert_message(
    m: &can_dbc::Message,
    written: &BTreeMap<&str, Vec<u64>>,
) -> Result<MessageSpec, DbcError> {
    let (id, extended) = match m.id {
        MessageId::Standard(id) => (u32::from(id), false),
        MessageId::Extended(id) => (id, true),
    };
    let bad_id = |id: u64| DbcError::BadId {
        message: m.name.clone(),
        id: u32::try_from(id).unwrap_or(u32::MAX),
    };
    // (Two messages of one name are refused later as such.)
    if let Some(raw) = written.get(m.name.as_str()) {
        if let Some(&first) = raw.first() {
            if !raw.contains(&u64::from(m.id.raw())) {
                return Err(bad_id(first & !EXTENDED_FLAG));
            }
        }
    }
    if !extended && id > MAX_STANDARD_ID {
        return Err(bad_id(id.into()));
    }
    let len = u8::try_from(m.size)
        .ok()
        .filter(|&len| len <= 8)
        .ok_or_else(|| DbcError::BadLength {
            message: m.name.clone(),
            len: m.size,
        })?;
    let mut signals: Vec<SignalSpec> = Vec::with_capacity(m.signals.len().min(64));
    for s in &m.signals {
        let signal = convert_signal(&m.name, s, len)?;
        if signals.iter().any(|t| t.name == signal.name) {
            return Err(DbcError::DuplicateSignal {
                message: m.name.clone(),
                signal: signal.name,
            });
        }
        signals.push(signal);
    }
    check_multiplexing(&m.name, &signals)?;
    Ok(MessageSpec {
        name: m.name.clone(),
        id,
        extended,
        len,
        signals,
    })
}

fn convert_signal(message: &str, s: &can_dbc::Signal, len: u8) -> Result<SignalSpec, DbcError> {
    let bad = |reason: &str| DbcError::BadSignal {
        message: message.to_string(),
        signal: s.name.clone(),
        reason: reason.to_string(),
    };
    let size = u8::try_from(s.size)
        .ok()
        .filter(|size| (1..=64).contains(size))
        .ok_or_else(|| bad(&format!("size {} is not 1..=64 bits", s.size)))?;
    if !s.factor.is_finite() || s.factor == 0.0 {
        return Err(bad(&format!("factor {} is zero or not finite", s.factor)));
    }
    if !s.offset.is_finite() {
        return Err(bad(&format!("offset {} is not finite", s.offset)));
    }
    let (min, max) = (number(s.min), number(s.max));
    if !min.is_finite() || !max.is_finite() || min > max {
        return Err(bad(&format!(
            "range [{min}|{max}] is not finite and ordered"
        )));
    }
    let multiplex = match s.multiplexer_indicator {
        MultiplexIndicator::Plain => Multiplex::Plain,
        MultiplexIndicator::Multiplexor => Multiplex::Multiplexor,
        MultiplexIndicator::MultiplexedSignal(v) => Multiplex::Multiplexed(v),
        MultiplexIndicator::MultiplexorAndMultiplexedSignal(_) => {
            return Err(bad("extended multiplexing (m<n>M) is not supported"))
        }
    };
    let out_of_frame = || DbcError::SignalOutOfFrame {
        message: message.to_string(),
        signal: s.name.clone(),
        start_bit: s.start_bit,
        size: s.size,
        len,
    };
    let spec = SignalSpec {
        name: s.name.clone(),
        start_bit: u16::try_from(s.start_bit).map_err(|_| out_of_frame())?,
        size,
        order: match s.byte_order {
            DbcOrder::LittleEndian => ByteOrder::Intel,
            DbcOrder::BigEndian => ByteOrder::Motorola,
        },
        signed: s.value_type == ValueType::Signed,
        factor: s.factor,
        offset: s.offset,
        min,
        max,
        unit: s.unit.clone(),
        multiplex,
    };
    if !spec.fits(len) {
        return Err(out_of_frame());
    }
    Ok(spec)
}

fn number(v: NumericValue) -> f64 {
    match v {
        NumericValue::Uint(v) => v as f64,
        NumericValue::Int(v) => v as f64,
        NumericValue::Double(v) => v,
    }
}

/// At most one multiplexor, and one there whenever a signal is multiplexed.
fn check_multiplexing(message: &str, signals: &[SignalSpec]) -> Result<(), DbcError> {
    let bad = |reason: &str| DbcError::BadMultiplex {
        message: message.to_string(),
        reason: reason.to_string(),
    };
    let multiplexors = signals
        .iter()
        .filter(|s| s.multiplex == Multiplex::Multiplexor)
        .count();
    if multiplexors > 1 {
        return Err(bad("more than one multiplexor (M) signal"));
    }
    let multiplexed = signals
        .iter()
        .any(|s| matches!(s.multiplex, Multiplex::Multiplexed(_)));
    if multiplexed && multiplexors == 0 {
        return Err(bad("multiplexed (m<n>) signals without a multiplexor (M)"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_ids_are_read_by_name() {
        let ids = written_ids("BO_ 70000 Big: 8 X\n BO_ 2147483650 Ext : 8 X\nBO_ x Y: 1 X\n");
        assert_eq!(ids.get("Big"), Some(&vec![70000]));
        assert_eq!(ids.get("Ext"), Some(&vec![2_147_483_650]));
        assert_eq!(ids.len(), 2);
    }

    #[test]
    fn multiplexing_needs_one_multiplexor() {
        let s = |multiplex| SignalSpec {
            name: "S".into(),
            start_bit: 0,
            size: 1,
            order: ByteOrder::Intel,
            signed: false,
            factor: 1.0,
            offset: 0.0,
            min: 0.0,
            max: 0.0,
            unit: String::new(),
            multiplex,
        };
        assert!(check_multiplexing("M", &[s(Multiplex::Multiplexed(1))]).is_err());
        assert!(
            check_multiplexing("M", &[s(Multiplex::Multiplexor), s(Multiplex::Multiplexor)])
                .is_err()
        );
        assert!(check_multiplexing(
            "M",
            &[s(Multiplex::Multiplexor), s(Multiplex::Multiplexed(1))]
        )
        .is_ok());
    }
}
