//! The panes laid out in a grid (two columns when more than one): each pane's picture fitted
//! into its cell, its overlay, and the pointer on it (camera drags and scrolls, spawn clicks).

use eframe::{egui, egui_wgpu};
use grassbench::glam::Vec2;

use super::camera::CameraMode;
use super::overlay;
use super::pane::Pane;
use super::spawn::{self, SpawnKind};

/// What happened on the panes.
#[derive(Default)]
pub struct Grid {
    /// Where each pane's picture lies, in points.
    pub pictures: Vec<egui::Rect>,
    /// The camera moved (dragged or scrolled on a pane).
    pub moved: bool,
    /// Clicks with the spawn tool: pane, normalised device coordinates, what to add.
    pub spawns: Vec<(usize, Vec2, SpawnKind)>,
}

/// Draws `panes` over the available area; drags and scrolls move `camera` (over `dt`
/// seconds), clicks add `spawn` unless it is off.
pub fn show(
    ui: &mut egui::Ui,
    render_state: &egui_wgpu::RenderState,
    panes: &mut [Pane],
    camera: &mut CameraMode,
    spawn: SpawnKind,
    dt: f32,
) -> Grid {
    let n = panes.len();
    let cols = if n == 1 { 1 } else { 2 };
    let rows = n.div_ceil(cols);
    let area = ui.available_rect_before_wrap();
    let cell = egui::vec2(area.width() / cols as f32, area.height() / rows as f32);
    let mut grid = Grid::default();
    for (k, pane) in panes.iter_mut().enumerate() {
        let (col, row) = (k % cols, k / cols);
        let rect = egui::Rect::from_min_size(
            area.min + egui::vec2(col as f32 * cell.x, row as f32 * cell.y),
            cell,
        )
        .shrink(4.0);
        // Fit the picture into the cell, keeping its aspect ratio.
        let aspect = pane.full_size.width as f32 / pane.full_size.height as f32;
        let fit = if rect.width() / rect.height() > aspect {
            egui::vec2(rect.height() * aspect, rect.height())
        } else {
            egui::vec2(rect.width(), rect.width() / aspect)
        };
        let pic = egui::Rect::from_center_size(rect.center(), fit);
        grid.pictures.push(pic);
        let response = ui.interact(
            pic,
            ui.scope_id().with(("pane", k)),
            egui::Sense::click_and_drag(),
        );
        if spawn != SpawnKind::Off
            && response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
        {
            grid.spawns.push((k, spawn::ndc(pic, pos), spawn));
        }
        if pane.error.is_none() || pane.technique.is_some() {
            let id = pane.texture(render_state);
            ui.painter().image(
                id,
                pic,
                egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                egui::Color32::WHITE,
            );
        }
        if response.hovered() || response.dragged() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            grid.moved |= ui.input(|i| camera.control(i, response.drag_delta(), scroll, dt));
        }
        overlay::draw(ui, pane, pic, k);
    }
    grid
}
