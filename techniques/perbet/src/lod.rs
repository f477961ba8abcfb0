//! Levels of detail per patch (Sec. 2.2 and 4.1): a 2D discrete distance to the camera's patch
//! (patches sharing an edge or a corner with it are at distance 1: the Chebyshev distance),
//! ranges per level, different limits going out than coming in (hysteresis), and transitions
//! that last a fixed number of steps between neighbouring levels only.

/// A representation of a patch (Sec. 2.1), finest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Level {
    /// 3D blades as chains of line segments.
    Geometry,
    /// 2.5D: animated vertical polygon strips with semi-transparent textures.
    Strips,
    /// 2D: a texture over the terrain.
    Flat,
}

impl Level {
    /// The neighbouring level one step towards `target` (itself if equal).
    pub fn towards(self, target: Self) -> Self {
        use Level::*;
        match (self, target) {
            (Geometry, Strips | Flat) | (Flat, Geometry) => Strips,
            (Strips, Geometry) => Geometry,
            (Strips, Flat) => Flat,
            (Flat, Strips) => Strips,
            _ => self,
        }
    }
}

/// Which level each discrete distance gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ranges {
    /// First distance drawn as strips (geometry below).
    pub strips_from: u32,
    /// Last distance drawn as strips (2D beyond).
    pub strips_to: u32,
    /// A patch moving away keeps its finer level this many patches past the limit.
    pub hysteresis: u32,
}

impl Ranges {
    /// The level for distance `d` without hysteresis.
    pub fn nominal(&self, d: u32) -> Level {
        if d < self.strips_from {
            Level::Geometry
        } else if d <= self.strips_to {
            Level::Strips
        } else {
            Level::Flat
        }
    }

    /// The level a patch at distance `d` that is now at `current` should go to: finer levels
    /// are taken at the nominal limit, coarser ones only `hysteresis` patches past it (Sec.
    /// 4.1: "slightly different limit values ... for going back and forth").
    pub fn wanted(&self, current: Level, d: u32) -> Level {
        let nominal = self.nominal(d);
        if nominal <= current {
            return nominal;
        }
        let late = self.nominal(d.saturating_sub(self.hysteresis));
        if late > current { late } else { current }
    }
}

/// A transition under way towards a neighbouring level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Transition {
    /// The level being reached (a neighbour of the current one).
    pub to: Level,
    /// Steps done, `0..steps`.
    pub step: u32,
}

/// The state of one patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PatchLod {
    /// Its level (the one it leaves, while in transition).
    pub level: Level,
    /// The transition under way, if any.
    pub transition: Option<Transition>,
}

impl PatchLod {
    /// Progress of the transition in `[0, 1)` (0 without one).
    pub fn progress(&self, steps: u32) -> f32 {
        self.transition
            .map_or(0.0, |t| t.step as f32 / steps.max(1) as f32)
    }

    /// Steps `self` one frame for distance `d`: snaps when `was_visible` is false, else
    /// advances, finishes, reverses or starts a transition (or switches at once when `steps`
    /// is 0).
    fn step(&mut self, ranges: &Ranges, d: u32, was_visible: bool, steps: u32) {
        if !was_visible {
            // A patch coming into view takes its level at once.
            *self = Self {
                level: ranges.nominal(d),
                transition: None,
            };
            return;
        }
        if steps == 0 {
            // No transitions: switch as soon as the level changes.
            *self = Self {
                level: ranges.wanted(self.level, d),
                transition: None,
            };
            return;
        }
        if let Some(t) = self.transition {
            let step = t.step + 1;
            let wanted = ranges.wanted(t.to, d);
            if step >= steps {
                *self = Self {
                    level: t.to,
                    transition: None,
                };
            } else if wanted != t.to && t.to.towards(wanted) == self.level {
                // The camera turned back: run the same transition backwards from where it is.
                *self = Self {
                    level: t.to,
                    transition: Some(Transition {
                        to: self.level,
                        step: steps - step,
                    }),
                };
            } else {
                self.transition = Some(Transition { to: t.to, step });
            }
            return;
        }
        let wanted = ranges.wanted(self.level, d);
        if wanted != self.level {
            self.transition = Some(Transition {
                to: self.level.towards(wanted),
                step: 0,
            });
        }
    }
}

/// The levels of every patch of a terrain.
#[derive(Clone, Debug)]
pub struct LodGrid {
    /// Patches along x and z.
    pub cols: u32,
    /// Patches along z.
    pub rows: u32,
    /// Ranges and hysteresis.
    pub ranges: Ranges,
    /// Frames a transition lasts.
    pub steps: u32,
    states: Vec<PatchLod>,
    visible: Vec<bool>,
}

impl LodGrid {
    /// A grid of `cols x rows` patches, none seen yet.
    pub fn new(cols: u32, rows: u32, ranges: Ranges, steps: u32) -> Self {
        let n = (cols * rows) as usize;
        Self {
            cols,
            rows,
            ranges,
            steps,
            states: vec![
                PatchLod {
                    level: Level::Flat,
                    transition: None,
                };
                n
            ],
            visible: vec![false; n],
        }
    }

    /// Discrete distance between patches `a` and `b` (Chebyshev: a shared edge or corner is 1).
    pub fn distance(a: (i64, i64), b: (i64, i64)) -> u32 {
        (a.0 - b.0)
            .abs()
            .max((a.1 - b.1).abs())
            .min(i64::from(u32::MAX)) as u32
    }

    /// Advances every patch one frame with the camera in patch `camera` (may lie outside the
    /// terrain) and `visible(i)` saying whether patch `i` (row-major) is in view now.
    pub fn update(&mut self, camera: (i64, i64), visible: impl Fn(usize) -> bool) {
        for i in 0..self.states.len() {
            let now = visible(i);
            let patch = ((i as u32 % self.cols) as i64, (i as u32 / self.cols) as i64);
            let d = Self::distance(patch, camera);
            self.states[i].step(&self.ranges, d, self.visible[i] && now, self.steps);
            self.visible[i] = now;
        }
    }

    /// The state of patch `i`.
    pub fn state(&self, i: usize) -> PatchLod {
        self.states.get(i).copied().unwrap_or(PatchLod {
            level: Level::Flat,
            transition: None,
        })
    }

    /// Patches in the grid.
    pub fn len(&self) -> usize {
        self.states.len()
    }

    /// Whether the grid has no patches.
    pub fn is_empty(&self) -> bool {
        self.states.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const RANGES: Ranges = Ranges {
        strips_from: 2,
        strips_to: 12,
        hysteresis: 1,
    };

    #[test]
    fn nominal_levels_follow_the_ranges() {
        let levels: Vec<Level> = (0..15).map(|d| RANGES.nominal(d)).collect();
        assert_eq!(&levels[..2], &[Level::Geometry; 2]);
        assert!(levels[2..=12].iter().all(|l| *l == Level::Strips));
        assert_eq!(&levels[13..], &[Level::Flat; 2]);
    }

    #[test]
    fn hysteresis_delays_only_the_way_out() {
        // In: strips become geometry at distance 1, as without hysteresis.
        assert_eq!(RANGES.wanted(Level::Strips, 1), Level::Geometry);
        // Out: geometry stays geometry at 2, becomes strips at 3.
        assert_eq!(RANGES.wanted(Level::Geometry, 2), Level::Geometry);
        assert_eq!(RANGES.wanted(Level::Geometry, 3), Level::Strips);
        assert_eq!(RANGES.wanted(Level::Strips, 13), Level::Strips);
        assert_eq!(RANGES.wanted(Level::Strips, 14), Level::Flat);
    }

    #[test]
    fn a_camera_pacing_across_a_limit_starts_one_transition_per_patch() {
        // The camera walks back and forth between patches 10 and 11 of a row; patch 12 is at
        // distance 2 or 1: without hysteresis it would flip every time.
        let mut grid = LodGrid::new(40, 1, RANGES, 20);
        let mut starts = vec![0; 40];
        let mut before: Vec<PatchLod> = (0..40).map(|i| grid.state(i)).collect();
        for frame in 0..400 {
            let camera = if (frame / 30) % 2 == 0 { 10 } else { 11 };
            grid.update((camera, 0), |_| true);
            for (i, b) in before.iter_mut().enumerate() {
                let now = grid.state(i);
                if now.transition.is_some_and(|t| t.step == 0) && frame > 0 {
                    starts[i] += 1;
                }
                *b = now;
            }
        }
        assert!(starts.iter().all(|s| *s <= 1), "{starts:?}");
    }

    #[test]
    fn transitions_last_their_steps_and_end_at_the_new_level() {
        let mut grid = LodGrid::new(20, 1, RANGES, 20);
        grid.update((0, 0), |_| true);
        assert_eq!(grid.state(1).level, Level::Geometry);
        // The camera moves away by 4 patches: patch 1 is now at distance 3. The transition is
        // under way for exactly `steps` frames, then the patch is at the new level.
        let mut frames = 0;
        for _ in 0..30 {
            grid.update((4, 0), |_| true);
            frames += u32::from(grid.state(1).transition.is_some());
        }
        assert_eq!(frames, 20);
        assert_eq!(grid.state(1).level, Level::Strips);
        assert_eq!(frames, 20);
    }

    proptest! {
        /// Every patch is at one level, or in transition to a neighbouring level, whatever the
        /// camera does.
        #[test]
        fn patches_are_in_one_level_or_between_neighbours(
            moves in proptest::collection::vec((-3i64..=3, -3i64..=3, any::<bool>()), 1..80),
            steps in 0u32..30,
        ) {
            let mut grid = LodGrid::new(24, 24, RANGES, steps);
            let mut camera = (12i64, 12i64);
            for (dx, dz, seen) in moves {
                camera = (camera.0 + dx, camera.1 + dz);
                grid.update(camera, |i| seen || i % 3 != 0);
                for i in 0..grid.len() {
                    let s = grid.state(i);
                    if let Some(t) = s.transition {
                        prop_assert!(t.to != s.level);
                        prop_assert_eq!(s.level.towards(t.to), t.to);
                        prop_assert!(t.step < steps.max(1));
                    }
                }
            }
        }
    }
}
