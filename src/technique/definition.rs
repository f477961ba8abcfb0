//! What a technique *is* — its parameter type, identity, variants, how it is made and what it
//! will allocate — written once per technique crate as a [`Technique`] impl, and turned into
//! the registry's object-safe [`TechniqueEntry`] by one generic function, [`entry`].
//!
//! A technique crate therefore writes no registration code of its own: no closures, no
//! parameter resolution, no `fn info` / `fn params` by hand. Parameters are resolved (defaults,
//! overrides, unknown keys, types, ranges) in exactly one place, [`TechniqueEntry::check`],
//! which `run`, `sweep`, `validate`, the window and the tests all use.

use super::{GrassTechnique, InitContext, TechniqueInfo};
use crate::gpu::GpuEstimate;
use crate::params::{ParamDoc, TechniqueParams, describe, resolve, to_table};
use crate::{Error, Result, Scene};

/// A real-time grass technique, typed: implement this (and [`GrassTechnique`] for the
/// per-frame work), then register `technique::entry::<YourTechnique>()`.
pub trait Technique: Sized + 'static {
    /// Its parameter struct (`[techniques.<id>]` in scene files, `--param` on the command line).
    type Params: TechniqueParams;

    /// Id, name and paper.
    const INFO: TechniqueInfo;

    /// Named parameter sets the comparison suite and the command line can ask for. `finest` is
    /// a field, so a technique that forgets it does not compile.
    const VARIANTS: Variants;

    /// Creates the technique with resolved, validated parameters.
    fn new(ctx: &InitContext<'_>, params: Self::Params) -> Result<Self>;

    /// What [`Technique::new`] with these parameters will allocate on the GPU, computed from
    /// the same numbers without any GPU work; the harness checks it against the adapter
    /// ([`crate::gpu::memory`]) before creating anything.
    fn estimate(scene: &Scene, params: &Self::Params) -> Result<GpuEstimate>;

    /// The device limits [`Technique::new`] with these parameters needs, computed without any
    /// GPU work: [`wgpu::Limits::default`] (what WebGPU guarantees on any GPU) unless the
    /// technique needs more. The registry's line adds the largest buffer of
    /// [`Technique::estimate`] to `max_buffer_size` by itself. Devices request the most any
    /// of a run's techniques needs, and a technique needing more than the adapter offers is
    /// refused before it is created ([`crate::gpu::limits`]).
    fn required_limits(_scene: &Scene, _params: &Self::Params) -> wgpu::Limits {
        wgpu::Limits::default()
    }

    /// The parameters in use.
    fn params(&self) -> &Self::Params;
}

/// Identity and parameters of a live technique, for the harness and result files. Implemented
/// for every [`Technique`]; a supertrait of [`GrassTechnique`], so `dyn GrassTechnique` has it.
pub trait Describe {
    /// Id, name and paper.
    fn info(&self) -> TechniqueInfo;

    /// The parameters in use, as recorded in result files.
    fn param_table(&self) -> toml::Table;
}

impl<T: Technique> Describe for T {
    fn info(&self) -> TechniqueInfo {
        T::INFO
    }

    fn param_table(&self) -> toml::Table {
        to_table(Technique::params(self))
    }
}

/// A named set of parameter overrides a technique offers to the comparison suite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    /// The variant's name, e.g. [`NO_TRANSITIONS`].
    pub name: &'static str,
    /// Parameter overrides, in TOML (`"shells = 128"`).
    pub params: &'static str,
}

/// A technique's variants. `finest` is a required field, so a technique without one does not
/// compile:
///
/// ```compile_fail
/// const V: grassbench::technique::Variants = grassbench::technique::Variants { others: &[] };
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variants {
    /// Overrides that force the technique's finest representation everywhere (for LOD
    /// fidelity); `""` when the defaults already are the finest.
    pub finest: &'static str,
    /// Further variants (e.g. [`NO_TRANSITIONS`]).
    pub others: &'static [Variant],
}

impl Variants {
    /// Every variant, [`FINEST`] first.
    pub fn iter(&self) -> impl Iterator<Item = Variant> + '_ {
        std::iter::once(Variant {
            name: FINEST,
            params: self.finest,
        })
        .chain(self.others.iter().copied())
    }

    /// The overrides of variant `name`, if there is one.
    pub fn get(&self, name: &str) -> Option<&'static str> {
        self.iter().find(|v| v.name == name).map(|v| v.params)
    }
}

/// Name of the variant that forces a technique's finest representation everywhere.
pub const FINEST: &str = "finest";
/// Name of the variant that switches levels of detail without transitions.
pub const NO_TRANSITIONS: &str = "no_transitions";
/// Name of the variant that sets a technique to its paper's own operating point, as far as the
/// paper states it (each value cited in the technique's `src/paper.rs`).
pub const PAPER: &str = "paper";
/// The parameter key that names a variant in any override table (`--param variant=paper`, a
/// scene's `[techniques.<id>]`, a sweep's `[params.<id>] variant = ["default", "paper"]`): the
/// variant's overrides apply first, the table's other keys on top of them.
pub const VARIANT_KEY: &str = "variant";
/// The value of [`VARIANT_KEY`] that names no variant: the parameter struct's defaults.
pub const DEFAULT_VARIANT: &str = "default";

/// `top`'s keys laid over `base`'s: what a variant with further overrides resolves to.
pub fn overlay(base: &toml::Table, top: &toml::Table) -> toml::Table {
    let mut table = base.clone();
    table.extend(top.iter().map(|(k, v)| (k.clone(), v.clone())));
    table
}

/// Where the variant overrides `variant` (TOML) fail to set exactly the values of `cited`, one
/// line per difference (none: they do): the variant must resolve to `cited`, each key it names
/// must hold `cited`'s value, and it must name `count` keys, one per cited constant, so it
/// sets nothing the paper does not state. For the `paper` variants' tests.
pub fn variant_differences<P: TechniqueParams + PartialEq + std::fmt::Debug>(
    technique: &str,
    variant: &str,
    cited: &P,
    count: usize,
) -> Vec<String> {
    let table = match variant.parse::<toml::Table>() {
        Ok(t) => t,
        Err(e) => return vec![format!("not valid TOML: {e}")],
    };
    let mut out = Vec::new();
    match resolve::<P>(technique, &table) {
        Ok(p) if &p == cited => {}
        Ok(p) => out.push(format!("resolves to {p:?}, cited {cited:?}")),
        Err(e) => out.push(e.to_string()),
    }
    let full = to_table(cited);
    for (key, value) in &table {
        if full.get(key) != Some(value) {
            out.push(format!("`{key} = {value}` is not the cited value"));
        }
    }
    if table.len() != count {
        out.push(format!("{} keys for {count} cited constants", table.len()));
    }
    out
}

/// The variant `overrides` names through [`VARIANT_KEY`], if any other than
/// [`DEFAULT_VARIANT`].
pub fn variant_of(overrides: &toml::Table) -> Option<&str> {
    overrides
        .get(VARIANT_KEY)
        .and_then(toml::Value::as_str)
        .filter(|&name| name != DEFAULT_VARIANT)
}

/// A result row's `key=value;...` parameter string with the variant `overrides` named put
/// first (`variant=paper;...`), so a reader sees which operating point a row was measured at.
pub fn label_params(overrides: &toml::Table, params: &str) -> String {
    match variant_of(overrides) {
        Some(name) if params.is_empty() => format!("{VARIANT_KEY}={name}"),
        Some(name) => format!("{VARIANT_KEY}={name};{params}"),
        None => params.to_owned(),
    }
}

/// One line of the registry: a [`Technique`] behind function pointers, so techniques of
/// different types sit in one table. Made by [`entry`], never by hand.
#[derive(Clone, Copy)]
pub struct TechniqueEntry {
    /// Id, name and paper.
    pub info: TechniqueInfo,
    /// Parameter variants for the comparison suite (see [`FINEST`], [`NO_TRANSITIONS`]).
    pub variants: Variants,
    defaults: fn() -> toml::Table,
    describe: fn() -> Vec<ParamDoc>,
    check: fn(&toml::Table) -> Result<toml::Table>,
    create: fn(&InitContext<'_>, &toml::Table) -> Result<Box<dyn GrassTechnique>>,
    estimate: fn(&Scene, &toml::Table) -> Result<GpuEstimate>,
    limits: fn(&Scene, &toml::Table) -> Result<wgpu::Limits>,
}

/// The registry line of technique `T`.
pub const fn entry<T: Technique + GrassTechnique>() -> TechniqueEntry {
    TechniqueEntry {
        info: T::INFO,
        variants: T::VARIANTS,
        defaults: defaults_of::<T>,
        describe: describe::<T::Params>,
        check: check_of::<T>,
        create: create_of::<T>,
        estimate: estimate_of::<T>,
        limits: limits_of::<T>,
    }
}

fn defaults_of<T: Technique>() -> toml::Table {
    to_table(&T::Params::default())
}

fn check_of<T: Technique>(overrides: &toml::Table) -> Result<toml::Table> {
    resolve::<T::Params>(T::INFO.id, overrides).map(|p| to_table(&p))
}

fn create_of<T: Technique + GrassTechnique>(
    ctx: &InitContext<'_>,
    overrides: &toml::Table,
) -> Result<Box<dyn GrassTechnique>> {
    let params = resolve::<T::Params>(T::INFO.id, overrides)?;
    Ok(Box::new(T::new(ctx, params)?))
}

fn estimate_of<T: Technique>(scene: &Scene, overrides: &toml::Table) -> Result<GpuEstimate> {
    T::estimate(scene, &resolve::<T::Params>(T::INFO.id, overrides)?)
}

fn limits_of<T: Technique>(scene: &Scene, overrides: &toml::Table) -> Result<wgpu::Limits> {
    let params = resolve::<T::Params>(T::INFO.id, overrides)?;
    let mut limits = T::required_limits(scene, &params);
    let largest = T::estimate(scene, &params)?.largest_buffer;
    limits.max_buffer_size = limits.max_buffer_size.max(largest);
    Ok(limits)
}

impl TechniqueEntry {
    /// The defaults of its parameter struct.
    pub fn default_params(&self) -> toml::Table {
        (self.defaults)()
    }

    /// Every parameter: key, description, unit, default, valid range or choices, read from the
    /// parameter struct's schema ([`crate::params::describe`]).
    pub fn describe(&self) -> Vec<ParamDoc> {
        (self.describe)()
    }

    /// The one parameter check: the defaults overlaid with `overrides`, every key known, every
    /// value of the right type and in range. Returns the full table the technique would run
    /// with; the error names the key and what would be accepted.
    pub fn check(&self, overrides: &toml::Table) -> Result<toml::Table> {
        (self.check)(&self.expand(overrides)?)
    }

    /// Creates the technique with `overrides` (checked as by [`Self::check`]).
    pub fn create(
        &self,
        ctx: &InitContext<'_>,
        overrides: &toml::Table,
    ) -> Result<Box<dyn GrassTechnique>> {
        (self.create)(ctx, &self.expand(overrides)?)
    }

    /// What [`Self::create`] with `overrides` will allocate on the GPU (no GPU work).
    pub fn estimate(&self, scene: &Scene, overrides: &toml::Table) -> Result<GpuEstimate> {
        (self.estimate)(scene, &self.expand(overrides)?)
    }

    /// `overrides` with its [`VARIANT_KEY`] replaced by the variant it names: the variant's
    /// overrides first, the table's other keys on top. Without the key, the table as it is;
    /// with a name the technique does not offer, an error listing those it does.
    pub fn expand(&self, overrides: &toml::Table) -> Result<toml::Table> {
        let Some(value) = overrides.get(VARIANT_KEY) else {
            return Ok(overrides.clone());
        };
        let offered = || {
            std::iter::once(DEFAULT_VARIANT)
                .chain(self.variants.iter().map(|v| v.name))
                .map(|n| format!("\"{n}\""))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let Some(name) = value.as_str() else {
            return Err(Error::param(
                format!("{}.{VARIANT_KEY}", self.info.id),
                value,
                format!("a variant name, one of {}", offered()),
            ));
        };
        let variant = if name == DEFAULT_VARIANT {
            toml::Table::new()
        } else {
            match self.variant(name) {
                Some(parsed) => parsed?,
                None => {
                    return Err(Error::param(
                        format!("{}.{VARIANT_KEY}", self.info.id),
                        name,
                        format!("one of {}", offered()),
                    ));
                }
            }
        };
        let mut rest = overrides.clone();
        rest.remove(VARIANT_KEY);
        Ok(overlay(&variant, &rest))
    }

    /// The device limits [`Self::create`] with `overrides` needs on `scene` (no GPU work):
    /// [`Technique::required_limits`], with `max_buffer_size` raised to the estimate's largest
    /// buffer.
    pub fn required_limits(&self, scene: &Scene, overrides: &toml::Table) -> Result<wgpu::Limits> {
        (self.limits)(scene, &self.expand(overrides)?)
    }

    /// The overrides of variant `name`, if the technique offers it.
    pub fn variant(&self, name: &str) -> Option<Result<toml::Table>> {
        self.variants
            .get(name)
            .map(|params| self.parse_variant(name, params))
    }

    /// The overrides of its [`FINEST`] variant (every technique has one).
    pub fn finest(&self) -> Result<toml::Table> {
        self.parse_variant(FINEST, self.variants.finest)
    }

    fn parse_variant(&self, name: &str, params: &str) -> Result<toml::Table> {
        params.parse::<toml::Table>().map_err(|e| Error::Technique {
            technique: self.info.id.to_owned(),
            message: format!("variant `{name}` is not valid TOML: {e}"),
        })
    }
}

impl std::fmt::Debug for TechniqueEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TechniqueEntry")
            .field("info", &self.info)
            .field("variants", &self.variants)
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::check_ranges;
    use crate::technique::{FrameEncoder, TechniqueStats};
    use serde::{Deserialize, Serialize};

    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct Knobs {
        /// Shells.
        #[schemars(range(min = 1, max = 64))]
        shells: u32,
        /// Bend.
        #[schemars(range(min = 0.0, max = 1.0))]
        bend: f32,
    }

    impl Default for Knobs {
        fn default() -> Self {
            Self {
                shells: 8,
                bend: 0.5,
            }
        }
    }

    impl TechniqueParams for Knobs {
        fn validate(&self) -> Result<()> {
            check_ranges("toy", self)
        }
    }

    struct Toy(Knobs);

    impl Technique for Toy {
        type Params = Knobs;
        const INFO: TechniqueInfo = TechniqueInfo {
            id: "toy",
            name: "toy",
            paper: "-",
            gpu_state: false,
            debug_views: &[],
        };
        const VARIANTS: Variants = Variants {
            finest: "shells = 64",
            others: &[Variant {
                name: NO_TRANSITIONS,
                params: "bend = 0.0",
            }],
        };
        fn new(_ctx: &InitContext<'_>, params: Knobs) -> Result<Self> {
            Ok(Self(params))
        }
        fn estimate(_scene: &Scene, params: &Knobs) -> Result<GpuEstimate> {
            Ok(GpuEstimate::buffer(u64::from(params.shells) * 100))
        }
        fn params(&self) -> &Knobs {
            &self.0
        }
    }

    impl GrassTechnique for Toy {
        fn encode(&self, _encoder: &mut FrameEncoder<'_>) {}
        fn stats(&self) -> TechniqueStats {
            TechniqueStats::default()
        }
    }

    const TOY: TechniqueEntry = entry::<Toy>();

    /// A small flat field: the toy's estimate does not depend on it.
    const TOY_SCENE: &str = r#"
        name = "toy"
        [terrain]
        size = [8.0, 8.0]
        max_height = 0.0
        height = { kind = "constant", value = 0.0 }
        density = { kind = "constant", value = 1.0 }
        covering = { kind = "grass" }
        [camera]
        fov_y = 50.0
        near = 0.1
        far = 100.0
        [camera.path]
        kind = "orbit"
        center = [0.0, 0.0, 0.0]
        radius = 10.0
        height = 2.0
        period = 60.0
        start_angle = 0.0
    "#;

    fn table(text: &str) -> toml::Table {
        text.parse().unwrap()
    }

    #[test]
    fn the_entry_checks_defaults_overrides_keys_types_and_ranges_in_one_place() {
        assert_eq!(TOY.info.id, "toy");
        assert_eq!(TOY.default_params(), table("shells = 8\nbend = 0.5"));
        assert_eq!(
            TOY.check(&table("shells = 12")).unwrap(),
            table("shells = 12\nbend = 0.5")
        );
        let unknown = TOY.check(&table("shelz = 12")).unwrap_err().to_string();
        assert!(
            unknown.contains("toy.shelz") && unknown.contains("toy.shells"),
            "{unknown}"
        );
        let range = TOY.check(&table("shells = -4")).unwrap_err().to_string();
        assert!(range.contains("toy"), "{range}");
        let nan = TOY.check(&table("bend = nan")).unwrap_err().to_string();
        assert!(nan.contains("toy.bend"), "{nan}");
        let kind = TOY
            .check(&table("bend = \"much\""))
            .unwrap_err()
            .to_string();
        assert!(kind.contains("toy"), "{kind}");
    }

    #[test]
    fn the_estimate_sees_the_same_resolved_parameters() {
        let scene = Scene::from_toml(TOY_SCENE, std::path::Path::new("toy.toml")).unwrap();
        assert_eq!(TOY.estimate(&scene, &table("")).unwrap().bytes, 800);
        assert_eq!(
            TOY.estimate(&scene, &table("shells = 2")).unwrap().bytes,
            200
        );
        assert!(TOY.estimate(&scene, &table("shells = 0")).is_err());
    }

    #[test]
    fn variants_list_finest_first_and_parse() {
        let names: Vec<_> = TOY.variants.iter().map(|v| v.name).collect();
        assert_eq!(names, [FINEST, NO_TRANSITIONS]);
        assert_eq!(TOY.finest().unwrap(), table("shells = 64"));
        assert_eq!(
            TOY.variant(NO_TRANSITIONS).unwrap().unwrap(),
            table("bend = 0.0")
        );
        assert!(TOY.variant("paper").is_none());
    }

    #[test]
    fn variant_differences_catch_a_wrong_value_an_uncited_key_and_bad_toml() {
        let cited = Knobs {
            shells: 64,
            ..Knobs::default()
        };
        assert!(variant_differences("toy", "shells = 64", &cited, 1).is_empty());
        // A value other than the cited one.
        assert_eq!(
            variant_differences("toy", "shells = 63", &cited, 1).len(),
            2
        );
        // A key that merely repeats the default is still a key the paper does not state.
        let extra = variant_differences("toy", "shells = 64\nbend = 0.5", &cited, 1);
        assert_eq!(extra, ["2 keys for 1 cited constants"]);
        assert!(!variant_differences("toy", "shells = ", &cited, 1).is_empty());
        assert!(!variant_differences("toy", "shellz = 64", &cited, 1).is_empty());
    }

    #[test]
    fn a_variant_key_expands_under_the_other_overrides_and_unknown_names_are_refused() {
        // The variant's own value, the defaults elsewhere.
        assert_eq!(
            TOY.check(&table("variant = \"finest\"")).unwrap(),
            table("shells = 64\nbend = 0.5")
        );
        // An explicit key wins over the variant's.
        assert_eq!(
            TOY.check(&table("variant = \"finest\"\nshells = 3"))
                .unwrap(),
            table("shells = 3\nbend = 0.5")
        );
        assert_eq!(
            TOY.check(&table("variant = \"default\"")).unwrap(),
            TOY.default_params()
        );
        let scene = Scene::from_toml(TOY_SCENE, std::path::Path::new("toy.toml")).unwrap();
        assert_eq!(
            TOY.estimate(&scene, &table("variant = \"finest\""))
                .unwrap()
                .bytes,
            6400
        );
        let unknown = TOY
            .check(&table("variant = \"paper\""))
            .unwrap_err()
            .to_string();
        assert!(
            unknown.contains("toy.variant") && unknown.contains("\"no_transitions\""),
            "{unknown}"
        );
        assert_eq!(
            label_params(&table("variant = \"paper\""), "a=1"),
            "variant=paper;a=1"
        );
        assert_eq!(label_params(&table("variant = \"default\""), "a=1"), "a=1");
        let kind = TOY.check(&table("variant = 3")).unwrap_err().to_string();
        assert!(kind.contains("toy.variant"), "{kind}");
    }
}
