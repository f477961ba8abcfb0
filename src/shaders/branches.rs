//! Branches on a uniform alone: `if (globals.frame.z == 1u)`, `if (omega <= 0.0)` where every
//! caller passes `params.lod.z`.
//!
//! On a GPU such a branch costs a compare and, the value being the same for every invocation,
//! nothing more. On lavapipe (Mesa 22, the software rasteriser the harness is measured on) a
//! shader whose `if` condition is computed from uniform-buffer values and constants alone can
//! be re-specialised every time its pipeline is bound: the driver clones the shader, replaces
//! those uniforms with their current values, optimises the result and compiles it again
//! before the draw, on the CPU, inside the pass. With Mesa's on-disk shader cache warm the
//! compile is a cache hit (still a clone, an optimisation and a lookup per bind); with the
//! cache cold or off it is a full LLVM compile every frame. Counted here by the LLVM modules
//! llvmpipe creates (a debugger's breakpoint on `LLVMModuleCreateWithNameInContext`, 8 and 24
//! measured frames on the football field): the reference's vertex shader, with its debug-view
//! branch on `globals.frame.z`, made one new vertex-shader module every frame, and none once
//! that branch became a `select`; with Mesa's shader cache off its pitch then took the same
//! time as with it on (it took 1.5x before). Boulanger's horizontal-slice vertex shaders (the
//! slices and their ground shadows) made two a frame, for Appendix A's degenerate-triangle test
//! on the sun's direction (`right_triangle_area`, reached through `btf_weights` with a local
//! written twice in straight-line code); once a `select`, none, and its pitch took the same
//! time with the cache off as on (4-5x before: the "slow pitch" of `results/run_to_run/`).
//! Zhang, bakay, perbet and jahrmann made none.
//!
//! Whether the driver keeps re-specialising a given shader depends on its own heuristics (the
//! shader's size, how much the inlined values remove, which branches its optimiser turns into
//! selects), which move with every edit; so every vertex shader is held to the rule
//! (`tests/tests/shaders.rs`), whether or not the driver re-specialises it today: a flag fixed
//! when the technique is created belongs in a pipeline-overridable constant (WGSL `override`),
//! one that may change (a debug view) in a `select` (with `&` and `|`, which do not
//! short-circuit into a branch as `&&` and `||` do) or in a storage buffer. Fragment and compute
//! shaders are left out, on the same count: no fragment or compute module was made again in any
//! technique's frames, though the prelude's point-light branch (`shade_leaf`, every technique's
//! fragments), bakay's wind-mode branch and jahrmann's ranges branch are on uniforms alone.
//!
//! A condition is "on a uniform alone" the way the driver's own analysis reads it after
//! inlining every function: its value is computed, through arithmetic, comparisons, selects,
//! `let`s, locals written only at the top level of a function (straight-line code, however
//! often) and the arguments of the calls that lead to it, from uniform-buffer loads at fixed
//! places and constants only. A value carried round a loop or merged from two branches is not
//! (the driver sees a phi there).

use std::collections::{HashMap, HashSet};

/// An `if` or `switch` whose selector is computed from uniform-buffer values and constants
/// alone, reached from an entry point.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct UniformBranch {
    /// The entry point whose call tree holds the branch.
    pub entry: String,
    /// Its stage.
    pub stage: naga::ShaderStage,
    /// The function holding the branch (the entry point's own name when it is there).
    pub function: String,
}

/// Every branch on a uniform alone in `module`, once per entry point and function, in the
/// module's order of entry points.
pub fn uniform_branches(module: &naga::Module) -> Vec<UniformBranch> {
    let mut found = Vec::new();
    for entry in &module.entry_points {
        let mut functions = Vec::new();
        let arguments = vec![Purity::Varying; entry.function.arguments.len()];
        visit(
            module,
            &entry.function,
            &entry.name,
            &arguments,
            &mut functions,
            0,
        );
        let mut seen = HashSet::new();
        for function in functions {
            if seen.insert(function.clone()) {
                found.push(UniformBranch {
                    entry: entry.name.clone(),
                    stage: entry.stage,
                    function,
                });
            }
        }
    }
    found
}

/// What an expression's value is computed from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Purity {
    /// Constants only (literals, constants, overrides).
    Constant,
    /// Uniform-buffer values and constants, at least one uniform.
    Uniform,
    /// Anything else: inputs, storage, textures, phis.
    Varying,
}

impl Purity {
    /// The purity of a value computed from operands of these purities.
    fn join(self, other: Self) -> Self {
        use Purity::*;
        match (self, other) {
            (Varying, _) | (_, Varying) => Varying,
            (Uniform, _) | (_, Uniform) => Uniform,
            (Constant, Constant) => Constant,
        }
    }
}

/// Pushes the names of the functions of `function`'s call tree (itself included, as `name`)
/// holding a branch on a uniform alone, given its arguments' purities.
fn visit(
    module: &naga::Module,
    function: &naga::Function,
    name: &str,
    arguments: &[Purity],
    found: &mut Vec<String>,
    depth: usize,
) {
    // WGSL forbids recursion; the depth only guards against a malformed module.
    if depth > module.functions.len() {
        return;
    }
    let purity = expression_purity(module, function, arguments);
    let of = |e: naga::Handle<naga::Expression>| {
        purity.get(e.index()).copied().unwrap_or(Purity::Varying)
    };
    let mut branches = false;
    let mut calls = Vec::new();
    super::walk::for_each_statement(&function.body, &mut |s| match s {
        naga::Statement::If { condition, .. } if of(*condition) == Purity::Uniform => {
            branches = true;
        }
        naga::Statement::Switch { selector, .. } if of(*selector) == Purity::Uniform => {
            branches = true;
        }
        naga::Statement::Call {
            function: callee,
            arguments: args,
            ..
        } => calls.push((*callee, args.iter().map(|a| of(*a)).collect::<Vec<_>>())),
        _ => {}
    });
    if branches {
        found.push(name.to_owned());
    }
    for (callee, args) in calls {
        let f = &module.functions[callee];
        let callee_name = f.name.clone().unwrap_or_default();
        visit(module, f, &callee_name, &args, found, depth + 1);
    }
}

/// Each expression's purity (by index), given the function's arguments'.
fn expression_purity(
    module: &naga::Module,
    function: &naga::Function,
    arguments: &[Purity],
) -> Vec<Purity> {
    // A local written only at the top level of the body holds one of the values written to
    // it wherever it is read: its purity is theirs, joined. The arena may list a local's
    // pointer before the values stored, so the purities are computed again with what the
    // locals hold until nothing changes (a chain of locals is no longer than their number).
    let written = top_level_stores(function);
    // Start from the least (constant) and raise: a write reading the local itself reads one of
    // the other values written to it.
    let mut locals: HashMap<naga::Handle<naga::LocalVariable>, Purity> = written
        .iter()
        .map(|(local, _)| (*local, Purity::Constant))
        .collect();
    let mut purity = pass(module, function, arguments, &locals);
    for _ in 0..=2 * written.len() {
        let of = |e: &naga::Handle<naga::Expression>| {
            purity.get(e.index()).copied().unwrap_or(Purity::Varying)
        };
        let known: HashMap<_, _> = written
            .iter()
            .map(|(local, values)| {
                let p = values.iter().map(of).fold(Purity::Constant, Purity::join);
                (*local, p)
            })
            .collect();
        if known == locals {
            break;
        }
        locals = known;
        purity = pass(module, function, arguments, &locals);
    }
    purity
}

/// One pass over `function`'s arena in order (naga lists an expression's operands before it),
/// with the locals' purities as given.
fn pass(
    module: &naga::Module,
    function: &naga::Function,
    arguments: &[Purity],
    locals: &HashMap<naga::Handle<naga::LocalVariable>, Purity>,
) -> Vec<Purity> {
    use naga::Expression as E;
    let mut purity = vec![Purity::Varying; function.expressions.len()];
    for (handle, expression) in function.expressions.iter() {
        let p = |e: &naga::Handle<naga::Expression>| {
            purity.get(e.index()).copied().unwrap_or(Purity::Varying)
        };
        let value = match expression {
            E::Literal(_) | E::Constant(_) | E::Override(_) | E::ZeroValue(_) => Purity::Constant,
            E::GlobalVariable(g) => {
                if module.global_variables[*g].space == naga::AddressSpace::Uniform {
                    Purity::Uniform
                } else {
                    Purity::Varying
                }
            }
            E::FunctionArgument(i) => arguments
                .get(*i as usize)
                .copied()
                .unwrap_or(Purity::Varying),
            E::LocalVariable(l) => locals.get(l).copied().unwrap_or(Purity::Varying),
            // An index that is not a constant is not a fixed place in the buffer.
            E::Access { base, index } => match p(index) {
                Purity::Constant => p(base),
                _ => Purity::Varying,
            },
            other => super::walk::value_operands(other).map_or(Purity::Varying, |operands| {
                operands.iter().map(p).fold(Purity::Constant, Purity::join)
            }),
        };
        purity[handle.index()] = value;
    }
    purity
}

/// The locals of `function` written only at the top level of its body (by their initialiser
/// and stores not inside a branch or a loop), with every value written to them: straight-line
/// writes the driver sees as plain values, where a write inside a branch or a loop would meet
/// the others in a phi.
fn top_level_stores(
    function: &naga::Function,
) -> Vec<(
    naga::Handle<naga::LocalVariable>,
    Vec<naga::Handle<naga::Expression>>,
)> {
    let mut all: HashMap<naga::Handle<naga::LocalVariable>, usize> = HashMap::new();
    super::walk::for_each_statement(&function.body, &mut |s| {
        if let naga::Statement::Store { pointer, .. } = s
            && let Some(local) = super::loops::root_local(function, *pointer)
        {
            *all.entry(local).or_default() += 1;
        }
    });
    let mut top: HashMap<naga::Handle<naga::LocalVariable>, Vec<naga::Handle<naga::Expression>>> =
        HashMap::new();
    for statement in function.body.iter() {
        if let naga::Statement::Store { pointer, value } = statement
            && let Some(local) = super::loops::root_local(function, *pointer)
        {
            top.entry(local).or_default().push(*value);
        }
    }
    let mut written = Vec::new();
    for (handle, local) in function.local_variables.iter() {
        let values = top.remove(&handle).unwrap_or_default();
        if values.len() != all.get(&handle).copied().unwrap_or(0) {
            continue;
        }
        written.push((handle, local.init.into_iter().chain(values).collect()));
    }
    written
}

#[cfg(test)]
mod tests {
    use super::*;

    fn branches_of(wgsl: &str) -> Vec<String> {
        let module = naga::front::wgsl::parse_str(wgsl).expect("test WGSL parses");
        uniform_branches(&module)
            .into_iter()
            .map(|b| format!("{}/{}", b.entry, b.function))
            .collect()
    }

    const HEADER: &str = "
        struct P { n: u32, f: vec4<f32> }
        @group(0) @binding(0) var<uniform> p: P;
        @group(0) @binding(1) var<storage, read_write> out: array<u32>;
        override N: u32 = 4u;
    ";

    fn compute(body: &str) -> String {
        format!(
            "{HEADER} @compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{ {body} }}"
        )
    }

    #[test]
    fn a_branch_on_uniforms_and_constants_is_found() {
        let cases = [
            "if (p.n == 1u) { out[0] = 1u; }",
            "let k = p.f.z * 2.0 + f32(N); if (k <= 0.0) { out[0] = 1u; }",
            "var k = p.n; if (min(k, 3u) > 1u) { out[0] = 1u; }",
            "if (p.n == 1u) { out[0] = 1u; } else if (p.n == 2u) { out[0] = 2u; }",
            "switch (p.n) { case 0u: { out[0] = 1u; } default: {} }",
            "if (id.x > 0u) { if (select(0u, 1u, p.f.x > 0.5) == 1u) { out[0] = 1u; } }",
            // A local written twice in straight-line code holds uniform values throughout.
            "var l = p.f.xyz; l = select(vec3(1.0), l / 2.0, p.f.w > 0.0); if (l.y < 1e-6 || l.x > 0.0) { out[0] = 1u; }",
        ];
        for body in cases {
            assert_eq!(branches_of(&compute(body)), ["main/main"], "{body}");
        }
    }

    #[test]
    fn branches_on_inputs_storage_constants_or_merged_values_pass() {
        let cases = [
            "if (id.x == p.n) { out[0] = 1u; }",
            "if (out[0] > p.n) { out[1] = 1u; }",
            "if (N > 2u) { out[0] = 1u; }",
            // A select is no branch.
            "out[0] = select(1u, 2u, p.n == 1u);",
            // A value merged from two branches is a phi to the driver.
            "var k = 0u; if (id.x > 0u) { k = p.n; } if (k == 1u) { out[0] = 1u; }",
            // A value carried round a loop is one too.
            "var k = p.n; for (var i = 0u; i < 4u; i++) { k = k + 1u; } if (k == 9u) { out[0] = 1u; }",
            // An index that is not constant is no fixed place in the buffer.
            "let v = array(p.f.x, p.f.y); if (v[id.x] > 0.0) { out[0] = 1u; }",
        ];
        for body in cases {
            assert!(branches_of(&compute(body)).is_empty(), "{body}");
        }
    }

    #[test]
    fn a_helper_is_found_through_its_callers_arguments() {
        let wgsl = format!(
            "{HEADER}
            fn share(x: f32, omega: f32) -> f32 {{
                if (omega <= 0.0) {{ return x; }}
                return x / omega;
            }}
            @compute @workgroup_size(1) fn a(@builtin(global_invocation_id) id: vec3<u32>) {{
                out[0] = u32(share(f32(id.x), p.f.z));
            }}
            @compute @workgroup_size(1) fn b(@builtin(global_invocation_id) id: vec3<u32>) {{
                out[0] = u32(share(f32(id.x), f32(id.y)));
            }}"
        );
        assert_eq!(branches_of(&wgsl), ["a/share"]);
    }
}
