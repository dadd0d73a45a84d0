//! The two-character status codes of SCIP 2.0 replies.
//!
//! Sources: spec §8 (per-command codes, pp. 11-21) and §9 "Response to
//! Invalid Commands" (p. 23); `0L` (abnormal state) from
//! seqsense/urg_stamped issue #70 and its `src/urg_sim/urg_sim.cpp`.

/// A reply status: two ASCII characters, sent followed by their sum.
pub(crate) type Status = [u8; 2];

/// Command accepted.
pub(crate) const OK: Status = *b"00";
/// Scan message of a running MD/MS/ME/ND/NE stream (spec p. 11).
pub(crate) const STREAMING: Status = *b"99";
/// Per-command codes 01..07 (meaning depends on the command).
pub(crate) const CODE_01: Status = *b"01";
pub(crate) const CODE_02: Status = *b"02";
pub(crate) const CODE_03: Status = *b"03";
pub(crate) const CODE_04: Status = *b"04";
pub(crate) const CODE_05: Status = *b"05";
pub(crate) const CODE_06: Status = *b"06";
pub(crate) const CODE_07: Status = *b"07";
/// GD/GS/GE/HD/HE: the laser is off (spec p. 13).
pub(crate) const LASER_OFF: Status = *b"10";
/// §9: buffer shortage (used for a line longer than the input buffer).
pub(crate) const BUFFER_SHORTAGE: Status = *b"0B";
/// §9: command with insufficient parameters.
pub(crate) const TOO_SHORT: Status = *b"0C";
/// §9 "Undefined Command 1": used for parameters followed by characters that
/// are not a `;string` (as urg_stamped's simulator does).
pub(crate) const EXTRA_CHARACTERS: Status = *b"0D";
/// §9 "Undefined Command 2": unknown command symbol, and any command but TM
/// in time-adjust mode (urg_c `connect_urg_device()` reads a `0Ee` reply to
/// QT as "the sensor is in TM mode").
pub(crate) const UNDEFINED: Status = *b"0E";
/// §9: the string characters exceed 16 letters.
pub(crate) const TAG_TOO_LONG: Status = *b"0G";
/// §9: the string characters hold an invalid letter.
pub(crate) const TAG_INVALID: Status = *b"0H";
/// The sensor is in the abnormal state; only RB recovers it.
pub(crate) const ABNORMAL: Status = *b"0L";
