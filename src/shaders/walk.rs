//! Every statement of a naga block, nested blocks included: what the shader analyses
//! ([`super::ops`], [`super::loops`]) walk to find calls and stores wherever they stand.

/// Calls `f` on every statement of `block` and of the blocks nested in it (the sides of an
/// `if`, a switch's cases, a loop's body and continuing block), a nesting statement before
/// its blocks' statements.
pub(super) fn for_each_statement(block: &naga::Block, f: &mut impl FnMut(&naga::Statement)) {
    use naga::Statement as S;
    for statement in block.iter() {
        f(statement);
        match statement {
            S::Block(b) => for_each_statement(b, f),
            S::If { accept, reject, .. } => {
                for_each_statement(accept, f);
                for_each_statement(reject, f);
            }
            S::Switch { cases, .. } => {
                for c in cases {
                    for_each_statement(&c.body, f);
                }
            }
            S::Loop {
                body, continuing, ..
            } => {
                for_each_statement(body, f);
                for_each_statement(continuing, f);
            }
            _ => {}
        }
    }
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
}
