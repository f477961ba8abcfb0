//! Technique parameters: one serde struct per technique with defaults, overridable key by key
//! from scene files (`[techniques.<id>]`), sweep files and the command line (`--param k=v`).
//!
//! Parameters travel as `toml::Table`s between the registry, the CLI and the techniques, so a
//! result file can record every value a run used (long format: run, key, value).
//!
//! Each struct also derives [`schemars::JsonSchema`]: its doc comments and range attributes
//! are the parameters' descriptions and valid ranges ([`describe`], [`check_ranges`]).

mod schema;

pub use schema::{
    ParamDoc, check_ranges, describe, first_sentence, range_disagreements, schema_of,
    schema_problems, undocumented,
};

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::{Error, Result};

/// A technique's parameter struct. Its [`schemars::JsonSchema`] derive carries a doc comment
/// for every field (the key's description) and `#[schemars(range(min = …, max = …))]` on every
/// numeric field (its valid range, `inner(range(…))` for arrays).
pub trait TechniqueParams:
    Serialize + DeserializeOwned + Default + Clone + schemars::JsonSchema
{
    /// Rejects NaN, out-of-range and absurd values with a message naming the key: calls
    /// [`check_ranges`] (the schema's ranges) first, then checks what a range cannot say.
    fn validate(&self) -> Result<()>;
}

/// The defaults of `P` overlaid with `overrides`; unknown keys and wrong types are errors that
/// list the valid keys.
pub fn resolve<P: TechniqueParams>(technique: &str, overrides: &toml::Table) -> Result<P> {
    let mut table = to_table(&P::default());
    for (key, value) in overrides {
        if !table.contains_key(key) {
            return Err(Error::UnknownName {
                kind: "parameter",
                name: format!("{technique}.{key}"),
                valid: table
                    .keys()
                    .map(|k| format!("{technique}.{k}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
        table.insert(key.clone(), value.clone());
    }
    let params: P = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| {
            Error::param(
                technique,
                format!("{overrides}").trim(),
                format!("values of the right type ({})", e.message()),
            )
        })?;
    params.validate()?;
    Ok(params)
}

/// A parameter struct as a TOML table (what result files record).
pub fn to_table<P: Serialize>(params: &P) -> toml::Table {
    toml::Table::try_from(params).unwrap_or_default()
}

/// A parameter value as text; floats print as the `f32` they came from (`0.15`, not
/// `0.15000000596046448`), since every technique parameter is `f32`.
pub fn format_value(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(f) => format!("{}", *f as f32),
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Parses `key=value` (value in TOML syntax; bare words are strings) into a table entry.
pub fn parse_assignment(text: &str) -> Result<(String, toml::Value)> {
    let (key, value) = text
        .split_once('=')
        .ok_or_else(|| Error::param("--param", text, "KEY=VALUE, e.g. segments=7"))?;
    let key = key.trim().to_owned();
    let value = value.trim();
    let parsed = format!("v = {value}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value.to_owned()));
    Ok((key, parsed))
}

/// Checks that `value` is finite and within `range`; the error names `name`.
pub fn check(name: &str, value: f32, range: std::ops::RangeInclusive<f32>) -> Result<()> {
    if value.is_finite() && range.contains(&value) {
        Ok(())
    } else {
        Err(Error::param(
            name,
            value,
            format!("a number in [{}, {}]", range.start(), range.end()),
        ))
    }
}

/// Checks that an integer lies within `range`; the error names `name`.
pub fn check_int<T: PartialOrd + std::fmt::Display + Copy>(
    name: &str,
    value: T,
    range: std::ops::RangeInclusive<T>,
) -> Result<()> {
    if range.contains(&value) {
        Ok(())
    } else {
        Err(Error::param(
            name,
            value,
            format!("an integer in [{}, {}]", range.start(), range.end()),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Clone, Debug, Serialize, serde::Deserialize, PartialEq, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct P {
        /// Segments.
        segments: u32,
        /// Bend.
        bend: f32,
    }

    impl Default for P {
        fn default() -> Self {
            Self {
                segments: 5,
                bend: 0.5,
            }
        }
    }

    impl TechniqueParams for P {
        fn validate(&self) -> Result<()> {
            check_int("t.segments", self.segments, 1..=16)?;
            check("t.bend", self.bend, 0.0..=2.0)
        }
    }

    #[test]
    fn overrides_defaults_and_rejects_bad_keys_types_and_ranges() {
        let mut t = toml::Table::new();
        assert_eq!(resolve::<P>("t", &t).unwrap(), P::default());
        let (k, v) = parse_assignment("segments=7").unwrap();
        t.insert(k, v);
        assert_eq!(resolve::<P>("t", &t).unwrap().segments, 7);
        let mut bad = toml::Table::new();
        bad.insert("segmentz".into(), 3.into());
        let e = resolve::<P>("t", &bad).unwrap_err().to_string();
        assert!(e.contains("t.segmentz") && e.contains("t.segments"), "{e}");
        let mut bad = toml::Table::new();
        bad.insert("segments".into(), "many".into());
        assert!(resolve::<P>("t", &bad).is_err());
        let mut bad = toml::Table::new();
        bad.insert("bend".into(), f64::NAN.into());
        assert!(
            resolve::<P>("t", &bad)
                .unwrap_err()
                .to_string()
                .contains("t.bend")
        );
    }
}
