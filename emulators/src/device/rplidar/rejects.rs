//! Counts of what the emulated RPLIDAR refused or dropped, by a stable
//! snake_case kind name.

/// Why a host byte, a request or an outgoing byte was dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RejectKind {
    /// A byte outside a request (not 0xA5 where a request must start).
    StrayByte,
    /// A request whose XOR checksum did not match; the device ignores it.
    BadChecksum,
    /// A well-formed request with an opcode the device does not know.
    UnknownCommand,
    /// A known opcode this model does not support (0xFF and 0xF0 on the A1).
    Unsupported,
    /// A request whose payload is too short, or names an unknown scan mode
    /// or configuration key.
    BadPayload,
    /// A partial request abandoned after 5 s without its next byte
    /// (protocol PDF §2: every byte must follow within 5 s).
    RequestTimeout,
    /// A byte that arrived while the core was rebooting after RESET.
    WhileRebooting,
    /// A scan request refused in Protection Stop (health error).
    ProtectionStop,
    /// An outgoing byte dropped because nobody polled and the transmit
    /// buffer was full.
    TxOverflow,
    /// Scan output skipped because the host went more than a second without
    /// polling (as a real host's receive buffer would overflow).
    StalledHost,
}

impl RejectKind {
    /// Every kind, in declaration order.
    pub const ALL: [RejectKind; 10] = [
        RejectKind::StrayByte,
        RejectKind::BadChecksum,
        RejectKind::UnknownCommand,
        RejectKind::Unsupported,
        RejectKind::BadPayload,
        RejectKind::RequestTimeout,
        RejectKind::WhileRebooting,
        RejectKind::ProtectionStop,
        RejectKind::TxOverflow,
        RejectKind::StalledHost,
    ];

    /// The kind's stable snake_case name.
    pub fn name(self) -> &'static str {
        match self {
            RejectKind::StrayByte => "stray_byte",
            RejectKind::BadChecksum => "bad_checksum",
            RejectKind::UnknownCommand => "unknown_command",
            RejectKind::Unsupported => "unsupported",
            RejectKind::BadPayload => "bad_payload",
            RejectKind::RequestTimeout => "request_timeout",
            RejectKind::WhileRebooting => "while_rebooting",
            RejectKind::ProtectionStop => "protection_stop",
            RejectKind::TxOverflow => "tx_overflow",
            RejectKind::StalledHost => "stalled_host",
        }
    }

    fn index(self) -> usize {
        self as usize
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
        self.counts[kind.index()]
    }

    /// Every kind's name with its count, in declaration order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        RejectKind::ALL
            .iter()
            .map(|kind| (kind.name(), self.get(*kind)))
    }

    pub(crate) fn add(&mut self, kind: RejectKind, n: u64) {
        let slot = &mut self.counts[kind.index()];
        *slot = slot.saturating_add(n);
    }

    pub(crate) fn count(&mut self, kind: RejectKind) {
        self.add(kind, 1);
    }
}
