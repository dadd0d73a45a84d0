//! The JSON surrogate format: `{"format": "shroud-surrogate", "version": 1,
//! "surrogate": {...}}`, the surrogate being the serde form of
//! [`Surrogate`] (fields documented in `docs/formats.md`). Numbers are written in the
//! shortest form that reads back to the same f64, so a round trip is bit-exact.

use super::FormatError;
use serde::de::IgnoredAny;
use serde::{Deserialize, Serialize};
use shroud_surrogate::validate_surrogate;
use shroud_surrogate::Surrogate;

/// The `format` tag of every surrogate document.
pub const SURROGATE_FORMAT_TAG: &str = "shroud-surrogate";
/// The version this build writes and reads.
pub const SURROGATE_JSON_VERSION: u32 = 1;

#[derive(Serialize)]
struct DocumentOut<'a> {
    format: &'a str,
    version: u32,
    surrogate: &'a Surrogate,
}

/// The envelope alone, read first so that a wrong tag or version is reported as
/// such rather than as a mismatch deep inside the surrogate.
#[derive(Deserialize)]
struct Envelope {
    format: String,
    version: u64,
    /// Required here, read by `DocumentIn`.
    #[serde(rename = "surrogate")]
    _surrogate: IgnoredAny,
}

#[derive(Deserialize)]
struct DocumentIn {
    surrogate: Surrogate,
}

/// The surrogate as a pretty-printed JSON document.
pub fn surrogate_to_json(surrogate: &Surrogate) -> Vec<u8> {
    let document = DocumentOut {
        format: SURROGATE_FORMAT_TAG,
        version: SURROGATE_JSON_VERSION,
        surrogate,
    };
    // serde_json fails only on I/O errors (a Vec never has any) and on maps with
    // non-string keys (the model has no maps); non-finite floats become `null`,
    // which the reader rejects.
    serde_json::to_vec_pretty(&document).expect("a surrogate always serializes to JSON")
}

/// Reads and validates a JSON surrogate document (see `docs/formats.md`, "Validation").
pub fn surrogate_from_json(bytes: &[u8]) -> Result<Surrogate, FormatError> {
    let json_error = |e: serde_json::Error| FormatError::SurrogateJson(e.to_string());
    let envelope: Envelope = serde_json::from_slice(bytes).map_err(json_error)?;
    if envelope.format != SURROGATE_FORMAT_TAG {
        return Err(FormatError::WrongFormatTag {
            found: envelope.format,
        });
    }
    if envelope.version != u64::from(SURROGATE_JSON_VERSION) {
        return Err(FormatError::UnsupportedVersion {
            found: envelope.version,
            supported: SURROGATE_JSON_VERSION,
        });
    }
    let document: DocumentIn = serde_json::from_slice(bytes).map_err(json_error)?;
    validate_surrogate(&document.surrogate)?;
    Ok(document.surrogate)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::SurrogateDefect;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;
    use shroud_surrogate::samples::fitted;
    use shroud_surrogate::Sides;

    fn bits(s: &Surrogate) -> Vec<u64> {
        s.surfaces()
            .flat_map(|f| f.surface.coefficients.iter().map(|c| c.to_bits()))
            .collect()
    }

    #[test]
    fn round_trip_is_exact() {
        for sides in [Sides::Upper, Sides::Lower, Sides::Sandwich] {
            let surrogate = fitted(sides, true);
            let back = surrogate_from_json(&surrogate_to_json(&surrogate)).unwrap();
            assert_eq!(back, surrogate);
            assert_eq!(bits(&back), bits(&surrogate));
        }
    }

    #[test]
    fn arbitrary_f64_coefficients_keep_every_bit() {
        let mut rng = Pcg64::seed_from_u64(3);
        let mut surrogate = fitted(Sides::Upper, true);
        for _ in 0..20 {
            for c in &mut surrogate.upper.as_mut().unwrap().surface.coefficients {
                // Random mantissas over a wide exponent range: the cases a
                // shortest-digits writer with an approximate reader gets wrong.
                *c = loop {
                    let x = f64::from_bits(rng.random());
                    if x.is_finite() {
                        break x;
                    }
                };
            }
            let back = surrogate_from_json(&surrogate_to_json(&surrogate)).unwrap();
            assert_eq!(bits(&back), bits(&surrogate));
        }
    }

    #[test]
    fn the_document_is_tagged_and_versioned() {
        let json: serde_json::Value =
            serde_json::from_slice(&surrogate_to_json(&fitted(Sides::Upper, true))).unwrap();
        assert_eq!(json["format"], "shroud-surrogate");
        assert_eq!(json["version"], 1);
        assert_eq!(
            json["surrogate"]["upper"]["surface"]["coefficients"]
                .as_array()
                .unwrap()
                .len(),
            30
        );
        assert_eq!(json["surrogate"]["upper"]["side"], "upper");
        assert_eq!(json["surrogate"]["lower"], serde_json::Value::Null);
    }

    #[test]
    fn wrong_tags_versions_and_syntax_are_named() {
        let text = String::from_utf8(surrogate_to_json(&fitted(Sides::Upper, true))).unwrap();
        let retagged = text.replacen("shroud-surrogate", "mesh", 1);
        assert_eq!(
            surrogate_from_json(retagged.as_bytes()),
            Err(FormatError::WrongFormatTag {
                found: "mesh".into()
            })
        );
        let reversioned = text.replacen("\"version\": 1", "\"version\": 2", 1);
        assert_eq!(
            surrogate_from_json(reversioned.as_bytes()),
            Err(FormatError::UnsupportedVersion {
                found: 2,
                supported: 1
            })
        );
        let cut = &text.as_bytes()[..text.len() / 2];
        assert!(
            matches!(surrogate_from_json(cut), Err(FormatError::SurrogateJson(m)) if m.contains("line"))
        );
        let missing = text.replacen("\"trim\"", "\"trimmed\"", 1);
        assert!(
            matches!(surrogate_from_json(missing.as_bytes()), Err(FormatError::SurrogateJson(m)) if m.contains("trim"))
        );
    }

    #[test]
    fn loaded_documents_are_validated() {
        let mut surrogate = fitted(Sides::Upper, true);
        surrogate.upper.as_mut().unwrap().certificate.violations = 1;
        assert!(matches!(
            surrogate_from_json(&surrogate_to_json(&surrogate)),
            Err(FormatError::InvalidSurrogate(
                SurrogateDefect::Certificate { .. }
            ))
        ));
        let mut surrogate = fitted(Sides::Upper, true);
        surrogate.trim.bits.pop();
        assert!(matches!(
            surrogate_from_json(&surrogate_to_json(&surrogate)),
            Err(FormatError::InvalidSurrogate(
                SurrogateDefect::TrimLength { .. }
            ))
        ));
    }
}
