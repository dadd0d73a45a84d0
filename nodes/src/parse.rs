//! Parsers for the small value syntaxes of the command line (`20x20`, `0,0,-1`).

use anyhow::{bail, Context, Result};

/// `"20x30"` -> `(20, 30)`; a single number means a square grid.
pub fn grid(text: &str) -> Result<(usize, usize)> {
    let parts: Vec<&str> = text.split(['x', 'X']).collect();
    let number = |s: &str| -> Result<usize> {
        s.trim()
            .parse::<usize>()
            .with_context(|| format!("grid '{text}': '{s}' is not a whole number"))
    };
    match parts.as_slice() {
        [n] => Ok((number(n)?, number(n)?)),
        [c, r] => Ok((number(c)?, number(r)?)),
        _ => bail!("grid '{text}' must look like 20x20"),
    }
}

/// `"x,y,z,..."` -> exactly `N` finite numbers.
pub fn numbers<const N: usize>(text: &str, what: &str) -> Result<[f64; N]> {
    let values: Vec<f64> = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .with_context(|| format!("{what} '{text}': '{s}' is not a number"))
        })
        .collect::<Result<_>>()?;
    let array: [f64; N] = values.try_into().map_err(|v: Vec<f64>| {
        anyhow::anyhow!(
            "{what} '{text}' needs {N} comma-separated numbers, got {}",
            v.len()
        )
    })?;
    if let Some(bad) = array.iter().find(|x| !x.is_finite()) {
        bail!("{what} '{text}' contains the non-finite value {bad}");
    }
    Ok(array)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_grids_and_vectors() {
        assert_eq!(grid("20x30").unwrap(), (20, 30));
        assert_eq!(grid("7").unwrap(), (7, 7));
        assert!(grid("20x").is_err() && grid("axb").is_err() && grid("1x2x3").is_err());
        assert_eq!(numbers::<3>("0, 0,-1", "dir").unwrap(), [0.0, 0.0, -1.0]);
        assert!(numbers::<3>("0,0", "dir").is_err());
        assert!(numbers::<3>("0,0,nan", "dir").is_err());
        assert!(numbers::<3>("0,0,inf", "dir").is_err());
    }
}
