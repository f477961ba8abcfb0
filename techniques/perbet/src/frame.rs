//! What one frame draws: the visible patches, far to near (Sec. 2.2: "the scene is rendered
//! from back to front ... we just need to process the prairie in the right order"), each in one
//! representation or, during a transition (Sec. 4), in two at once with the transition's
//! morph, fade and growth.

use crate::lod::{Level, PatchLod};

/// Bit 0 of [`Entry::flags`]: strips are planes of constant x (else of constant z).
pub const FLAG_ORIENTATION: u32 = 1;
/// Bit 1 of [`Entry::flags`]: draw the strips from the last to the first (far to near).
pub const FLAG_REVERSED: u32 = 2;

/// One drawn patch in one representation (the shader's `Entry`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Entry {
    /// World xz of the patch's corner.
    pub origin: [f32; 2],
    /// Which pre-computed patch (2D: its first patch's; its fragments look up their own).
    pub variant: u32,
    /// [`FLAG_ORIENTATION`], [`FLAG_REVERSED`].
    pub flags: u32,
    /// Opacity of this representation.
    pub opacity: f32,
    /// 3D blades: 0 at their own shape, 1 at their painted target on the strips.
    pub morph: f32,
    /// Strips: 1 standing, 0 sunk into the ground.
    pub grow: f32,
    /// 3D blades in a morph: index of the same patch's strips entry. 2D: the patches the
    /// surface spans, along x (low 16 bits) and z (high 16 bits) ([`extent`]).
    pub link: u32,
}

/// [`Entry::link`] of a 2D entry spanning `x` by `z` patches (each below 65 536).
pub fn extent(x: u32, z: u32) -> u32 {
    (x & 0xffff) | (z << 16)
}

/// How a patch is drawn this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Representation {
    /// 3D blades: opacity and morph.
    pub geometry: Option<(f32, f32)>,
    /// Strips: opacity and growth.
    pub strips: Option<(f32, f32)>,
    /// 2D texture: opacity.
    pub flat: Option<f32>,
}

/// The representations of a patch in `state`, for transitions of `steps` frames whose last
/// `fade` fraction cross-fades 3D blades and strips.
///
/// - 3D ↔ 2.5D (Sec. 4.2): with `m` the progress towards the strips, each 3D blade is drawn at
///   `m` of the way to its painted copy, both levels animated; over the last `fade` of the way
///   the blades fade out and the strips in ("an additional fade in - fade out").
/// - 2.5D ↔ 2D (Sec. 4.3): with `g` the progress towards 2D, eased by a smoothstep, the strips
///   are sunk by `g` of their height into the ground while the 2D texture fades in with
///   opacity `g`.
///
/// Going the other way runs the same functions backwards, so a reversed transition is
/// continuous.
pub fn representation(state: PatchLod, steps: u32, fade: f32) -> Representation {
    let p = state.progress(steps);
    let crossfade = |m: f32| {
        if fade <= 0.0 {
            if m >= 1.0 { 1.0 } else { 0.0 }
        } else {
            ((m - (1.0 - fade)) / fade).clamp(0.0, 1.0)
        }
    };
    let geometry_strips = |m: f32| Representation {
        geometry: Some((1.0 - crossfade(m), m)),
        strips: Some((crossfade(m), 1.0)),
        flat: None,
    };
    // Growth eases in and out (smoothstep): the paper does not say how strips grow, and a
    // linear growth would leave the last step visibly short of standing.
    let strips_flat = |g: f32| {
        let g = g * g * (3.0 - 2.0 * g);
        Representation {
            geometry: None,
            strips: Some((1.0, 1.0 - g)),
            flat: Some(g),
        }
    };
    match (state.level, state.transition.map(|t| t.to)) {
        (Level::Geometry, Some(Level::Strips)) => geometry_strips(p),
        (Level::Strips, Some(Level::Geometry)) => geometry_strips(1.0 - p),
        (Level::Strips, Some(Level::Flat)) => strips_flat(p),
        (Level::Flat, Some(Level::Strips)) => strips_flat(1.0 - p),
        (Level::Geometry, _) => Representation {
            geometry: Some((1.0, 0.0)),
            ..Default::default()
        },
        (Level::Strips, _) => Representation {
            strips: Some((1.0, 1.0)),
            ..Default::default()
        },
        (Level::Flat, _) => Representation {
            flat: Some(1.0),
            ..Default::default()
        },
    }
}

/// The entries of one frame, in draw order within each representation (far to near).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lists {
    /// 3D blade entries.
    pub geometry: Vec<Entry>,
    /// Strip entries.
    pub strips: Vec<Entry>,
    /// 2D entries.
    pub flat: Vec<Entry>,
}

impl Lists {
    /// Empties the lists (keeping their memory).
    pub fn clear(&mut self) {
        self.geometry.clear();
        self.strips.clear();
        self.flat.clear();
    }

    /// Adds a patch (call far to near) drawn as `r`; `base` carries its origin, variant and
    /// flags.
    pub fn push(&mut self, base: Entry, r: Representation) {
        let mut link = u32::MAX;
        if let Some((opacity, grow)) = r.strips {
            link = self.strips.len() as u32;
            self.strips.push(Entry {
                opacity,
                grow,
                ..base
            });
        }
        if let Some((opacity, morph)) = r.geometry {
            self.geometry.push(Entry {
                opacity,
                morph: if link == u32::MAX { 0.0 } else { morph },
                link,
                ..base
            });
        }
        if let Some(opacity) = r.flat {
            self.flat.push(Entry {
                opacity,
                link: extent(1, 1),
                ..base
            });
        }
    }

    /// All entries in one array (3D, then strips, then 2D) with geometry links made absolute,
    /// and the indices of the first strips and first 2D entry.
    pub fn concatenate(&self, out: &mut Vec<Entry>) -> [u32; 2] {
        out.clear();
        let strips_base = self.geometry.len() as u32;
        out.extend(self.geometry.iter().map(|e| Entry {
            link: if e.link == u32::MAX {
                0
            } else {
                e.link + strips_base
            },
            ..*e
        }));
        out.extend_from_slice(&self.strips);
        out.extend_from_slice(&self.flat);
        [strips_base, strips_base + self.strips.len() as u32]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lod::Transition;

    fn state(level: Level, to: Option<Level>, step: u32) -> PatchLod {
        PatchLod {
            level,
            transition: to.map(|to| Transition { to, step }),
        }
    }

    #[test]
    fn a_transitions_first_step_looks_like_the_old_level() {
        let r = representation(state(Level::Geometry, Some(Level::Strips), 0), 20, 0.25);
        assert_eq!(r.geometry, Some((1.0, 0.0)));
        assert_eq!(r.strips, Some((0.0, 1.0)));
        let r = representation(state(Level::Strips, Some(Level::Flat), 0), 20, 0.25);
        assert_eq!((r.strips, r.flat), (Some((1.0, 1.0)), Some(0.0)));
        let r = representation(state(Level::Strips, Some(Level::Geometry), 0), 20, 0.25);
        assert_eq!(r.strips, Some((1.0, 1.0)));
        assert_eq!(r.geometry, Some((0.0, 1.0)));
    }

    #[test]
    fn a_transitions_last_step_is_next_to_the_new_level() {
        let r = representation(state(Level::Geometry, Some(Level::Strips), 19), 20, 0.25);
        let (blade_opacity, morph) = r.geometry.unwrap();
        assert!(morph > 0.94 && blade_opacity < 0.21, "{r:?}");
        let r = representation(state(Level::Flat, Some(Level::Strips), 19), 20, 0.25);
        let (_, grow) = r.strips.unwrap();
        assert!(grow > 0.99 && r.flat.unwrap() < 0.01, "{r:?}");
    }

    #[test]
    fn reversing_a_transition_is_continuous() {
        for step in 1..20 {
            let forward =
                representation(state(Level::Geometry, Some(Level::Strips), step), 20, 0.25);
            let back = representation(
                state(Level::Strips, Some(Level::Geometry), 20 - step),
                20,
                0.25,
            );
            let close = |a: Option<(f32, f32)>, b: Option<(f32, f32)>| {
                let (a, b) = (a.unwrap(), b.unwrap());
                (a.0 - b.0).abs() < 1e-5 && (a.1 - b.1).abs() < 1e-5
            };
            assert!(close(forward.geometry, back.geometry) && close(forward.strips, back.strips));
        }
    }

    #[test]
    fn geometry_links_to_the_strips_of_its_patch() {
        let mut lists = Lists::default();
        let a = Entry {
            variant: 1,
            ..Default::default()
        };
        let b = Entry {
            variant: 2,
            ..Default::default()
        };
        lists.push(a, representation(state(Level::Strips, None, 0), 20, 0.25));
        lists.push(
            b,
            representation(state(Level::Geometry, Some(Level::Strips), 5), 20, 0.25),
        );
        let mut all = Vec::new();
        let bases = lists.concatenate(&mut all);
        assert_eq!(bases, [1, 3]);
        assert_eq!(all[0].variant, 2);
        assert_eq!(all[all[0].link as usize].variant, 2);
        assert!(all[0].morph > 0.0);
    }
}
