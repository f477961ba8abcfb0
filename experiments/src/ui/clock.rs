//! The window's clock: the frame every pane shows, played at a time scale. One clock for the
//! one world: panes never run at different frames.

/// Frame position and playback.
pub struct Clock {
    /// Frame position (fractional at time scales other than 1).
    pub frame: f64,
    /// Advancing every window frame.
    pub playing: bool,
    /// Scene frames per window frame.
    pub time_scale: f64,
}

impl Default for Clock {
    fn default() -> Self {
        Self {
            frame: 0.0,
            playing: true,
            time_scale: 1.0,
        }
    }
}

impl Clock {
    /// The scene frame shown.
    pub fn index(&self) -> u64 {
        self.frame.max(0.0) as u64
    }

    /// Advances by the time scale when playing; a script stops at its last frame.
    pub fn tick(&mut self, last: Option<u64>) {
        if self.playing {
            self.frame += self.time_scale;
        }
        if let Some(last) = last
            && self.frame >= last as f64
        {
            self.frame = last as f64;
            self.playing = false;
        }
    }

    /// Pauses and moves to the next whole frame.
    pub fn step(&mut self) {
        self.playing = false;
        self.frame = self.frame.floor() + 1.0;
    }
}
