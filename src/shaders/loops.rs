//! Loops whose trip count a uniform buffer sets: `for (var k = 0u; k < params.count; k++)`.
//!
//! On a GPU such a loop costs its trips and nothing more. On lavapipe (Mesa 22, the software
//! rasteriser the harness is measured on) a shader whose loop exits on a uniform-buffer value
//! is re-specialised every time its pipeline is bound: the driver copies the shader, inlines
//! the uniform's current value, unrolls the loop and optimises the result on the CPU before
//! the next draw or dispatch, outside every timestamped pass. For bakay's bend pass (a loop
//! over 16 shells) that was 5-6 ms a frame, which the cost model could not see and which no
//! GPU pays: bakay's football field measured 12 ms with the bound in the uniform and 6 ms
//! with the same bound as a constant (320x180, `results/cost_model/README.md`).
//!
//! A count fixed when the technique is created belongs in a pipeline-overridable constant
//! (WGSL `override`, set through [`crate::shaders::PipelineSpec::constants`]), which every
//! driver specialises once, at pipeline creation; a count that changes every frame in a
//! storage buffer. [`uniform_bound_loops`] finds the loops that do neither, and a test holds
//! every shader of the repository to it (`tests/tests/shaders.rs`).
//!
//! The analysis follows values through expressions and local variables within a function
//! (not through a call's arguments): a loop exits on a uniform when the condition of an `if`
//! that breaks out of it, or its `break if`, reads a `var<uniform>` global.

use std::collections::HashSet;

/// The functions (entry points by their name, helpers by theirs) holding a loop whose exit
/// condition reads a uniform buffer, once each, in the module's order.
pub fn uniform_bound_loops(module: &naga::Module) -> Vec<String> {
    let helpers = module
        .functions
        .iter()
        .map(|(_, f)| (f.name.clone().unwrap_or_default(), f));
    let entries = module
        .entry_points
        .iter()
        .map(|e| (e.name.clone(), &e.function));
    helpers
        .chain(entries)
        .filter(|(_, f)| Taint::of(module, f).has_uniform_bound_loop(&f.body))
        .map(|(name, _)| name)
        .collect()
}

/// Which expressions and local variables of one function carry a uniform buffer's value.
struct Taint {
    expressions: Vec<bool>,
}

impl Taint {
    /// Follows uniform values through `function`'s expressions and the stores into its local
    /// variables until nothing new is reached (a store can feed a load written before it in
    /// the arena, inside a loop).
    fn of(module: &naga::Module, function: &naga::Function) -> Self {
        let mut locals = HashSet::new();
        let mut stores = Vec::new();
        super::walk::for_each_statement(&function.body, &mut |s| {
            if let naga::Statement::Store { pointer, value } = s {
                stores.push((*pointer, *value));
            }
        });
        loop {
            let expressions = expression_taint(module, function, &locals);
            let tainted = |e: naga::Handle<naga::Expression>| expressions[e.index()];
            let mut grown = false;
            for (handle, local) in function.local_variables.iter() {
                if local.init.is_some_and(tainted) && locals.insert(handle) {
                    grown = true;
                }
            }
            for &(pointer, value) in &stores {
                if let Some(local) = root_local(function, pointer)
                    && tainted(value)
                    && locals.insert(local)
                {
                    grown = true;
                }
            }
            if !grown {
                return Self { expressions };
            }
        }
    }

    fn tainted(&self, e: naga::Handle<naga::Expression>) -> bool {
        self.expressions.get(e.index()).copied().unwrap_or(false)
    }

    /// Whether `block` (nested blocks included) holds a loop that exits on a tainted value.
    fn has_uniform_bound_loop(&self, block: &naga::Block) -> bool {
        use naga::Statement as S;
        block.iter().any(|statement| match statement {
            S::Loop {
                body,
                continuing,
                break_if,
            } => {
                break_if.is_some_and(|c| self.tainted(c))
                    || body.iter().any(|s| self.breaks_on_taint(s))
                    || self.has_uniform_bound_loop(body)
                    || self.has_uniform_bound_loop(continuing)
            }
            S::Block(b) => self.has_uniform_bound_loop(b),
            S::If { accept, reject, .. } => {
                self.has_uniform_bound_loop(accept) || self.has_uniform_bound_loop(reject)
            }
            S::Switch { cases, .. } => cases.iter().any(|c| self.has_uniform_bound_loop(&c.body)),
            _ => false,
        })
    }

    /// Whether `statement`, directly in a loop's body, is an `if` on a tainted condition with
    /// a `break` on one side (what `for` and `while` conditions become).
    fn breaks_on_taint(&self, statement: &naga::Statement) -> bool {
        let breaks = |b: &naga::Block| b.iter().any(|s| matches!(s, naga::Statement::Break));
        match statement {
            naga::Statement::If {
                condition,
                accept,
                reject,
            } => self.tainted(*condition) && (breaks(accept) || breaks(reject)),
            _ => false,
        }
    }
}

/// The local variable a pointer expression points into (`v`, `v[i]`, `v.x`), if any.
pub(super) fn root_local(
    function: &naga::Function,
    mut pointer: naga::Handle<naga::Expression>,
) -> Option<naga::Handle<naga::LocalVariable>> {
    use naga::Expression as E;
    // A pointer chain is no longer than the arena.
    for _ in 0..function.expressions.len() {
        match function.expressions[pointer] {
            E::LocalVariable(l) => return Some(l),
            E::Access { base, .. } | E::AccessIndex { base, .. } => pointer = base,
            _ => return None,
        }
    }
    None
}

/// Whether each expression of `function` (by index) reads a uniform buffer, directly or
/// through its operands, given the local variables already known to hold one's value.
/// naga's arena lists an expression's operands before it, so one pass in order suffices.
fn expression_taint(
    module: &naga::Module,
    function: &naga::Function,
    locals: &HashSet<naga::Handle<naga::LocalVariable>>,
) -> Vec<bool> {
    use naga::Expression as E;
    let mut taint = vec![false; function.expressions.len()];
    for (handle, expression) in function.expressions.iter() {
        let t = |e: &naga::Handle<naga::Expression>| taint.get(e.index()).copied().unwrap_or(false);
        let value = match expression {
            E::GlobalVariable(g) => {
                module.global_variables[*g].space == naga::AddressSpace::Uniform
            }
            E::LocalVariable(l) => locals.contains(l),
            other => {
                super::walk::value_operands(other).is_some_and(|operands| operands.iter().any(t))
            }
        };
        taint[handle.index()] = value;
    }
    taint
}

#[cfg(test)]
mod tests {
    use super::*;

    fn loops_of(wgsl: &str) -> Vec<String> {
        let module = naga::front::wgsl::parse_str(wgsl).expect("test WGSL parses");
        uniform_bound_loops(&module)
    }

    const HEADER: &str = "
        struct P { n: u32, m: vec4<u32> }
        @group(0) @binding(0) var<uniform> p: P;
        @group(0) @binding(1) var<storage, read_write> out: array<u32>;
        override N: u32 = 4u;
    ";

    #[test]
    fn a_for_bounded_by_a_uniform_is_found_through_lets_locals_and_arithmetic() {
        let cases = [
            "for (var k = 0u; k < p.n; k++) { out[k] = k; }",
            "let n = p.m.y * 2u; for (var k = 0u; k < n; k++) { out[k] = k; }",
            "var hi = p.n; var lo = 0u; while (hi - lo > 1u) { hi = (hi + lo) / 2u; }",
            "var n = 1u; n = min(p.m.x, 8u); var k = 0u; loop { if (k >= n) { break; } k++; }",
            "var k = 0u; loop { k++; continuing { break if k > p.n; } }",
            "if (id.x > 0u) { for (var k = 0u; k < u32(f32(p.n) * 0.5); k++) { out[k] = k; } }",
        ];
        for body in cases {
            let wgsl = format!(
                "{HEADER} @compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{ {body} }}"
            );
            assert_eq!(loops_of(&wgsl), ["main"], "{body}");
        }
    }

    #[test]
    fn loops_bounded_by_constants_overrides_storage_or_inputs_pass() {
        let cases = [
            "for (var k = 0u; k < 8u; k++) { out[k] = p.n; }",
            "for (var k = 0u; k < N; k++) { out[k] = k; }",
            "for (var k = 0u; k < out[0]; k++) { out[k + 1u] = k; }",
            "for (var k = 0u; k < id.x; k++) { out[k] = k; }",
            // A uniform read inside the body, or a branch on one that does not leave the
            // loop, is not a bound.
            "for (var k = 0u; k < 4u; k++) { if (p.n > k) { out[k] = k; } }",
            // An early exit on a uniform outside any loop.
            "if (p.n == 0u) { return; } out[0] = 1u;",
        ];
        for body in cases {
            let wgsl = format!(
                "{HEADER} @compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{ {body} }}"
            );
            assert!(loops_of(&wgsl).is_empty(), "{body}");
        }
    }

    #[test]
    fn a_helper_function_is_named_once() {
        let wgsl = format!(
            "{HEADER}
            fn walk(x: u32) -> u32 {{
                var s = x;
                for (var k = 0u; k < p.n; k++) {{ s += k; }}
                for (var k = 0u; k < p.m.x; k++) {{ s += k; }}
                return s;
            }}
            @compute @workgroup_size(1) fn main() {{ out[0] = walk(1u); }}"
        );
        assert_eq!(loops_of(&wgsl), ["walk"]);
    }
}
