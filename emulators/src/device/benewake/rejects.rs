//! Counts of what the emulated Benewake rangefinder refused or dropped, by a
//! stable snake_case kind name.

/// Why a host byte, a command or an outgoing byte was dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RejectKind {
    /// A byte outside a command frame (not 0x5A where one must start).
    StrayByte,
    /// A command whose length byte is below 4 or above 32.
    BadLength,
    /// A command whose sum did not match, on a model checking sums.
    BadChecksum,
    /// A well-formed command with an ID the model does not know, or a known
    /// ID with the wrong length.
    UnknownCommand,
    /// A command sent to the original TFmini, which has no `5A` command set.
    Unsupported,
    /// A known command with a value the model refuses (unknown output
    /// format, non-standard baud rate, enable flag other than 0/1).
    BadPayload,
    /// A trigger command while the frame rate is not 0, or output is off.
    IgnoredTrigger,
    /// An outgoing byte dropped because nobody polled and the transmit
    /// buffer was full.
    TxOverflow,
    /// Frames skipped because the host went more than a second without
    /// polling.
    StalledHost,
}

impl RejectKind {
    /// Every kind, in declaration order.
    pub const ALL: [RejectKind; 9] = [
        RejectKind::StrayByte,
        RejectKind::BadLength,
        RejectKind::BadChecksum,
        RejectKind::UnknownCommand,
        RejectKind::Unsupported,
        RejectKind::BadPayload,
        RejectKind::IgnoredTrigger,
        RejectKind::TxOverflow,
        RejectKind::StalledHost,
    ];

    /// The kind's stable snake_case name.
    pub fn name(self) -> &'static str {
        match self {
            RejectKind::StrayByte => "stray_byte",
            RejectKind::BadLength => "bad_length",
            RejectKind::BadChecksum => "bad_checksum",
            RejectKind::UnknownCommand => "unknown_command",
            RejectKind::Unsupported => "unsupported",
            RejectKind::BadPayload => "bad_payload",
            RejectKind::IgnoredTrigger => "ignored_trigger",
            RejectKind::TxOverflow => "tx_overflow",
            RejectKind::StalledHost => "stalled_host",
        }
    }
}

/// How many times each [`RejectKind`] happened.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RejectCounts {
    counts: [u64; RejectKind::ALL.len()],
}

impl RejectCounts {
    /// How many times `kind` happened.
    pub fn get(&self, kind: RejectKind) -> u64 {
        self.counts[kind as usize]
    }

    /// Every kind's name with its count, in declaration order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        RejectKind::ALL
            .iter()
            .map(|kind| (kind.name(), self.get(*kind)))
    }

    pub(crate) fn add(&mut self, kind: RejectKind, n: u64) {
        let slot = &mut self.counts[kind as usize];
        *slot = slot.saturating_add(n);
    }

    pub(crate) fn count(&mut self, kind: RejectKind) {
        self.add(kind, 1);
    }
}
