//! The difference view: two panes compared live with FLIP or an absolute difference.

use eframe::egui;
use grassbench::compare::StepMaps;
use grassbench::metrics;

/// Which difference to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiffMode {
    /// FLIP error map (magma) and mean FLIP.
    Flip,
    /// Absolute RGB difference x4 and mean absolute difference.
    Absolute,
    /// Each pane's change since its previous frame, pane A against pane B as the reference:
    /// spurious change (A changed where B did not: popping, shimmer) in red, missing change
    /// (B changed where A did not: blur, frozen impostors) in cyan, x4
    /// ([`grassbench::compare::StepMaps`]).
    Temporal,
}

/// State of the difference view.
pub struct DiffView {
    /// Shown at all.
    pub enabled: bool,
    /// First pane.
    pub a: usize,
    /// Second pane.
    pub b: usize,
    /// FLIP or absolute.
    pub mode: DiffMode,
    /// The difference image.
    pub texture: Option<egui::TextureHandle>,
    /// Mean FLIP, or mean absolute difference in 0..255, or mean spurious change in units of
    /// the reference pane's change.
    pub mean: Option<f64>,
    /// Temporal mode: mean missing change in units of the reference pane's change.
    pub missing: Option<f64>,
    /// What went wrong last time (e.g. panes of different sizes).
    pub error: Option<String>,
    /// What the shown difference was measured on: panes A and B, mode, and the frames each
    /// had received.
    pub measured: Option<(usize, usize, DiffMode, u64, u64)>,
}

impl Default for DiffView {
    fn default() -> Self {
        Self {
            enabled: false,
            a: 0,
            b: 1,
            mode: DiffMode::Flip,
            texture: None,
            mean: None,
            missing: None,
            error: None,
            measured: None,
        }
    }
}

impl DiffView {
    /// Recomputes the temporal difference: pane A's step `a` = (previous, last) against pane
    /// B's step `b`.
    pub fn update_temporal(
        &mut self,
        ctx: &egui::Context,
        a: (&image::RgbaImage, &image::RgbaImage),
        b: (&image::RgbaImage, &image::RgbaImage),
    ) {
        match StepMaps::of(a, b) {
            Ok(maps) => {
                let (spurious, missing) = maps.means();
                self.show(ctx, &maps.image(4.0));
                self.mean = Some(spurious);
                self.missing = Some(missing);
                self.error = None;
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Uploads `img` as the difference texture.
    fn show(&mut self, ctx: &egui::Context, img: &image::RgbaImage) {
        let color = egui::ColorImage::from_rgba_unmultiplied(
            [img.width() as usize, img.height() as usize],
            img.as_raw(),
        );
        match &mut self.texture {
            Some(t) => t.set(color, egui::TextureOptions::LINEAR),
            None => {
                self.texture =
                    Some(ctx.load_texture("difference", color, egui::TextureOptions::LINEAR))
            }
        }
    }

    /// Recomputes the difference of two images (FLIP or absolute mode).
    pub fn update(&mut self, ctx: &egui::Context, a: &image::RgbaImage, b: &image::RgbaImage) {
        let result = match self.mode {
            DiffMode::Temporal => return,
            DiffMode::Flip => metrics::flip(a, b).map(|f| (f.heatmap, f64::from(f.mean))),
            DiffMode::Absolute => metrics::abs_diff_image(a, b, 4.0).map(|d| {
                let sum: f64 = d
                    .pixels()
                    .map(|p| f64::from(p.0[0]) + f64::from(p.0[1]) + f64::from(p.0[2]))
                    .sum();
                let mean = sum / (3.0 * 4.0 * f64::from(d.width() * d.height()).max(1.0));
                (d, mean)
            }),
        };
        match result {
            Ok((img, mean)) => {
                self.show(ctx, &img);
                self.mean = Some(mean);
                self.missing = None;
                self.error = None;
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }
}
