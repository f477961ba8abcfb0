//! Every statement of a naga block, nested blocks included: what the shader analyses
//! ([`super::ops`], [`super::loops`], [`super::trips`]) walk to find calls and stores wherever
//! they stand, and how many times each runs where a loop's trips are known.

/// Calls `f` on every statement of `block` and of the blocks nested in it (the sides of an
/// `if`, a switch's cases, a loop's body and continuing block), a nesting statement before
/// its blocks' statements.
pub(super) fn for_each_statement(block: &naga::Block, f: &mut impl FnMut(&naga::Statement)) {
    for_each_weighted(block, 1, &|_| None, &mut |s, _| f(s));
}

/// [`for_each_statement`] with how many times each statement runs each time `block` runs
/// `weight` times: a loop's body and continuing block `trips(loop)` times over (once where
/// `trips` does not know, or says none: its exit test still runs), every other nested block as often as the statement holding it
/// (both sides of a branch, every case of a switch).
pub(super) fn for_each_weighted(
    block: &naga::Block,
    weight: u64,
    trips: &impl Fn(&naga::Statement) -> Option<u64>,
    f: &mut impl FnMut(&naga::Statement, u64),
) {
    use naga::Statement as S;
    for statement in block.iter() {
        f(statement, weight);
        match statement {
            S::Block(b) => for_each_weighted(b, weight, trips, f),
            S::If { accept, reject, .. } => {
                for_each_weighted(accept, weight, trips, f);
                for_each_weighted(reject, weight, trips, f);
            }
            S::Switch { cases, .. } => {
                for c in cases {
                    for_each_weighted(&c.body, weight, trips, f);
                }
            }
            S::Loop {
                body, continuing, ..
            } => {
                let inner = weight.saturating_mul(trips(statement).unwrap_or(1).max(1));
                for_each_weighted(body, inner, trips, f);
                for_each_weighted(continuing, inner, trips, f);
            }
            _ => {}
        }
    }
}

/// The operands of an expression whose value is computed from its operands alone (loads,
/// accesses, swizzles, constructors, arithmetic, comparisons, selects, conversions, math
/// functions); `None` for every other kind (globals, locals, arguments, constants, texture
/// reads, call results, ...), whose value each analysis decides for itself. What the shader
/// analyses ([`super::loops`], [`super::branches`]) follow values through.
pub(super) fn value_operands(
    expression: &naga::Expression,
) -> Option<Vec<naga::Handle<naga::Expression>>> {
    use naga::Expression as E;
    Some(match expression {
        E::Load { pointer } => vec![*pointer],
        E::Access { base, index } => vec![*base, *index],
        E::AccessIndex { base, .. } => vec![*base],
        E::Splat { value, .. } => vec![*value],
        E::Swizzle { vector, .. } => vec![*vector],
        E::Compose { components, .. } => components.clone(),
        E::Unary { expr, .. } | E::As { expr, .. } => vec![*expr],
        E::Binary { left, right, .. } => vec![*left, *right],
        E::Select {
            condition,
            accept,
            reject,
        } => vec![*condition, *accept, *reject],
        E::Relational { argument, .. } => vec![*argument],
        E::Math {
            arg,
            arg1,
            arg2,
            arg3,
            ..
        } => std::iter::once(*arg)
            .chain([arg1, arg2, arg3].into_iter().flatten().copied())
            .collect(),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nested_statements_are_visited() {
        let module = naga::front::wgsl::parse_str(
            "@group(0) @binding(0) var<storage, read_write> out: array<u32>;
             @compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
                 if (id.x > 0u) { out[0] = 1u; } else { out[1] = 2u; }
                 for (var k = 0u; k < 4u; k++) { switch (k) { case 0u: { out[2] = k; } default: {} } }
             }",
        )
        .expect("test WGSL parses");
        let mut stores = 0;
        for_each_statement(&module.entry_points[0].function.body, &mut |s| {
            stores += usize::from(matches!(s, naga::Statement::Store { .. }));
        });
        // The two sides of the `if`, the switch's case inside the loop, and the loop's step (a
        // constant initialiser is the variable's `init`, not a store): every one nested.
        assert_eq!(stores, 4);
    }

    #[test]
    fn loops_weigh_their_blocks_by_their_trips() {
        let module = naga::front::wgsl::parse_str(
            "@group(0) @binding(0) var<storage, read_write> out: array<u32>;
             @compute @workgroup_size(1) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
                 out[0] = 1u;
                 for (var i = 0u; i < 3u; i++) {
                     if (id.x > i) { out[1] = i; }
                     for (var j = 0u; j < 2u; j++) { out[2] = j; }
                 }
             }",
        )
        .expect("test WGSL parses");
        // Every loop runs 3 times here: the outer loop's body thrice, the inner's nine.
        let mut weights = Vec::new();
        for_each_weighted(
            &module.entry_points[0].function.body,
            1,
            &|_| Some(3),
            &mut |s, w| {
                if let naga::Statement::Store { value, .. } = s
                    && let naga::Expression::Literal(naga::Literal::U32(1)) =
                        module.entry_points[0].function.expressions[*value]
                {
                    weights.push(("first", w));
                } else if matches!(s, naga::Statement::Store { .. }) {
                    weights.push(("other", w));
                }
            },
        );
        // `out[0]` once; `out[1]` (in a branch) and the outer step thrice; the inner
        // counter's start thrice; `out[2]` and the inner step nine times.
        let mut found: Vec<u64> = weights.iter().map(|&(_, w)| w).collect();
        found.sort_unstable();
        assert_eq!(found, [1, 3, 3, 3, 9, 9]);
        assert_eq!(weights[0], ("first", 1));
    }
}
