//! Why a cloud yields no rim to use as the polygon of interest, with the numbers
//! that show it and what to do, and the rule that picks the rim among loops.

use super::loops::BoundaryLoop;
use super::BoundaryParams;
use thiserror::Error;

/// Why boundary detection gave no single rim.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BoundaryFailure {
    /// Neighbourhoods span so much of the part that most points look one-sided.
    #[error(
        "too sparse to tell its rim: {candidates} of its {points} points ({:.0} %) look like rim points, \
         the {k} nearest neighbours of a point reaching {:.0} % of the part's size (median); \
         use a denser scan (about {suggested} points or more) or give the polygon of interest",
        100.0 * *.candidates as f64 / *.points as f64,
        100.0 * .reach
    )]
    TooSparse {
        points: usize,
        candidates: usize,
        k: usize,
        /// Median distance to the k-th neighbour over the bounding box diagonal.
        reach: f64,
        suggested: usize,
    },
    /// No chain of rim points at all: a closed surface.
    #[error(
        "no gap in its surface: {candidates} of its {points} points look like rim points, \
         the longest chain of them has {longest} (a rim needs {min}); if it is a closed surface, \
         cut it open or use a part with an open rim, or give the polygon of interest"
    )]
    NoGap {
        points: usize,
        candidates: usize,
        longest: usize,
        min: usize,
    },
    /// Rim pieces exist but none closes.
    #[error(
        "its rim points ({candidates}, in {pieces} chains of {min} or more, the longest of {longest}) \
         do not close into a loop: the rim has gaps wider than the reach of {k} neighbours; \
         scan the rim more densely or give the polygon of interest"
    )]
    OpenRim {
        candidates: usize,
        pieces: usize,
        longest: usize,
        min: usize,
        k: usize,
    },
    /// Two or more loops of similar length: which one is the rim is not clear.
    #[error(
        "it has {} open boundary loops of similar length ({}); the longest is taken only when \
         the next is shorter than {:.0} % of it: trim the part to one rim or give the polygon of interest",
        .lengths.len(),
        describe(.lengths, .points),
        100.0 * .ratio
    )]
    SeveralLoops {
        /// Lengths of the rival loops, longest first (cloud units).
        lengths: Vec<f64>,
        /// Their point counts.
        points: Vec<usize>,
        ratio: f64,
    },
}

/// "length 1.88 over 301 points, length 1.87 over 296 points".
fn describe(lengths: &[f64], points: &[usize]) -> String {
    lengths
        .iter()
        .zip(points)
        .map(|(l, n)| format!("length {l:.3} over {n} points"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The rim among `loops` (longest first): the longest, unless the next one is
/// at least `params.ambiguous_ratio` of its length (then every such rival is
/// reported). A part with a small hole besides its rim still has one clear rim.
pub fn choose_rim(
    mut loops: Vec<BoundaryLoop>,
    params: &BoundaryParams,
) -> Result<Option<BoundaryLoop>, BoundaryFailure> {
    let Some(longest) = loops.first().map(|l| l.length) else {
        return Ok(None);
    };
    let rivals: Vec<&BoundaryLoop> = loops
        .iter()
        .take_while(|l| l.length >= params.ambiguous_ratio * longest)
        .collect();
    if rivals.len() > 1 {
        return Err(BoundaryFailure::SeveralLoops {
            lengths: rivals.iter().map(|l| l.length).collect(),
            points: rivals.iter().map(|l| l.indices.len()).collect(),
            ratio: params.ambiguous_ratio,
        });
    }
    Ok(Some(loops.swap_remove(0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ring(length: f64, points: usize) -> BoundaryLoop {
        BoundaryLoop {
            indices: (0..points).collect(),
            length,
        }
    }

    #[test]
    fn the_longest_loop_wins_unless_a_rival_is_close() {
        let params = BoundaryParams::default();
        let rim = choose_rim(vec![ring(2.0, 200), ring(0.5, 40)], &params).unwrap();
        assert_eq!(rim.map(|l| l.length), Some(2.0));
        assert_eq!(choose_rim(Vec::new(), &params).unwrap(), None);
        let err =
            choose_rim(vec![ring(2.0, 200), ring(1.9, 190), ring(0.2, 20)], &params).unwrap_err();
        assert_eq!(
            err,
            BoundaryFailure::SeveralLoops {
                lengths: vec![2.0, 1.9],
                points: vec![200, 190],
                ratio: params.ambiguous_ratio,
            }
        );
        let text = err.to_string();
        assert!(text.contains("2 open boundary loops"), "{text}");
        assert!(text.contains("length 1.900 over 190 points"), "{text}");
    }
}
