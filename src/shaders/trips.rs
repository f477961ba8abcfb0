//! How many times a loop runs its body, where that is known when its pipeline is made: a
//! counter that starts at a constant, steps by a constant and is tested against a constant or
//! a pipeline-overridable constant (WGSL `override`, whose value the pipeline's creator
//! passes: [`super::PipelineSpec::constants`]). `for (var k = 0u; k < SHELLS; k++)` runs
//! `SHELLS` times; the op counter ([`super::ops`]) counts its body that many times.
//!
//! A loop whose trips depend on the data (a bound read from a buffer or an input, a binary
//! search's `while`, a counter stored to anywhere else) has no count here and is counted as
//! one trip: a lower bound. An early `break` or `return` inside a counted loop is not
//! followed, so there the count is an upper bound; a SIMD rasteriser runs the loop until
//! every invocation of a batch has left it, so the upper bound is what it pays for a batch
//! whose invocations leave at different trips.

use std::collections::HashMap;

/// Most trips counted: a loop that would run longer is counted as unknown (one trip).
const MAX_TRIPS: u64 = 1 << 16;

/// Deepest expression followed to a constant (operands precede their expression in naga's
/// arenas, so this only bounds a malformed IR).
const MAX_DEPTH: u32 = 64;

/// The loops of one function whose trips its module and the pipeline's constants fix.
pub(super) struct Trips<'a> {
    module: &'a naga::Module,
    function: &'a naga::Function,
    constants: &'a [(&'a str, f64)],
    /// Stores into each local variable anywhere in the function: the value stored, and
    /// whether the store is to the whole variable (not to a part of it).
    stores: HashMap<naga::Handle<naga::LocalVariable>, Vec<(naga::Handle<naga::Expression>, bool)>>,
}

impl<'a> Trips<'a> {
    /// The loops of `function` of `module`, with the values of the pipeline's overridable
    /// constants by name (or by their `@id` written as a number, as wgpu takes them too).
    pub(super) fn new(
        module: &'a naga::Module,
        function: &'a naga::Function,
        constants: &'a [(&'a str, f64)],
    ) -> Self {
        let mut stores = HashMap::new();
        super::walk::for_each_statement(&function.body, &mut |s| {
            if let naga::Statement::Store { pointer, value } = *s
                && let Some(local) = super::loops::root_local(function, pointer)
            {
                let whole = function.expressions[pointer] == naga::Expression::LocalVariable(local);
                stores
                    .entry(local)
                    .or_insert_with(Vec::new)
                    .push((value, whole));
            }
        });
        Self {
            module,
            function,
            constants,
            stores,
        }
    }

    /// How many times `statement` runs its body if it is a loop whose trips are known
    /// ([`self`](super::trips)); `None` for any other statement or loop.
    pub(super) fn of(&self, statement: &naga::Statement) -> Option<u64> {
        let naga::Statement::Loop {
            body,
            continuing,
            break_if: None,
        } = statement
        else {
            return None;
        };
        let (condition, runs_while) = exit_test(body)?;
        let naga::Expression::Binary { op, left, right } = self.function.expressions[condition]
        else {
            return None;
        };
        // The counter on the left: `k < n`, or `n > k` turned round.
        let (counter, bound, op) = match (self.counter(left), self.counter(right)) {
            (Some(k), None) => (k, right, op),
            (None, Some(k)) => (k, left, flipped(op)?),
            _ => return None,
        };
        let bound = self.value(&self.function.expressions, bound, 0)?;
        let step = self.step(counter, body, continuing)?;
        let start = self.start(counter, condition, body, continuing)?;
        let local = &self.function.local_variables[counter];
        let (min, max) = range(&self.module.types[local.ty].inner)?;
        let test = |k: i128| {
            let holds = match op {
                naga::BinaryOperator::Less => k < bound,
                naga::BinaryOperator::LessEqual => k <= bound,
                naga::BinaryOperator::Greater => k > bound,
                naga::BinaryOperator::GreaterEqual => k >= bound,
                naga::BinaryOperator::NotEqual => k != bound,
                _ => return None,
            };
            Some(holds == runs_while)
        };
        let mut k = start;
        for trips in 0..=MAX_TRIPS {
            if !test(k)? {
                return Some(trips);
            }
            k += step;
            if k < min || k > max {
                // The counter wraps (or overflows) before the loop ends.
                return None;
            }
        }
        None
    }

    /// The local variable `e` loads, if it is a load of a whole one.
    fn counter(
        &self,
        e: naga::Handle<naga::Expression>,
    ) -> Option<naga::Handle<naga::LocalVariable>> {
        let naga::Expression::Load { pointer } = self.function.expressions[e] else {
            return None;
        };
        match self.function.expressions[pointer] {
            naga::Expression::LocalVariable(local) => Some(local),
            _ => None,
        }
    }

    /// The constant `counter` holds when the loop (its exit test `condition`, its `body` and
    /// `continuing` block) starts, where the loop stores to it once (its step) and nothing
    /// else does but, for a variable declared without a value, one constant store written
    /// before the loop (what `for (var k = 0u; ...)` nested in another loop becomes: the
    /// variable set again each time the outer loop runs).
    fn start(
        &self,
        counter: naga::Handle<naga::LocalVariable>,
        condition: naga::Handle<naga::Expression>,
        body: &naga::Block,
        continuing: &naga::Block,
    ) -> Option<i128> {
        let mut inside = 0;
        for block in [body, continuing] {
            super::walk::for_each_statement(block, &mut |s| {
                if let naga::Statement::Store { pointer, .. } = *s
                    && super::loops::root_local(self.function, pointer) == Some(counter)
                {
                    inside += 1;
                }
            });
        }
        let stores = self.stores.get(&counter).map_or(&[][..], Vec::as_slice);
        let e = &self.function.expressions;
        match (inside, self.function.local_variables[counter].init, stores) {
            (1, Some(init), [_]) => self.value(e, init, 0),
            (1, None, [_]) => Some(0),
            // The arena lists expressions in the order they are written: a value stored
            // before the loop precedes its exit test.
            (1, None, [_, _]) => stores
                .iter()
                .find(|&&(value, whole)| whole && value < condition)
                .and_then(|&(value, _)| self.value(e, value, 0)),
            _ => None,
        }
    }

    /// The constant `counter` steps by each trip: its one store, `k = k ± c` (what `k++`,
    /// `k += c` and `k -= c` become), standing in the loop's body or continuing block
    /// outside any branch.
    fn step(
        &self,
        counter: naga::Handle<naga::LocalVariable>,
        body: &naga::Block,
        continuing: &naga::Block,
    ) -> Option<i128> {
        let mut found = None;
        for_each_unconditional(body, &mut |s| found = found.or(self.step_of(counter, s)));
        for_each_unconditional(continuing, &mut |s| {
            found = found.or(self.step_of(counter, s))
        });
        found.filter(|&c| c != 0)
    }

    /// The step of `statement` if it is the store `counter = counter ± c`.
    fn step_of(
        &self,
        counter: naga::Handle<naga::LocalVariable>,
        statement: &naga::Statement,
    ) -> Option<i128> {
        let naga::Statement::Store { pointer, value } = *statement else {
            return None;
        };
        let e = &self.function.expressions;
        if e[pointer] != naga::Expression::LocalVariable(counter) {
            return None;
        }
        let naga::Expression::Binary { op, left, right } = e[value] else {
            return None;
        };
        let is_counter = |h| self.counter(h) == Some(counter);
        match op {
            naga::BinaryOperator::Add if is_counter(left) => self.value(e, right, 0),
            naga::BinaryOperator::Add if is_counter(right) => self.value(e, left, 0),
            naga::BinaryOperator::Subtract if is_counter(left) => {
                self.value(e, right, 0).map(|c| -c)
            }
            _ => None,
        }
    }

    /// The integer value of expression `h` of `arena` (the function's, or the module's
    /// global expressions for constants and overrides), where it is a constant: literals,
    /// `const`s, `override`s (the pipeline's value, else their default) and arithmetic on
    /// them.
    fn value(
        &self,
        arena: &naga::Arena<naga::Expression>,
        h: naga::Handle<naga::Expression>,
        depth: u32,
    ) -> Option<i128> {
        use naga::Expression as E;
        if depth > MAX_DEPTH {
            return None;
        }
        let global = &self.module.global_expressions;
        match arena[h] {
            E::Literal(l) => literal(l),
            E::ZeroValue(_) => Some(0),
            E::Constant(c) => self.value(global, self.module.constants[c].init, depth + 1),
            E::Override(o) => {
                let o = &self.module.overrides[o];
                let named = |key: &str| {
                    o.name.as_deref() == Some(key) || o.id.is_some_and(|id| id.to_string() == key)
                };
                match self.constants.iter().find(|(key, _)| named(key)) {
                    Some(&(_, v)) if v.fract() == 0.0 && v.abs() < 1e15 => Some(v as i128),
                    Some(_) => None,
                    None => self.value(global, o.init?, depth + 1),
                }
            }
            E::As {
                expr,
                kind: naga::ScalarKind::Uint | naga::ScalarKind::Sint,
                ..
            } => self.value(arena, expr, depth + 1),
            E::Binary { op, left, right } => {
                let a = self.value(arena, left, depth + 1)?;
                let b = self.value(arena, right, depth + 1)?;
                match op {
                    naga::BinaryOperator::Add => a.checked_add(b),
                    naga::BinaryOperator::Subtract => a.checked_sub(b),
                    naga::BinaryOperator::Multiply => a.checked_mul(b),
                    naga::BinaryOperator::Divide => a.checked_div(b),
                    naga::BinaryOperator::Modulo => a.checked_rem(b),
                    _ => None,
                }
            }
            _ => None,
        }
    }
}

/// The condition of a loop's exit test and whether the loop goes on while it holds: the first
/// statement of its body (after the expressions it emits) is `if c {} else { break; }` (what
/// `for` and `while` become: goes on while `c`) or `if c { break; }` (goes on while not `c`).
fn exit_test(body: &naga::Block) -> Option<(naga::Handle<naga::Expression>, bool)> {
    let first = body
        .iter()
        .find(|s| !matches!(s, naga::Statement::Emit(_)))?;
    let naga::Statement::If {
        condition,
        accept,
        reject,
    } = first
    else {
        return None;
    };
    let is_break = |b: &naga::Block| matches!(b.iter().as_slice(), [naga::Statement::Break]);
    if accept.is_empty() && is_break(reject) {
        Some((*condition, true))
    } else if is_break(accept) && reject.is_empty() {
        Some((*condition, false))
    } else {
        None
    }
}

/// Calls `f` on the statements of `block` that run every time it runs: its own and those of
/// plain nested blocks, not those behind a branch or in a nested loop.
fn for_each_unconditional(block: &naga::Block, f: &mut impl FnMut(&naga::Statement)) {
    for statement in block.iter() {
        match statement {
            naga::Statement::Block(b) => for_each_unconditional(b, f),
            s => f(s),
        }
    }
}

/// The comparison `op` with its operands swapped (`n > k` is `k < n`).
fn flipped(op: naga::BinaryOperator) -> Option<naga::BinaryOperator> {
    use naga::BinaryOperator as B;
    Some(match op {
        B::Less => B::Greater,
        B::LessEqual => B::GreaterEqual,
        B::Greater => B::Less,
        B::GreaterEqual => B::LessEqual,
        B::NotEqual => B::NotEqual,
        _ => return None,
    })
}

/// An integer literal's value.
fn literal(l: naga::Literal) -> Option<i128> {
    use naga::Literal as L;
    match l {
        L::U16(v) => Some(v.into()),
        L::I16(v) => Some(v.into()),
        L::U32(v) => Some(v.into()),
        L::I32(v) => Some(v.into()),
        L::U64(v) => Some(v.into()),
        L::I64(v) | L::AbstractInt(v) => Some(v.into()),
        _ => None,
    }
}

/// The values an integer counter of type `ty` can hold.
fn range(ty: &naga::TypeInner) -> Option<(i128, i128)> {
    let naga::TypeInner::Scalar(scalar) = ty else {
        return None;
    };
    let bits = u32::from(scalar.width) * 8;
    match scalar.kind {
        naga::ScalarKind::Uint => Some((0, (1i128 << bits) - 1)),
        naga::ScalarKind::Sint => Some((-(1i128 << (bits - 1)), (1i128 << (bits - 1)) - 1)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The trips of every loop of `body` (in a compute entry point with an override `N`
    /// defaulting to 4 and `M` without a default), in the order they stand, `constants`
    /// passed as the pipeline's.
    fn trips_in(body: &str, constants: &[(&str, f64)]) -> Vec<Option<u64>> {
        let wgsl = format!(
            "override N: u32 = 4u;
             @id(7) override M: u32;
             const C: i32 = 3;
             @group(0) @binding(0) var<storage, read_write> out: array<u32>;
             @compute @workgroup_size(1)
             fn main(@builtin(global_invocation_id) id: vec3<u32>) {{ {body} }}"
        );
        let module = naga::front::wgsl::parse_str(&wgsl).expect("test WGSL parses");
        let function = &module.entry_points[0].function;
        let trips = Trips::new(&module, function, constants);
        let mut found = Vec::new();
        super::super::walk::for_each_statement(&function.body, &mut |s| {
            if matches!(s, naga::Statement::Loop { .. }) {
                found.push(trips.of(s));
            }
        });
        found
    }

    #[test]
    fn loops_bounded_by_constants_and_overrides_count_their_trips() {
        // Each loop's body, the pipeline's constants, the trips.
        type Case<'a> = (&'a str, &'a [(&'a str, f64)], u64);
        let cases: [Case<'_>; 12] = [
            ("for (var k = 0u; k < 8u; k++) { out[k] = k; }", &[], 8),
            ("for (var k = 0u; k <= 8u; k++) { out[k] = k; }", &[], 9),
            ("for (var k = 1u; k < 8u; k += 2u) { out[k] = k; }", &[], 4),
            (
                "for (var k = 0; k < C * 2 + 1; k++) { out[k] = 1u; }",
                &[],
                7,
            ),
            ("for (var k = 10; k > 0; k -= 3) { out[k] = 1u; }", &[], 4),
            ("for (var k = 0u; 5u > k; k++) { out[k] = k; }", &[], 5),
            ("for (var k = 0u; k != 6u; k++) { out[k] = k; }", &[], 6),
            // An override: its default, or the pipeline's value (by name or by `@id`).
            ("for (var k = 0u; k < N; k++) { out[k] = k; }", &[], 4),
            (
                "let n = N; for (var k = 0u; k < n; k++) { out[k] = k; }",
                &[("N", 16.0)],
                16,
            ),
            (
                "for (var k = 0u; k < M + 1u; k++) { out[k] = k; }",
                &[("7", 2.0)],
                3,
            ),
            // `while` with its step in the body; `loop` with its own exit test.
            (
                "var k = 2u; while (k < 8u) { out[k] = k; k += 2u; }",
                &[],
                3,
            ),
            (
                "var k = 0u; loop { if (k >= 3u) { break; } out[k] = k; continuing { k++; } }",
                &[],
                3,
            ),
        ];
        for (body, constants, expected) in cases {
            assert_eq!(trips_in(body, constants), [Some(expected)], "{body}");
        }
        // Nested loops each count their own.
        assert_eq!(
            trips_in(
                "for (var i = 0u; i < 3u; i++) { for (var j = 0u; j < N; j++) { out[i + j] = j; } }",
                &[]
            ),
            [Some(3), Some(4)]
        );
    }

    #[test]
    fn loops_whose_trips_depend_on_data_are_not_counted() {
        let cases = [
            // Bounds from a buffer, an input, an override without a value.
            "for (var k = 0u; k < out[0]; k++) { out[k + 1u] = k; }",
            "for (var k = 0u; k < id.x; k++) { out[k] = k; }",
            "for (var k = 0u; k < M; k++) { out[k] = k; }",
            // A start that is not constant; a counter stored to in a branch too.
            "var k = id.x; for (; k < 8u; k++) { out[k] = k; }",
            "for (var k = 0u; k < 8u; k++) { if (out[k] > 0u) { k += 1u; } }",
            // A step behind a branch; a step that is not constant.
            "var k = 0u; while (k < 8u) { if (out[k] > 0u) { k++; } }",
            "for (var k = 1u; k < 8u; k *= 2u) { out[k] = k; }",
            // A binary search; a test that is not the loop's first statement.
            "var lo = 0u; var hi = 64u; while (hi - lo > 1u) { let m = (lo + hi) / 2u; if (out[m] > 5u) { hi = m; } else { lo = m; } }",
            "var k = 0u; loop { out[k] = k; if (k >= 3u) { break; } continuing { k++; } }",
            // An unsigned counter that wraps before its test fails; one that never ends.
            "for (var k = 3u; k >= 0u; k--) { out[k] = k; }",
            "for (var k = 0u; k != 7u; k += 2u) { out[k] = k; }",
        ];
        for body in cases {
            assert_eq!(trips_in(body, &[]), [None], "{body}");
        }
    }
}
