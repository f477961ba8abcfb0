//! The prairie as the technique keeps it from frame to frame: where the grass grids lie and
//! what each holds (Sec. 5.1, 5.3), the blades' and flowers' animation (Sec. 3.2-3.4), the
//! billboards with their anchor plants and the anchors' animation (Sec. 4.1-4.2), and, with
//! sorting, what ordering single plants far to near reads (Sec. 5.4). Built once at start-up
//! together with the billboard texture (Fig. 11), whose texels the wings are cut to
//! ([`wing_trim`](crate::wing_trim)).

use grassbench::Scene;
use grassbench::glam::Vec3;

use crate::animate::Animation;
use crate::billboard::Billboards;
use crate::billboard_texture::{self, Look};
use crate::culling::GridIndex;
use crate::order::BlockOrders;
use crate::params::{Params, Sorting};
use crate::prairie::{Layout, Planted};
use crate::shader_data::BladeStatic;
use crate::wing_trim::Skyline;

/// Everything planted and moving that persists between frames.
pub struct Plants {
    /// Where the grass grids lie.
    pub layout: Layout,
    /// The grass grids' blade and flower ranges and bounds (Sec. 5.3), boxes widened for the
    /// anchors.
    pub grids: GridIndex,
    /// The blades' and flowers' animation.
    pub blades: Animation,
    /// Every grid's billboards at every step and their anchor plants (Sec. 4.1-4.2).
    pub billboards: Billboards,
    /// The anchors' animation (only `P3` is drawn).
    pub anchors: Animation,
    /// Each anchor's top point at rest.
    pub anchor_rest: Vec<Vec3>,
    /// Height of the billboard texture (the tallest blade), m.
    pub billboard_height: f32,
    /// What sorting (Sec. 5.4) reads; `None` without sorting.
    pub sorting: Option<SortLookup>,
}

/// What ordering the frame's single plants far to near (Sec. 5.4) reads.
pub struct SortLookup {
    /// The pre-computed billboard orders of the nine sections (Fig. 17).
    pub orders: BlockOrders,
    /// Each blade's static instance data (copied in draw order every frame).
    pub statics: Vec<BladeStatic>,
    /// Each blade's root xyz and height.
    pub plants: Vec<[f32; 4]>,
    /// The blade at each lattice point, `grid·n² + cell` (`u32::MAX` where none grows).
    pub slots: Vec<u32>,
}

/// The billboard texture (Fig. 11) as composed at start-up.
pub struct BillboardTexels {
    /// Texels of every layer, layer after layer.
    pub texels: Vec<[u8; 4]>,
    /// Layers: one per billboard step, at least one.
    pub layers: u32,
}

/// A blade's static instance data.
pub fn blade_static(p: &Planted) -> BladeStatic {
    BladeStatic {
        root_facing: p.root.extend(p.facing).to_array(),
        shape: [p.height, p.width, p.variation, 0.0],
    }
}

impl Plants {
    /// The blades `planted` on `layout` at rest, their billboards (none without level of
    /// detail) with each wing cut to the texels it can show when `trim_wings`, and the
    /// billboard texture.
    pub fn new(
        params: &Params,
        scene: &Scene,
        layout: Layout,
        planted: &[Planted],
    ) -> (Self, BillboardTexels) {
        let grass = &scene.config.grass;
        let seed = scene.config.seed;
        let blades = Animation::new(planted, params.flower_mass);
        // Billboards (Ch. 4): anchors, wings and the start-up texture of Fig. 11.
        let billboard_height = grass.height[1];
        let mut billboards = if params.lod && layout.grid_count() > 0 {
            Billboards::new(
                &layout,
                params,
                &scene.blades,
                &scene.terrain,
                seed,
                planted,
            )
        } else {
            Billboards::empty()
        };
        let mut anchors = Animation::new(&billboards.anchors, params.flower_mass);
        anchors.set_rotations(false);
        let anchor_rest = anchors
            .blade_out
            .iter()
            .map(|d| Vec3::from_slice(&d.p3[..3]))
            .collect();
        // The texture's blades per metre of wing follow the lattice spacing (one plant per
        // spacing², the scene's strata by default), so a billboard shows as many blades as
        // grow in its block.
        let look = Look {
            grass,
            spacing: layout.spacing().min_element(),
            flower_fraction: params.flower_fraction,
            petal_size: params.petal_size,
        };
        let layers = billboards.steps.len().max(1) as u32;
        let mut texels = billboard_texture::billboard_texture(&look, &billboards.steps, seed);
        texels.resize(
            (billboard_texture::SIZE.0 * billboard_texture::SIZE.1 * layers) as usize,
            [0; 4],
        );
        if params.trim_wings {
            let skyline = Skyline::new(
                &texels,
                billboard_texture::SIZE,
                layers,
                params.effective_alpha_cutoff(),
            );
            billboards.cut_wings(&skyline);
        }
        let sorting = (params.sorting == Sorting::Sort)
            .then(|| SortLookup::new(&layout, planted, &billboards));
        let mut grids = GridIndex::new(planted);
        // The grids' anchors (the far groups' have their own boxes).
        grids.include(
            &billboards.anchors[..billboards.grid_anchors as usize],
            billboard_height,
        );
        let plants = Self {
            layout,
            grids,
            blades,
            billboards,
            anchors,
            anchor_rest,
            billboard_height,
            sorting,
        };
        (plants, BillboardTexels { texels, layers })
    }
}

impl SortLookup {
    /// The lookups of `planted` on `layout` and the block orders of `billboards`.
    fn new(layout: &Layout, planted: &[Planted], billboards: &Billboards) -> Self {
        let n = layout.per_side;
        let mut slots = vec![u32::MAX; (layout.grid_count() * n * n) as usize];
        for (b, p) in planted.iter().enumerate() {
            slots[(p.grid * n * n + p.cell) as usize] = b as u32;
        }
        Self {
            orders: BlockOrders::new(&billboards.per_side(n)),
            statics: planted.iter().map(blade_static).collect(),
            plants: planted
                .iter()
                .map(|p| p.root.extend(p.height).to_array())
                .collect(),
            slots,
        }
    }
}
