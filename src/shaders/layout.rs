//! Struct layouts as WGSL sees them, so every Rust mirror of a uniform or storage struct can be
//! checked against its shader in the crate that owns both, without a GPU.

use crate::{Error, Result};

/// Size in bytes of the WGSL struct `name` in a technique's `source` (composed with the
/// prelude, as [`super::module`] composes it), laid out the way naga lays it out for the GPU.
/// Errors name the struct or the parse error.
pub fn struct_size(source: &str, name: &str) -> Result<u32> {
    let composed = super::compose(source);
    let invalid = |message: String| Error::InvalidFile {
        path: format!("WGSL source of struct `{name}`").into(),
        message,
    };
    let module = naga::front::wgsl::parse_str(&composed)
        .map_err(|e| invalid(e.emit_to_string(&composed)))?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|e| invalid(format!("no layout: {e}")))?;
    module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .map(|(handle, _)| layouter[handle].size)
        .ok_or_else(|| invalid(format!("no struct named `{name}`")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_follow_wgsl_alignment() {
        let src = "struct A { a: f32, b: vec3<f32> }\nstruct B { m: mat4x4<f32>, c: u32 }";
        // vec3 aligns to 16: a at 0, b at 16, size rounded to 32.
        assert_eq!(struct_size(src, "A").unwrap(), 32);
        assert_eq!(struct_size(src, "B").unwrap(), 80);
        assert!(
            struct_size(src, "C")
                .unwrap_err()
                .to_string()
                .contains("`C`")
        );
        assert!(struct_size("struct", "A").is_err());
    }
}
