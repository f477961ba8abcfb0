//! Parameters that explain themselves: each technique's parameter struct derives
//! [`schemars::JsonSchema`], so its doc comments become each key's description and its
//! `#[schemars(range(min = …, max = …))]` attributes each numeric key's valid range.
//!
//! The schema is the one source of the ranges: [`check_ranges`] (which every
//! [`TechniqueParams::validate`] calls first) reads them from it, [`describe`] shows them in
//! `grassbench list`, the window's tooltips and the report, and [`range_disagreements`] lets a
//! test check that `validate` accepts each range's ends and refuses the values just past them.

use serde_json::{Map, Value as Json};

use super::{TechniqueParams, to_table};
use crate::{Error, Result};

/// Units a description may state at the end of its first sentence (`"Petal quad side, m."`,
/// `"…, 1/s (Eq. 7's a)."`); only these are recognised, so no unit is guessed.
const UNITS: &[&str] = &[
    "m", "m²", "s", "1/s", "1/s²", "m/s", "m/s²", "radians", "texels", "frames",
];

/// Abbreviations whose full stop does not end a sentence.
const ABBREVIATIONS: &[&str] = &["Sec", "Eq", "Eqs", "Fig", "e.g", "i.e", "cf", "vs", "Ch"];

/// One parameter of a technique, as its struct's schema describes it.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamDoc {
    /// The key (`alpha_cutoff`), as in scene files and `--param`.
    pub key: String,
    /// The field's doc comment on one line, rustdoc links reduced to their code.
    pub description: String,
    /// The unit the description's first sentence ends with (`m`, `1/s`, `radians`, …), if it
    /// names one of the few recognised; `None` leaves it in the description.
    pub unit: Option<String>,
    /// The default value.
    pub default: toml::Value,
    /// Smallest and largest valid value (of each element, for an array), when the schema
    /// gives both.
    pub range: Option<(f64, f64)>,
    /// Whether the value (or each element) is an integer.
    pub integer: bool,
    /// The values an enumerated parameter may take, in declaration order; empty otherwise.
    pub choices: Vec<String>,
}

impl ParamDoc {
    /// The description's first sentence.
    pub fn summary(&self) -> &str {
        first_sentence(&self.description)
    }

    /// What values are valid, as text: `[0.01, 0.99]`, `"sort" | "alpha_to_coverage"`, or
    /// empty when the schema says nothing beyond the type.
    pub fn bounds(&self) -> String {
        if let Some((lo, hi)) = self.range {
            let each = if self.default.is_array() { "each " } else { "" };
            format!(
                "{each}[{}, {}]",
                self.format_bound(lo),
                self.format_bound(hi)
            )
        } else if !self.choices.is_empty() {
            self.choices
                .iter()
                .map(|c| format!("\"{c}\""))
                .collect::<Vec<_>>()
                .join(" | ")
        } else {
            String::new()
        }
    }

    /// [`Self::bounds`] followed by the unit, when there is one (`[0.001, 10] m`).
    pub fn bounds_with_unit(&self) -> String {
        match (&self.unit, self.bounds()) {
            (Some(unit), b) if !b.is_empty() => format!("{b} {unit}"),
            (Some(unit), _) => unit.clone(),
            (None, b) => b,
        }
    }

    /// The description and the valid values on one line each, for a tooltip.
    pub fn tooltip(&self) -> String {
        let bounds = self.bounds_with_unit();
        if bounds.is_empty() {
            self.description.clone()
        } else {
            format!("{}\nvalid: {bounds}", self.description)
        }
    }

    fn format_bound(&self, x: f64) -> String {
        if self.integer {
            format!("{}", x as i64)
        } else {
            format!("{}", x as f32)
        }
    }
}

/// The JSON schema of `P`, as a JSON value.
pub fn schema_of<P: schemars::JsonSchema>() -> Json {
    schemars::schema_for!(P).to_value()
}

/// Every parameter of `P`, in the struct's field order: key, description, unit, default,
/// range and choices, read from its schema.
pub fn describe<P: TechniqueParams>() -> Vec<ParamDoc> {
    let root = schema_of::<P>();
    let defaults = to_table(&P::default());
    fields(&root)
        .into_iter()
        .map(|field| {
            let description = clean(field.schema.get("description"));
            let unit = unit_of(first_sentence(&description));
            ParamDoc {
                default: defaults
                    .get(&field.key)
                    .cloned()
                    .unwrap_or_else(|| toml::Value::String(String::new())),
                key: field.key,
                description,
                unit,
                range: field.range,
                integer: field.integer,
                choices: field.choices,
            }
        })
        .collect()
}

/// Checks every numeric value of `params` against its schema: finite, and within the range
/// the schema gives (each element, for an array). The error names `technique.key` (or
/// `technique.key[i]`) and the range. [`TechniqueParams::validate`] calls this first, then
/// checks what a range cannot say (powers of two, orderings, "0 or at least 1").
pub fn check_ranges<P: TechniqueParams>(technique: &str, params: &P) -> Result<()> {
    let root = schema_of::<P>();
    let table = toml::Table::try_from(params).map_err(|e| Error::Technique {
        technique: technique.to_owned(),
        message: format!("its parameters do not serialise: {e}"),
    })?;
    for field in fields(&root) {
        let Some(value) = table.get(&field.key) else {
            continue;
        };
        let name = format!("{technique}.{}", field.key);
        match value {
            toml::Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    check_value(&format!("{name}[{i}]"), item, field.range)?;
                }
            }
            other => check_value(&name, other, field.range)?,
        }
    }
    Ok(())
}

fn check_value(name: &str, value: &toml::Value, range: Option<(f64, f64)>) -> Result<()> {
    match *value {
        toml::Value::Float(f) => {
            // Every float parameter is an `f32`: compare as `f32`, so a bound like 0.01 accepts
            // the `f32` written as 0.01.
            let v = f as f32;
            match range {
                Some((lo, hi)) => super::check(name, v, lo as f32..=hi as f32),
                None if v.is_finite() => Ok(()),
                None => Err(Error::param(name, v, "a finite number")),
            }
        }
        toml::Value::Integer(i) => match range {
            Some((lo, hi)) => super::check_int(name, i, lo as i64..=hi as i64),
            None => Ok(()),
        },
        _ => Ok(()),
    }
}

/// Keys of `docs` whose description is empty: a parameter without a doc comment.
pub fn undocumented(docs: &[ParamDoc]) -> Vec<String> {
    docs.iter()
        .filter(|d| d.description.trim().is_empty())
        .map(|d| d.key.clone())
        .collect()
}

/// Where a technique's schema and its parameter check disagree, one line each; empty when
/// they agree. For every numeric key with a range in `docs`: both ends must be accepted (an
/// error naming `technique.key` counts as refused; keys in `bounds_depend_on_others`, as
/// `technique.key`, are spared this half, for ranges that other keys narrow, like an
/// ordering), and the values just past them (the next `f32`, the next integer) refused with an
/// error naming the key. For every numeric key without a range: ±1e30 (or 0 and 2³¹−1 for
/// integers) must not be refused on that key's account, or `check` tests a range the schema
/// does not know. `check` is the technique's whole check (defaults overlaid with the
/// overrides, as [`crate::technique::TechniqueEntry::check`]).
pub fn range_disagreements(
    technique: &str,
    docs: &[ParamDoc],
    check: &dyn Fn(&toml::Table) -> Result<toml::Table>,
    bounds_depend_on_others: &[&str],
) -> Vec<String> {
    let mut problems = Vec::new();
    for doc in docs {
        let qualified = format!("{technique}.{}", doc.key);
        let elements = match &doc.default {
            toml::Value::Array(items) => Some(items.len()),
            toml::Value::Float(_) | toml::Value::Integer(_) => None,
            _ => continue,
        };
        let value_at = |x: f64| {
            let one = if doc.integer {
                toml::Value::Integer(x as i64)
            } else {
                toml::Value::Float(f64::from(x as f32))
            };
            match elements {
                Some(n) => toml::Value::Array(vec![one; n]),
                None => one,
            }
        };
        let outcome = |x: f64| {
            let mut overrides = toml::Table::new();
            overrides.insert(doc.key.clone(), value_at(x));
            check(&overrides).err().map(|e| e.to_string())
        };
        let Some((lo, hi)) = doc.range else {
            let probes = if doc.integer {
                [0.0, f64::from(i32::MAX)]
            } else {
                [-1e30, 1e30]
            };
            for x in probes {
                if let Some(e) = outcome(x).filter(|e| e.contains(&qualified)) {
                    problems.push(format!(
                        "{qualified}: no range in the schema, but {x} is refused: {e}"
                    ));
                }
            }
            continue;
        };
        if !bounds_depend_on_others.contains(&qualified.as_str()) {
            for x in [lo, hi] {
                if let Some(e) = outcome(x).filter(|e| e.contains(&qualified)) {
                    problems.push(format!(
                        "{qualified}: {x} is in the schema's range [{lo}, {hi}] but refused: {e}"
                    ));
                }
            }
        }
        let past = if doc.integer {
            [lo - 1.0, hi + 1.0]
        } else {
            [
                f64::from((lo as f32).next_down()),
                f64::from((hi as f32).next_up()),
            ]
        };
        for x in past {
            // A value the type cannot hold (-1 for a `u32`) is refused by deserialising, with
            // an error that quotes the overrides, so the bare key.
            match outcome(x) {
                Some(e) if e.contains(&doc.key) => {}
                Some(e) => problems.push(format!(
                    "{qualified}: {x} is past the schema's range [{lo}, {hi}] and refused, but not on this key's account: {e}"
                )),
                None => problems.push(format!(
                    "{qualified}: {x} is past the schema's range [{lo}, {hi}] but accepted"
                )),
            }
        }
    }
    problems
}

/// Everything wrong with `P`'s schema, one line each: keys without a description
/// ([`undocumented`]) and ranges its `validate` does not keep ([`range_disagreements`],
/// through [`super::resolve`]). Each technique's tests assert this is empty.
pub fn schema_problems<P: TechniqueParams>(
    technique: &str,
    bounds_depend_on_others: &[&str],
) -> Vec<String> {
    let docs = describe::<P>();
    let check =
        |overrides: &toml::Table| super::resolve::<P>(technique, overrides).map(|p| to_table(&p));
    undocumented(&docs)
        .into_iter()
        .map(|key| format!("{technique}.{key}: no description (doc comment)"))
        .chain(range_disagreements(
            technique,
            &docs,
            &check,
            bounds_depend_on_others,
        ))
        .collect()
}

/// One property of a parameter struct's schema.
struct Field<'a> {
    key: String,
    schema: &'a Map<String, Json>,
    range: Option<(f64, f64)>,
    integer: bool,
    choices: Vec<String>,
}

/// The properties of `root` in field order (the schema's `required` list, which follows the
/// struct; any others after, by name).
fn fields(root: &Json) -> Vec<Field<'_>> {
    let Some(properties) = root.get("properties").and_then(Json::as_object) else {
        return Vec::new();
    };
    let mut keys: Vec<&str> = root
        .get("required")
        .and_then(Json::as_array)
        .map(|r| r.iter().filter_map(Json::as_str).collect())
        .unwrap_or_default();
    for key in properties.keys() {
        if !keys.contains(&key.as_str()) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .filter_map(|key| {
            let schema = properties.get(key)?.as_object()?;
            let target = resolve_ref(root, schema);
            let numeric = match target.get("type").and_then(Json::as_str) {
                Some("array") => target.get("items").and_then(Json::as_object),
                _ => Some(target),
            }
            .filter(|n| {
                matches!(
                    n.get("type").and_then(Json::as_str),
                    Some("integer" | "number")
                )
            });
            let range = numeric
                .and_then(|n| Some((n.get("minimum")?.as_f64()?, n.get("maximum")?.as_f64()?)));
            let integer =
                numeric.is_some_and(|n| n.get("type").and_then(Json::as_str) == Some("integer"));
            Some(Field {
                key: key.to_owned(),
                schema,
                range,
                integer,
                choices: choices(target),
            })
        })
        .collect()
}

/// `schema`, or the definition its `$ref` points at.
fn resolve_ref<'a>(root: &'a Json, schema: &'a Map<String, Json>) -> &'a Map<String, Json> {
    schema
        .get("$ref")
        .and_then(Json::as_str)
        .and_then(|r| r.strip_prefix("#/$defs/"))
        .and_then(|name| root.get("$defs")?.get(name)?.as_object())
        .unwrap_or(schema)
}

/// The string values an enumeration schema allows (`enum`, or `oneOf` / `anyOf` of
/// `const`s, as schemars writes unit variants with and without doc comments).
fn choices(schema: &Map<String, Json>) -> Vec<String> {
    let strings = |values: &Vec<Json>| -> Vec<String> {
        values
            .iter()
            .filter_map(Json::as_str)
            .map(str::to_owned)
            .collect()
    };
    if let Some(values) = schema.get("enum").and_then(Json::as_array) {
        return strings(values);
    }
    ["oneOf", "anyOf"]
        .iter()
        .filter_map(|k| schema.get(*k).and_then(Json::as_array))
        .flatten()
        .flat_map(|variant| {
            if let Some(c) = variant.get("const").and_then(Json::as_str) {
                vec![c.to_owned()]
            } else {
                variant
                    .get("enum")
                    .and_then(Json::as_array)
                    .map(strings)
                    .unwrap_or_default()
            }
        })
        .collect()
}

/// A doc comment on one line, with rustdoc's link brackets around code removed.
fn clean(description: Option<&Json>) -> String {
    let text = description.and_then(Json::as_str).unwrap_or_default();
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace("[`", "`")
        .replace("`]", "`")
}

/// The first sentence of `text`: up to the first full stop outside parentheses and code that
/// is followed by a space (or ends the text) and does not end an abbreviation (`Sec.`).
pub fn first_sentence(text: &str) -> &str {
    let mut depth = 0i32;
    let mut code = false;
    for (i, c) in text.char_indices() {
        match c {
            '`' => code = !code,
            '(' if !code => depth += 1,
            ')' if !code => depth -= 1,
            '.' if !code && depth <= 0 => {
                let rest = &text[i + 1..];
                let ends = rest.is_empty() || rest.starts_with(char::is_whitespace);
                let word = text[..i]
                    .rsplit(|ch: char| ch.is_whitespace() || ch == '(')
                    .next()
                    .unwrap_or_default();
                if ends && !ABBREVIATIONS.contains(&word) {
                    return &text[..=i];
                }
            }
            _ => {}
        }
    }
    text
}

/// The unit `sentence` states after its last comma (`", m."`, `", 1/s (…"`), if a recognised
/// one.
fn unit_of(sentence: &str) -> Option<String> {
    UNITS
        .iter()
        .find(|unit| {
            [".", " (", ";", ":"]
                .iter()
                .any(|end| sentence.contains(&format!(", {unit}{end}")))
        })
        .map(|unit| (*unit).to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::resolve;
    use serde::{Deserialize, Serialize};

    /// How it bends.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(rename_all = "snake_case")]
    enum Mode {
        /// Softly.
        Soft,
        /// Hard.
        HardEdge,
    }

    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct P {
        /// Segments per blade (Sec. 3.2). More is smoother.
        #[schemars(range(min = 1, max = 16))]
        segments: u32,
        /// Side of a patch, m (the paper's 2.5 m). Second sentence.
        #[schemars(range(min = 0.01, max = 0.99))]
        side: f32,
        /// Where, m.
        #[schemars(inner(range(min = -10.0, max = 10.0)))]
        at: [f32; 2],
        /// How it bends: `soft` or `hard_edge`.
        mode: Mode,
        /// Unchecked gain.
        gain: f32,
        /// 0 or at least 4, radians per (m/s).
        #[schemars(range(min = 0, max = 64))]
        gaps: u32,
    }

    impl Default for P {
        fn default() -> Self {
            Self {
                segments: 5,
                side: 0.5,
                at: [0.0, 1.0],
                mode: Mode::Soft,
                gain: 1.0,
                gaps: 0,
            }
        }
    }

    impl TechniqueParams for P {
        fn validate(&self) -> Result<()> {
            check_ranges("t", self)?;
            if self.gaps != 0 && self.gaps < 4 {
                return Err(Error::param("t.gaps", self.gaps, "0 or at least 4"));
            }
            Ok(())
        }
    }

    fn check_p(overrides: &toml::Table) -> Result<toml::Table> {
        resolve::<P>("t", overrides).map(|p| to_table(&p))
    }

    #[test]
    fn describe_reads_descriptions_units_ranges_and_choices_in_field_order() {
        let docs = describe::<P>();
        let keys: Vec<_> = docs.iter().map(|d| d.key.as_str()).collect();
        assert_eq!(keys, ["segments", "side", "at", "mode", "gain", "gaps"]);
        let [segments, side, at, mode, gain, gaps] = &docs[..] else {
            panic!("{docs:?}");
        };
        assert_eq!(segments.summary(), "Segments per blade (Sec. 3.2).");
        assert_eq!(
            (segments.range, segments.integer, segments.unit.as_deref()),
            (Some((1.0, 16.0)), true, None)
        );
        assert_eq!(segments.default, toml::Value::Integer(5));
        assert_eq!(segments.bounds(), "[1, 16]");
        assert_eq!(side.summary(), "Side of a patch, m (the paper's 2.5 m).");
        assert_eq!(side.unit.as_deref(), Some("m"));
        assert_eq!(side.bounds_with_unit(), "[0.01, 0.99] m");
        // What the window shows on hover.
        assert_eq!(
            side.tooltip(),
            "Side of a patch, m (the paper's 2.5 m). Second sentence.\nvalid: [0.01, 0.99] m"
        );
        assert_eq!(gain.tooltip(), "Unchecked gain.");
        assert_eq!(at.range, Some((-10.0, 10.0)));
        assert_eq!(at.bounds_with_unit(), "each [-10, 10] m");
        assert_eq!(mode.choices, ["soft", "hard_edge"]);
        assert_eq!(mode.bounds(), "\"soft\" | \"hard_edge\"");
        assert_eq!(mode.description, "How it bends: `soft` or `hard_edge`.");
        assert_eq!((gain.range, gain.bounds()), (None, String::new()));
        // "radians per (m/s)" is not a unit the sentence ends with.
        assert_eq!(gaps.unit, None);
        assert!(undocumented(&docs).is_empty());
    }

    #[test]
    fn check_ranges_reads_the_schema_and_names_the_key() {
        P::default().validate().unwrap();
        let bad = |f: fn(&mut P), needle: &str| {
            let mut p = P::default();
            f(&mut p);
            let e = p.validate().unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        };
        bad(|p| p.segments = 17, "t.segments");
        bad(|p| p.segments = 0, "an integer in [1, 16]");
        bad(|p| p.side = 0.995, "a number in [0.01, 0.99]");
        bad(|p| p.side = f32::NAN, "t.side");
        bad(|p| p.at = [0.0, 11.0], "t.at[1]");
        bad(|p| p.gain = f32::INFINITY, "t.gain");
        // The ends themselves, as the f32 written.
        P {
            side: 0.01,
            segments: 16,
            ..P::default()
        }
        .validate()
        .unwrap();
    }

    #[test]
    fn range_disagreements_finds_checks_stricter_or_looser_than_the_schema() {
        let docs = describe::<P>();
        assert_eq!(
            range_disagreements("t", &docs, &check_p, &[]),
            Vec::<String>::new()
        );
        // A check that refuses an end of the range, one that accepts a value past it, and one
        // that checks a key the schema gives no range.
        let strict = |o: &toml::Table| -> Result<toml::Table> {
            let t = check_p(o)?;
            if t.get("segments").and_then(toml::Value::as_integer) == Some(16) {
                return Err(Error::param("t.segments", 16, "fewer"));
            }
            if t.get("gain").and_then(toml::Value::as_float) > Some(1e6) {
                return Err(Error::param("t.gain", 0, "at most 1e6"));
            }
            Ok(t)
        };
        let found = range_disagreements("t", &docs, &strict, &[]);
        assert_eq!(found.len(), 2, "{found:#?}");
        assert!(found[0].contains("t.segments: 16"), "{found:#?}");
        assert!(found[1].contains("t.gain: no range"), "{found:#?}");
        assert!(range_disagreements("t", &docs, &strict, &["t.segments"]).len() == 1);
        let loose = |o: &toml::Table| -> Result<toml::Table> {
            let mut p: P =
                toml::Value::Table(crate::technique::overlay(&to_table(&P::default()), o))
                    .try_into()
                    .map_err(|e: toml::de::Error| Error::param("t", "?", e.to_string()))?;
            p.side = p.side.clamp(0.01, 0.99);
            p.validate().map(|()| to_table(&p))
        };
        let found = range_disagreements("t", &docs, &loose, &[]);
        assert_eq!(found.len(), 2, "{found:#?}");
        assert!(
            found
                .iter()
                .all(|f| f.contains("t.side") && f.contains("accepted"))
        );
    }

    #[test]
    fn first_sentences_skip_abbreviations_parentheses_and_code() {
        assert_eq!(
            first_sentence("A, m (Sec. 5.1: 1. 2). B."),
            "A, m (Sec. 5.1: 1. 2)."
        );
        assert_eq!(first_sentence("See Fig. 13 here. B."), "See Fig. 13 here.");
        assert_eq!(first_sentence("Uses `a. b` then. B"), "Uses `a. b` then.");
        assert_eq!(first_sentence("No stop"), "No stop");
        assert_eq!(
            unit_of("Pull back, 1/s² (an addition)."),
            Some("1/s²".into())
        );
        assert_eq!(unit_of("Period, s."), Some("s".into()));
        assert_eq!(unit_of("Gravity, m/s² of tip rate."), None);
    }
}
