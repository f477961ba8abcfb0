//! What one shader invocation reads from textures: its `textureLoad`s (a texel, unfiltered)
//! and its `textureSample*`s (filtered: bilinear or trilinear, mip level chosen), counted in
//! the entry point's naga IR and in every function it calls. On a software rasteriser each is
//! a stretch of code per invocation, and the pipeline statistics count invocations, not what
//! happens inside one; these counts let the cost model price that (`crate::cost`).
//!
//! The count is static: a call counts its callee's fetches once per call site, a loop's body
//! once, and both sides of a branch. So it is exact for straight-line shaders (most of the
//! harness's) and an upper bound where a branch skips fetches (debug views).

use std::collections::HashMap;

/// Texture reads of one invocation of a shader entry point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct TextureFetches {
    /// `textureLoad` calls (one texel, no filtering).
    pub loads: u64,
    /// `textureSample*` and `textureGather*` calls (filtered).
    pub samples: u64,
}

impl std::ops::Add for TextureFetches {
    type Output = Self;

    fn add(self, o: Self) -> Self {
        Self {
            loads: self.loads + o.loads,
            samples: self.samples + o.samples,
        }
    }
}

/// The texture fetches of every entry point of `module` (a parsed, composed shader), by name.
pub fn entry_fetches(module: &naga::Module) -> Vec<(String, TextureFetches)> {
    let mut memo = HashMap::new();
    module
        .entry_points
        .iter()
        .map(|e| {
            (
                e.name.clone(),
                function_fetches(module, &e.function, &mut memo, 0),
            )
        })
        .collect()
}

/// Deepest call chain followed (WGSL forbids recursion; this only bounds a malformed IR).
const MAX_CALL_DEPTH: u32 = 64;

/// The fetches of `function`: its own image expressions plus its callees', once per call site.
fn function_fetches(
    module: &naga::Module,
    function: &naga::Function,
    memo: &mut HashMap<naga::Handle<naga::Function>, TextureFetches>,
    depth: u32,
) -> TextureFetches {
    let own = function
        .expressions
        .iter()
        .fold(TextureFetches::default(), |acc, (_, e)| match e {
            naga::Expression::ImageSample { .. } => TextureFetches {
                samples: acc.samples + 1,
                ..acc
            },
            naga::Expression::ImageLoad { .. } => TextureFetches {
                loads: acc.loads + 1,
                ..acc
            },
            _ => acc,
        });
    let mut calls = Vec::new();
    collect_calls(&function.body, &mut calls);
    calls.into_iter().fold(own, |acc, callee| {
        let fetches = match memo.get(&callee) {
            Some(f) => *f,
            None if depth < MAX_CALL_DEPTH => {
                let f = function_fetches(module, &module.functions[callee], memo, depth + 1);
                memo.insert(callee, f);
                f
            }
            None => TextureFetches::default(),
        };
        acc + fetches
    })
}

/// Every function called in `block`, once per call site, nested blocks included.
fn collect_calls(block: &naga::Block, out: &mut Vec<naga::Handle<naga::Function>>) {
    use naga::Statement as S;
    for statement in block.iter() {
        match statement {
            S::Call { function, .. } => out.push(*function),
            S::Block(b) => collect_calls(b, out),
            S::If { accept, reject, .. } => {
                collect_calls(accept, out);
                collect_calls(reject, out);
            }
            S::Switch { cases, .. } => {
                for c in cases {
                    collect_calls(&c.body, out);
                }
            }
            S::Loop {
                body, continuing, ..
            } => {
                collect_calls(body, out);
                collect_calls(continuing, out);
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SOURCE: &str = "
        @group(0) @binding(0) var t: texture_2d<f32>;
        @group(0) @binding(1) var s: sampler;
        fn height(p: vec2<i32>) -> f32 {
            return textureLoad(t, p, 0).r + textureLoad(t, p + vec2(1, 0), 0).r;
        }
        fn tint(uv: vec2<f32>) -> vec4<f32> {
            return textureSample(t, s, uv) * height(vec2(0, 0));
        }
        @vertex fn vs(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
            let h = height(vec2(i32(v), 0)) + height(vec2(0, i32(v)));
            return vec4(h);
        }
        @fragment fn fs(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
            var c = tint(uv);
            if (uv.x > 0.5) {
                c += textureSampleLevel(t, s, uv, 1.0);
            }
            for (var i = 0; i < 4; i++) {
                c += textureSampleGrad(t, s, uv, vec2(0.1), vec2(0.1));
            }
            return c;
        }
        @fragment fn plain(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
            return vec4(uv, 0.0, 1.0);
        }
    ";

    fn of(name: &str) -> TextureFetches {
        entry_fetches(&naga::front::wgsl::parse_str(SOURCE).unwrap())
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, f)| f)
            .unwrap_or_else(|| panic!("no entry {name}"))
    }

    #[test]
    fn calls_count_per_call_site_and_loops_and_branches_once() {
        // Two calls of a two-load function.
        assert_eq!(
            of("vs"),
            TextureFetches {
                loads: 4,
                samples: 0
            }
        );
        // tint: 1 sample + height's 2 loads; the branch's sample; the loop body's once.
        assert_eq!(
            of("fs"),
            TextureFetches {
                loads: 2,
                samples: 3
            }
        );
        assert_eq!(of("plain"), TextureFetches::default());
    }
}
