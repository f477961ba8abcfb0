//! The panes laid out in the grid that gives each the largest picture at its aspect ratio
//! ([`arrange`]), or the wipe view's one picture of two panes; their overlays, and the pointer
//! on them (camera drags and scrolls, spawn clicks).

use eframe::egui;
use grassbench::glam::Vec2;

use super::camera::CameraMode;
use super::display::PaneDisplay;
use super::overlay;
use super::spawn::{self, SpawnKind};
use super::wipe::Wipe;

/// Space between pictures, in points.
const GAP: f32 = 6.0;

/// What happened on the panes.
#[derive(Default)]
pub struct Grid {
    /// Where each pane's picture lies, in points (the wipe view's picture for both of its
    /// panes; `None` for a pane not shown).
    pub pictures: Vec<Option<egui::Rect>>,
    /// The camera moved (dragged or scrolled on a pane).
    pub moved: bool,
    /// Clicks with the spawn tool: pane, normalised device coordinates, what to add.
    pub spawns: Vec<(usize, Vec2, SpawnKind)>,
}

/// What the panes are drawn with.
pub struct Controls<'a> {
    /// The shared camera, moved by drags and scrolls.
    pub camera: &'a mut CameraMode,
    /// What a click adds to the wind.
    pub spawn: SpawnKind,
    /// Seconds since the last window frame.
    pub dt: f32,
    /// The figures over each pane are unfolded.
    pub figures: &'a mut bool,
    /// The wipe view.
    pub wipe: &'a mut Wipe,
}

/// The rectangles of `n` pictures of width / height `aspect` in `area`, `gap` apart: the
/// grid (columns x rows) whose pictures are largest, centred in `area`, in reading order.
pub fn arrange(area: egui::Rect, n: usize, aspect: f32, gap: f32) -> Vec<egui::Rect> {
    if n == 0 || area.width() <= 0.0 || area.height() <= 0.0 {
        return Vec::new();
    }
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        16.0 / 9.0
    };
    // Picture width for `cols` columns: the narrower of what the width and the height allow.
    let width = |cols: usize| {
        let rows = n.div_ceil(cols);
        let by_width = (area.width() - gap * (cols - 1) as f32) / cols as f32;
        let by_height = (area.height() - gap * (rows - 1) as f32) / rows as f32 * aspect;
        by_width.min(by_height).max(1.0)
    };
    let cols = (1..=n)
        .max_by(|&a, &b| width(a).total_cmp(&width(b)))
        .unwrap_or(1);
    let rows = n.div_ceil(cols);
    let size = egui::vec2(width(cols), width(cols) / aspect);
    let block = egui::vec2(
        size.x * cols as f32 + gap * (cols - 1) as f32,
        size.y * rows as f32 + gap * (rows - 1) as f32,
    );
    let origin = area.center() - block / 2.0;
    (0..n)
        .map(|k| {
            let (col, row) = (k % cols, k / cols);
            // A last row with fewer pictures is centred too.
            let in_row = (n - row * cols).min(cols);
            let indent = (cols - in_row) as f32 * (size.x + gap) / 2.0;
            let min = origin
                + egui::vec2(
                    indent + col as f32 * (size.x + gap),
                    row as f32 * (size.y + gap),
                );
            egui::Rect::from_min_size(min, size)
        })
        .collect()
}

/// Draws `panes` over the available area (or the wipe view, when on) and acts on the pointer.
pub fn show(ui: &mut egui::Ui, panes: &[PaneDisplay], mut controls: Controls<'_>) -> Grid {
    let area = ui.available_rect_before_wrap();
    let aspect = panes.first().map_or(16.0 / 9.0, |p| {
        p.full_size.width as f32 / p.full_size.height.max(1) as f32
    });
    let mut grid = Grid {
        pictures: vec![None; panes.len()],
        ..Grid::default()
    };
    let wipe = *controls.wipe;
    if wipe.enabled && wipe.a < panes.len() && wipe.b < panes.len() {
        let Some(&pic) = arrange(area, 1, aspect, GAP).first() else {
            return grid;
        };
        let (left, right) = wipe.sides();
        // The pointer first, so the divider (interacted later) takes precedence over it.
        pointer(ui, &mut grid, left, pic, &mut controls);
        let texture = |k: usize| panes.get(k).and_then(|p| p.texture());
        controls.wipe.show(ui, pic, texture(left), texture(right));
        grid.pictures[wipe.a] = Some(pic);
        grid.pictures[wipe.b] = Some(pic);
        let half = |x0: f32, x1: f32| egui::Rect::from_x_y_ranges(x0..=x1, pic.y_range());
        let x = controls.wipe.divider_x(pic);
        overlay::draw(ui, &panes[left], half(pic.min.x, x), left, controls.figures);
        overlay::draw(
            ui,
            &panes[right],
            half(x, pic.max.x),
            right,
            controls.figures,
        );
        return grid;
    }
    for (k, (pane, pic)) in panes
        .iter()
        .zip(arrange(area, panes.len(), aspect, GAP))
        .enumerate()
    {
        grid.pictures[k] = Some(pic);
        pointer(ui, &mut grid, k, pic, &mut controls);
        if let Some(id) = pane.texture() {
            ui.painter().image(
                id,
                pic,
                egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                egui::Color32::WHITE,
            );
        }
        overlay::draw(ui, pane, pic, k, controls.figures);
    }
    grid
}

/// The pointer on pane `k`'s picture `pic`: drags and scrolls move the camera, clicks add the
/// spawn tool's primitive.
fn pointer(ui: &egui::Ui, grid: &mut Grid, k: usize, pic: egui::Rect, controls: &mut Controls<'_>) {
    let response = ui.interact(
        pic,
        ui.scope_id().with(("pane", k)),
        egui::Sense::click_and_drag(),
    );
    if controls.spawn != SpawnKind::Off
        && response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        grid.spawns.push((k, spawn::ndc(pic, pos), controls.spawn));
    }
    if response.hovered() || response.dragged() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        let (drag, dt) = (response.drag_delta(), controls.dt);
        grid.moved |= ui.input(|i| controls.camera.control(i, drag, scroll, dt));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(w: f32, h: f32) -> egui::Rect {
        egui::Rect::from_min_size(egui::pos2(300.0, 0.0), egui::vec2(w, h))
    }

    #[test]
    fn four_wide_panes_fill_a_landscape_window_two_by_two() {
        let rects = arrange(area(980.0, 800.0), 4, 16.0 / 9.0, 0.0);
        assert_eq!(rects.len(), 4);
        // Two columns as wide as the area, rows touching, the block centred vertically.
        assert_eq!(rects[0].width(), 490.0);
        assert_eq!(rects[1].min.x, rects[0].max.x);
        assert_eq!(rects[2].min.y, rects[0].max.y);
        assert!((rects[0].min.y - (800.0 - 2.0 * 490.0 * 9.0 / 16.0) / 2.0).abs() < 1e-3);
    }

    #[test]
    fn two_panes_stack_when_that_gives_larger_pictures() {
        // 980 x 800: side by side each is 490 wide; stacked each is 400 tall = 711 wide.
        let rects = arrange(area(980.0, 800.0), 2, 16.0 / 9.0, 0.0);
        assert!((rects[0].width() - 400.0 * 16.0 / 9.0).abs() < 1e-3);
        assert_eq!(rects[0].min.x, rects[1].min.x);
        // A very wide area puts them side by side.
        let rects = arrange(area(2000.0, 500.0), 2, 16.0 / 9.0, 0.0);
        assert_eq!(rects[0].min.y, rects[1].min.y);
        // Three in two columns: the last row's one picture is centred.
        let rects = arrange(area(1000.0, 600.0), 3, 16.0 / 9.0, 0.0);
        assert!((rects[2].center().x - area(1000.0, 600.0).center().x).abs() < 1e-3);
    }
}
