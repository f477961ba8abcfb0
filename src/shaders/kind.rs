//! What a render pipeline's fragments cost: opaque, alpha-tested or blended. The kind is read
//! off the pipeline itself — its colour targets' blend state, alpha to coverage, and whether
//! its fragment entry point can `discard` (found in the shader's naga IR) — so no technique
//! declares it, and the work counters ([`crate::technique::work`]) split fragment invocations
//! by it for the cost model.

/// How a pipeline's fragments reach the target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FragmentKind {
    /// Written as they are (depth-tested or not): no discard, no blending.
    #[default]
    Opaque,
    /// The fragment shader can discard, or alpha to coverage is on: the alpha test of cut-out
    /// blades, leaves and slices.
    AlphaTested,
    /// Blended with what is under them (a blend state other than replace).
    Blended,
}

impl FragmentKind {
    /// Every kind, in column order.
    pub const ALL: [FragmentKind; 3] = [Self::Opaque, Self::AlphaTested, Self::Blended];

    /// `opaque`, `alpha_tested` or `blended`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Opaque => "opaque",
            Self::AlphaTested => "alpha_tested",
            Self::Blended => "blended",
        }
    }

    /// The kind of a pipeline with these colour `targets`, multisample state and fragment
    /// entry point (`discards`: whether it can discard). Blending wins over the alpha test:
    /// a blended fragment pays for both its read-modify-write and any test before it.
    pub fn of(
        targets: &[Option<wgpu::ColorTargetState>],
        multisample: &wgpu::MultisampleState,
        discards: bool,
    ) -> Self {
        let blended = targets.iter().flatten().any(|t| {
            t.blend.is_some_and(|b| {
                b != wgpu::BlendState::REPLACE && t.write_mask != wgpu::ColorWrites::empty()
            })
        });
        if blended {
            Self::Blended
        } else if discards || multisample.alpha_to_coverage_enabled {
            Self::AlphaTested
        } else {
            Self::Opaque
        }
    }
}

/// A shader module created by [`super::module`]: the wgpu module (what `Deref` gives), which
/// fragment entry points can discard, and what its entry points' invocations do (counted
/// per pipeline, whose overridable constants can set its loops' trips).
#[derive(Debug)]
pub struct Module {
    pub(super) raw: wgpu::ShaderModule,
    pub(super) discarding: Vec<String>,
    /// The parsed module and its validation (`None`: naga could not parse it, the device
    /// reports why), what [`Module::ops`] counts in.
    pub(super) parsed: Option<super::Parsed>,
    /// Its textures of floating-point texels ([`super::float_textures`]).
    pub(super) float: Vec<String>,
    /// Its textures and samplers that read one mip level ([`super::module_with_bindings`]).
    pub(super) single_level: Vec<String>,
}

impl std::ops::Deref for Module {
    type Target = wgpu::ShaderModule;

    fn deref(&self) -> &wgpu::ShaderModule {
        &self.raw
    }
}

impl Module {
    /// The interpolated input slots of fragment entry point `entry` ([`fragment_inputs`]);
    /// 0 for an unknown entry or a module naga could not parse.
    pub fn fragment_inputs(&self, entry: &str) -> u32 {
        self.parsed
            .as_ref()
            .map_or(0, |(module, _)| fragment_inputs(module, entry))
    }

    /// Whether fragment entry point `entry` can discard.
    pub fn discards(&self, entry: &str) -> bool {
        self.discarding.iter().any(|e| e == entry)
    }

    /// The costly operations (texture fetches, transcendentals, ...) of one invocation of
    /// entry point `entry` in a pipeline with these overridable `constants` (as
    /// [`super::PipelineSpec::constants`]; its loops bounded by them run that many times);
    /// none for an unknown entry: the device reports it when the pipeline is created.
    pub fn ops(&self, entry: &str, constants: &[(&str, f64)]) -> super::ShaderOps {
        let Some((module, info)) = &self.parsed else {
            return super::ShaderOps::default();
        };
        let float: Vec<&str> = self.float.iter().map(String::as_str).collect();
        let single_level: Vec<&str> = self.single_level.iter().map(String::as_str).collect();
        let bound = super::Bound {
            float: &float,
            single_level: &single_level,
        };
        super::ops::count_entries(module, info.as_ref(), bound, constants, Some(entry))
            .into_iter()
            .next()
            .map(|(_, f)| f)
            .unwrap_or_default()
    }
}

/// The input slots (`@location`s, flat ones too) fragment entry point `entry` of `module`
/// reads, arguments and the members of struct arguments alike: what a rasteriser sets up for
/// every triangle it rasterises, one plane equation a slot (lavapipe: a sub-pixel triangle 68 ns
/// with none, 135 with five, `results/cost_model/README.md`, *Instances and interpolated
/// inputs*).
/// 0 for a name that is no fragment entry point.
pub fn fragment_inputs(module: &naga::Module, entry: &str) -> u32 {
    let Some(ep) = module
        .entry_points
        .iter()
        .find(|e| e.name == entry && e.stage == naga::ShaderStage::Fragment)
    else {
        return 0;
    };
    let is_location = |b: &Option<naga::Binding>| matches!(b, Some(naga::Binding::Location { .. }));
    ep.function
        .arguments
        .iter()
        .map(|arg| match &module.types[arg.ty].inner {
            naga::TypeInner::Struct { members, .. } if arg.binding.is_none() => {
                members.iter().filter(|m| is_location(&m.binding)).count()
            }
            _ => usize::from(is_location(&arg.binding)),
        })
        .sum::<usize>() as u32
}

/// The fragment entry points of `module` (a parsed, composed shader) that can reach a
/// `discard`, directly or through the functions they call.
pub fn discarding_fragment_entries(module: &naga::Module) -> Vec<String> {
    module
        .entry_points
        .iter()
        .filter(|e| e.stage == naga::ShaderStage::Fragment)
        .filter(|e| block_discards(module, &e.function.body, &mut Vec::new()))
        .map(|e| e.name.clone())
        .collect()
}

/// Whether `block` (of `module`) can discard; `seen` guards against visiting a function twice.
fn block_discards(
    module: &naga::Module,
    block: &naga::Block,
    seen: &mut Vec<naga::Handle<naga::Function>>,
) -> bool {
    use naga::Statement as S;
    block.iter().any(|statement| match statement {
        S::Kill => true,
        S::Block(b) => block_discards(module, b, seen),
        S::If { accept, reject, .. } => {
            block_discards(module, accept, seen) || block_discards(module, reject, seen)
        }
        S::Switch { cases, .. } => cases.iter().any(|c| block_discards(module, &c.body, seen)),
        S::Loop {
            body, continuing, ..
        } => block_discards(module, body, seen) || block_discards(module, continuing, seen),
        S::Call { function, .. } => {
            if seen.contains(function) {
                false
            } else {
                seen.push(*function);
                block_discards(module, &module.functions[*function].body, seen)
            }
        }
        _ => false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SOURCE: &str = "
        fn cut(a: f32) { if (a < 0.5) { discard; } }
        @fragment fn direct(@location(0) a: f32) -> @location(0) vec4<f32> {
            if (a < 0.1) { discard; }
            return vec4(a);
        }
        @fragment fn through_a_call(@location(0) a: f32) -> @location(0) vec4<f32> {
            loop { cut(a); break; }
            return vec4(a);
        }
        @fragment fn never(@location(0) a: f32) -> @location(0) vec4<f32> {
            return vec4(a);
        }
    ";

    #[test]
    fn fragment_inputs_count_locations_of_arguments_and_struct_members() {
        let module = naga::front::wgsl::parse_str(
            "struct In { @builtin(position) p: vec4<f32>, @location(0) a: vec3<f32>, \
             @location(1) @interpolate(flat) b: u32 }\n\
             @fragment fn structured(v: In) -> @location(0) vec4<f32> { return vec4(v.a, 1.0); }\n\
             @fragment fn loose(@builtin(position) p: vec4<f32>, @location(0) a: vec4<f32>, \
             @location(2) c: f32, s: In) -> @location(0) vec4<f32> { return a * c; }\n\
             @fragment fn bare(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> { return p; }\n\
             @vertex fn vs() -> @builtin(position) vec4<f32> { return vec4(0.0); }",
        )
        .unwrap();
        assert_eq!(fragment_inputs(&module, "structured"), 2);
        assert_eq!(fragment_inputs(&module, "loose"), 4);
        assert_eq!(fragment_inputs(&module, "bare"), 0);
        // A vertex entry point or an unknown name reads no fragment inputs.
        assert_eq!(fragment_inputs(&module, "vs"), 0);
        assert_eq!(fragment_inputs(&module, "missing"), 0);
    }

    #[test]
    fn discards_are_found_directly_and_through_calls() {
        let mut found = discarding_fragment_entries(&naga::front::wgsl::parse_str(SOURCE).unwrap());
        found.sort();
        assert_eq!(found, ["direct", "through_a_call"]);
    }

    #[test]
    fn blending_wins_then_the_alpha_test() {
        let target = |blend| {
            [Some(wgpu::ColorTargetState {
                format: wgpu::TextureFormat::Rgba8Unorm,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            })]
        };
        let ms = wgpu::MultisampleState::default();
        let a2c = wgpu::MultisampleState {
            count: 4,
            alpha_to_coverage_enabled: true,
            ..Default::default()
        };
        let blend = Some(wgpu::BlendState::ALPHA_BLENDING);
        assert_eq!(
            FragmentKind::of(&target(None), &ms, false),
            FragmentKind::Opaque
        );
        assert_eq!(
            FragmentKind::of(&target(Some(wgpu::BlendState::REPLACE)), &ms, false),
            FragmentKind::Opaque
        );
        assert_eq!(
            FragmentKind::of(&target(None), &ms, true),
            FragmentKind::AlphaTested
        );
        assert_eq!(
            FragmentKind::of(&target(None), &a2c, false),
            FragmentKind::AlphaTested
        );
        assert_eq!(
            FragmentKind::of(&target(blend), &ms, true),
            FragmentKind::Blended
        );
        // Depth- or stencil-only passes (nothing written to colour) are not blended.
        let masked = [Some(wgpu::ColorTargetState {
            format: wgpu::TextureFormat::Rgba8Unorm,
            blend,
            write_mask: wgpu::ColorWrites::empty(),
        })];
        assert_eq!(FragmentKind::of(&masked, &ms, false), FragmentKind::Opaque);
    }
}
