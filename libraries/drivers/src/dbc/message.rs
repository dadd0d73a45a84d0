//! One DBC message (`BO_`): its CAN id, length and signals, and the codec
//! between a whole [`CanFrame`] and named physical values, multiplexing
//! included.

use super::{DbcError, Multiplex, SignalSpec};
use crate::can::CanFrame;

/// A message of a database: a CAN id and the signals its payload carries.
#[derive(Debug, Clone, PartialEq)]
pub struct MessageSpec {
    pub name: String,
    pub id: u32,
    pub extended: bool,
    /// The DLC, 0..=8.
    pub len: u8,
    /// In the DBC's order.
    pub signals: Vec<SignalSpec>,
}

/// Decoded values in the message's signal order; `None` for a multiplexed
/// signal the multiplexor did not select.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedMessage<'a> {
    pub spec: &'a MessageSpec,
    pub values: Vec<Option<f64>>,
}

impl MessageSpec {
    pub fn signal(&self, name: &str) -> Option<&SignalSpec> {
        self.signals.iter().find(|s| s.name == name)
    }

    pub fn signal_index(&self, name: &str) -> Option<usize> {
        self.signals.iter().position(|s| s.name == name)
    }

    /// The `M` signal, if the message is multiplexed.
    pub fn multiplexor(&self) -> Option<&SignalSpec> {
        self.signals
            .iter()
            .find(|s| s.multiplex == Multiplex::Multiplexor)
    }

    /// Every signal's value. `ShortFrame` when the frame carries fewer bytes
    /// than the DLC (longer frames are fine: the extra bytes are ignored); a
    /// remote frame carries none, so it decodes only for a DLC of 0.
    pub fn decode(&self, frame: &CanFrame) -> Result<DecodedMessage<'_>, DbcError> {
        let found = frame.payload().len();
        if found < usize::from(self.len) {
            return Err(DbcError::ShortFrame {
                message: self.name.clone(),
                found,
                expected: usize::from(self.len),
            });
        }
        // Bytes past the payload are zero in a well-formed frame; make sure.
        let mut data = [0u8; 8];
        for (to, from) in data.iter_mut().zip(frame.payload()) {
            *to = *from;
        }
        let selector = self.multiplexor().map(|m| m.raw(&data));
        let values = self
            .signals
            .iter()
            .map(|s| match s.multiplex {
                Multiplex::Multiplexed(v) if selector != Some(v) => None,
                _ => Some(s.decode(&data)),
            })
            .collect();
        Ok(DecodedMessage { spec: self, values })
    }

    /// A data frame of `len` bytes carrying `values` (by signal name; the last
    /// value given for a name wins). Every non-multiplexed signal must be given
    /// (`MissingSignal`), and of the multiplexed ones exactly those the
    /// multiplexor's value selects; values for unselected ones are ignored. A
    /// name the message lacks is `UnknownSignal`. Unspecified bits are 0.
    pub fn encode(&self, values: &[(&str, f64)]) -> Result<CanFrame, DbcError> {
        if let Some((name, _)) = values.iter().find(|(n, _)| self.signal(n).is_none()) {
            return Err(DbcError::UnknownSignal {
                message: self.name.clone(),
                signal: (*name).to_string(),
            });
        }
        let value_of = |signal: &SignalSpec| {
            values
                .iter()
                .rev()
                .find(|(n, _)| *n == signal.name)
                .map(|(_, v)| *v)
                .ok_or_else(|| DbcError::MissingSignal {
                    message: self.name.clone(),
                    signal: signal.name.clone(),
                })
        };
        let mut data = [0u8; 8];
        // The multiplexor first: its raw value decides which signals follow.
        let selector = match self.multiplexor() {
            Some(m) => {
                self.encode_one(m, value_of(m)?, &mut data)?;
                Some(m.raw(&data))
            }
            None => None,
        };
        for signal in &self.signals {
            match signal.multiplex {
                Multiplex::Multiplexor => continue,
                Multiplex::Multiplexed(v) if selector != Some(v) => continue,
                _ => self.encode_one(signal, value_of(signal)?, &mut data)?,
            }
        }
        Ok(CanFrame {
            id: self.id,
            extended: self.extended,
            remote: false,
            len: self.len.min(8),
            data,
        })
    }

    fn encode_one(
        &self,
        signal: &SignalSpec,
        value: f64,
        data: &mut [u8; 8],
    ) -> Result<(), DbcError> {
        signal.encode(value, data).map_err(|e| match e {
            DbcError::ValueOutOfRange {
                signal,
                value,
                min,
                max,
                ..
            } => DbcError::ValueOutOfRange {
                message: self.name.clone(),
                signal,
                value,
                min,
                max,
            },
            other => other,
        })
    }
}

impl DecodedMessage<'_> {
    /// The value of the signal named, if the message has it and it is present.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.spec.signal_index(name).and_then(|i| self.value(i))
    }

    /// The value of the `index`th signal, if present.
    pub fn value(&self, index: usize) -> Option<f64> {
        self.values.get(index).copied().flatten()
    }

    /// The present values, with their signals' names.
    pub fn iter(&self) -> impl Iterator<Item = (&str, f64)> {
        self.spec
            .signals
            .iter()
            .zip(&self.values)
            .filter_map(|(s, v)| v.map(|v| (s.name.as_str(), v)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dbc::ByteOrder;

    fn byte_signal(name: &str, byte: u16, multiplex: Multiplex) -> SignalSpec {
        SignalSpec {
            name: name.into(),
            start_bit: byte * 8,
            size: 8,
            order: ByteOrder::Intel,
            signed: false,
            factor: 1.0,
            offset: 0.0,
            min: 0.0,
            max: 0.0,
            unit: String::new(),
            multiplex,
        }
    }

    fn message() -> MessageSpec {
        MessageSpec {
            name: "M".into(),
            id: 0x10,
            extended: false,
            len: 3,
            signals: vec![
                byte_signal("Sel", 0, Multiplex::Multiplexor),
                byte_signal("A", 1, Multiplex::Multiplexed(0)),
                byte_signal("B", 1, Multiplex::Multiplexed(1)),
                byte_signal("C", 2, Multiplex::Plain),
            ],
        }
    }

    #[test]
    fn decode_needs_the_whole_dlc() {
        let m = message();
        let short = CanFrame::new(0x10, false, &[1, 2]).unwrap();
        assert_eq!(
            m.decode(&short),
            Err(DbcError::ShortFrame {
                message: "M".into(),
                found: 2,
                expected: 3
            })
        );
        let long = CanFrame::new(0x10, false, &[1, 2, 3, 4]).unwrap();
        let d = m.decode(&long).unwrap();
        assert_eq!(d.values, vec![Some(1.0), None, Some(2.0), Some(3.0)]);
        assert_eq!(d.get("B"), Some(2.0));
        assert_eq!(d.get("A"), None);
        assert_eq!(d.iter().count(), 3);
        let remote = CanFrame::remote(0x10, false, 3).unwrap();
        assert!(m.decode(&remote).is_err());
    }

    #[test]
    fn encode_writes_the_selected_signals() {
        let m = message();
        let f = m
            .encode(&[("Sel", 0.0), ("A", 7.0), ("B", 9.0), ("C", 5.0)])
            .unwrap();
        assert_eq!(f.payload(), &[0, 7, 5]);
        assert!(matches!(
            m.encode(&[("Sel", 1.0), ("A", 7.0), ("C", 5.0)]),
            Err(DbcError::MissingSignal { signal, .. }) if signal == "B"
        ));
    }
}
