//! The wipe view: one picture showing two panes' techniques side by side, split by a vertical
//! divider dragged with the mouse; a key ([`FLIP_KEY`]) swaps which technique is on which
//! side, so the same pixels flip between the two (the strongest way to see a difference).

use eframe::egui;

/// The key that swaps the two sides.
pub const FLIP_KEY: egui::Key = egui::Key::F;

/// Half-width of the divider's grip, in points.
const GRIP: f32 = 6.0;

/// State of the wipe view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wipe {
    /// Shown instead of the grid.
    pub enabled: bool,
    /// The pane shown left of the divider (right of it when flipped).
    pub a: usize,
    /// The pane shown right of the divider (left of it when flipped).
    pub b: usize,
    /// The divider's position across the picture, 0 (left edge) to 1 (right edge).
    pub split: f32,
    /// The two sides swapped.
    pub flipped: bool,
}

impl Default for Wipe {
    fn default() -> Self {
        Self {
            enabled: false,
            a: 0,
            b: 1,
            split: 0.5,
            flipped: false,
        }
    }
}

impl Wipe {
    /// The panes shown left and right of the divider.
    pub fn sides(&self) -> (usize, usize) {
        if self.flipped {
            (self.b, self.a)
        } else {
            (self.a, self.b)
        }
    }

    /// The divider's x in `pic`.
    pub fn divider_x(&self, pic: egui::Rect) -> f32 {
        pic.min.x + self.split * pic.width()
    }

    /// Draws the two textures in `pic` split at the divider, and the divider; dragging the
    /// divider moves it. Returns whether it was dragged.
    pub fn show(
        &mut self,
        ui: &egui::Ui,
        pic: egui::Rect,
        left: Option<egui::TextureId>,
        right: Option<egui::TextureId>,
    ) -> bool {
        let x = self.divider_x(pic);
        let painter = ui.painter_at(pic);
        let halves = [
            (left, pic.min.x, x, 0.0, self.split),
            (right, x, pic.max.x, self.split, 1.0),
        ];
        for (texture, x0, x1, u0, u1) in halves {
            if let Some(id) = texture
                && x1 > x0
            {
                painter.image(
                    id,
                    egui::Rect::from_x_y_ranges(x0..=x1, pic.y_range()),
                    egui::Rect::from_x_y_ranges(u0..=u1, 0.0..=1.0),
                    egui::Color32::WHITE,
                );
            }
        }
        let grip = egui::Rect::from_x_y_ranges(x - GRIP..=x + GRIP, pic.y_range());
        let response = ui
            .interact(
                grip,
                ui.scope_id().with("wipe divider"),
                egui::Sense::drag(),
            )
            .on_hover_cursor(egui::CursorIcon::ResizeHorizontal);
        let dragged = response.dragged();
        if dragged && let Some(pos) = response.interact_pointer_pos() {
            self.split = ((pos.x - pic.min.x) / pic.width()).clamp(0.0, 1.0);
        }
        let x = self.divider_x(pic);
        let colour = if dragged || response.hovered() {
            egui::Color32::YELLOW
        } else {
            egui::Color32::WHITE
        };
        painter.line_segment(
            [egui::pos2(x, pic.min.y), egui::pos2(x, pic.max.y)],
            egui::Stroke::new(2.0, colour),
        );
        painter.circle_filled(egui::pos2(x, pic.center().y), GRIP, colour);
        dragged
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flipping_swaps_the_sides() {
        let mut wipe = Wipe {
            a: 2,
            b: 0,
            ..Wipe::default()
        };
        assert_eq!(wipe.sides(), (2, 0));
        wipe.flipped = true;
        assert_eq!(wipe.sides(), (0, 2));
        let pic = egui::Rect::from_min_size(egui::pos2(100.0, 0.0), egui::vec2(400.0, 225.0));
        wipe.split = 0.25;
        assert_eq!(wipe.divider_x(pic), 200.0);
    }
}
