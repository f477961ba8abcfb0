//! The terrain as a quadtree of bounding spheres over the uniform grid of cells
//! (Boulanger Sec. 4.1).
//!
//! Leaves are the grid cells (one patch each); an inner node bounds a square group of cells, a
//! *macro-cell*. Each frame the tree is walked from the root: nodes whose bounding sphere lies
//! outside the view frustum are dropped with everything under them; a node far enough from the
//! eye (beyond every level that needs single cells, and at least `macro_factor` times its own
//! side away) is kept whole and drawn as one horizontal slice with texture repetition;
//! otherwise the walk descends. So the farther the ground, the larger the pieces it is drawn in
//! (Fig. 19), and culling costs O(visible nodes), not O(cells). Single cells, which may carry
//! thousands of geometric blades, are also tested with their bounding box, which is tighter
//! than the sphere under a low camera.

use glam::{Vec2, Vec3};
use grassbench::camera::{Aabb, Frustum};
use grassbench::terrain::Terrain;

/// The uniform grid of cells over the terrain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellGrid {
    /// World (x, z) of the corner of cell (0, 0): the terrain's min corner.
    pub origin: Vec2,
    /// Side of a cell (= the patch), m.
    pub cell: f32,
    /// Cells along x.
    pub nx: u32,
    /// Cells along z.
    pub nz: u32,
}

impl CellGrid {
    /// Cells of side `cell` covering `terrain` (the last row and column may stick out).
    pub fn new(terrain: &Terrain, cell: f32) -> Self {
        let n = |s: f32| ((s / cell - 1e-4).ceil() as u32).max(1);
        Self {
            origin: terrain.min_corner(),
            cell,
            nx: n(terrain.size().x),
            nz: n(terrain.size().y),
        }
    }

    /// World (x, z) of the min corner of cell `(i, j)`.
    pub fn cell_min(&self, i: u32, j: u32) -> Vec2 {
        self.origin + Vec2::new(i as f32, j as f32) * self.cell
    }

    /// Total cells.
    pub fn count(&self) -> u64 {
        u64::from(self.nx) * u64::from(self.nz)
    }
}

/// A rectangle of cells: `ni x nj` cells from `(i0, j0)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRect {
    /// First cell along x.
    pub i0: u32,
    /// First cell along z.
    pub j0: u32,
    /// Cells along x.
    pub ni: u32,
    /// Cells along z.
    pub nj: u32,
}

impl CellRect {
    /// Whether cell `(i, j)` is inside.
    pub fn contains(&self, i: u32, j: u32) -> bool {
        (self.i0..self.i0 + self.ni).contains(&i) && (self.j0..self.j0 + self.nj).contains(&j)
    }
}

const NONE: u32 = u32::MAX;

/// How far a cell's bounds reach beyond its sampled ground.
#[derive(Clone, Copy)]
struct Reach {
    /// Vertical margin on the sampled heights, m.
    margin: f32,
    /// How far blades lean past the cell, m.
    overhang: f32,
    /// How high blades stand, m.
    height: f32,
}

#[derive(Clone, Debug)]
struct Node {
    rect: CellRect,
    /// Where the roots are: the cells' ground, between the lowest and highest ground.
    ground: Aabb,
    /// Everything drawn for the node (blades lean past the cell and stand above the ground).
    bounds: Aabb,
    center: Vec3,
    radius: f32,
    children: [u32; 4],
    /// Blades that grow in its cells ([`crate::population`]).
    blades: u64,
    /// Lowest and highest local density under the node (sampled, with a margin).
    density_range: [f32; 2],
}

/// A node the walk kept: one cell, or a macro-cell drawn as one piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Selected {
    /// The cells it covers.
    pub rect: CellRect,
    /// Distance from the eye to the nearest point of its ground, m.
    pub near: f32,
    /// Distance from the eye to the farthest point of its ground, m.
    pub far: f32,
    /// Blades that grow in its cells ([`crate::population`]).
    pub blades: u64,
    /// Lowest and highest local density under it (3x3 samples per cell, ± 0.05).
    pub density_range: [f32; 2],
    /// Lowest and highest ground under it, m.
    pub ground_y: [f32; 2],
}

/// What a walk of the tree selected.
#[derive(Clone, Debug, Default)]
pub struct Selection {
    /// Single cells (near the eye).
    pub cells: Vec<Selected>,
    /// Macro-cells (farther away), drawn as horizontal slices only.
    pub macro_cells: Vec<Selected>,
    /// Nodes whose sphere was tested.
    pub nodes_visited: u32,
}

/// How to walk the tree for one view.
#[derive(Clone, Copy, Debug)]
pub struct Walk {
    /// The view frustum.
    pub frustum: Frustum,
    /// The eye.
    pub eye: Vec3,
    /// Nodes nearer than this are split down to single cells (the reach of geometry and of
    /// the vertical slices).
    pub cell_distance: f32,
    /// A macro-cell is kept whole only when at least this many times its side away.
    pub macro_factor: f32,
}

/// The quadtree over a [`CellGrid`].
#[derive(Clone, Debug)]
pub struct Quadtree {
    grid: CellGrid,
    nodes: Vec<Node>,
    root: u32,
}

impl Quadtree {
    /// Builds the tree: leaves sample the terrain's height and density at 3x3 points
    /// per cell; `overhang` is how far blades reach past their cell and `height` how high;
    /// `cell_blades(i, j)` is how many blades grow in cell `(i, j)`, summed up the tree.
    pub fn build(
        terrain: &Terrain,
        grid: CellGrid,
        overhang: f32,
        height: f32,
        cell_blades: &dyn Fn(u32, u32) -> u64,
    ) -> Self {
        let side = grid.nx.max(grid.nz).next_power_of_two();
        let (lo, hi) = terrain.height_range();
        // Bilinear heights peak at map samples; 3x3 points per cell can miss a sample inside
        // the cell, so leaves get a margin of a tenth of the height range.
        let margin = 0.1 * (hi - lo) + 0.01;
        let mut tree = Self {
            grid,
            nodes: Vec::new(),
            root: NONE,
        };
        let reach = Reach {
            margin,
            overhang,
            height,
        };
        tree.root = tree.build_node(terrain, 0, 0, side, &reach, cell_blades);
        tree
    }

    fn build_node(
        &mut self,
        terrain: &Terrain,
        i0: u32,
        j0: u32,
        side: u32,
        reach: &Reach,
        cell_blades: &dyn Fn(u32, u32) -> u64,
    ) -> u32 {
        let Reach {
            margin,
            overhang,
            height,
        } = *reach;
        let g = self.grid;
        if i0 >= g.nx || j0 >= g.nz {
            return NONE;
        }
        let rect = CellRect {
            i0,
            j0,
            ni: side.min(g.nx - i0),
            nj: side.min(g.nz - j0),
        };
        let (ground, children, blades, density_range) = if side == 1 {
            let min = g.cell_min(i0, j0);
            let (mut h_lo, mut h_hi) = (f32::INFINITY, f32::NEG_INFINITY);
            let mut range = [f32::INFINITY, f32::NEG_INFINITY];
            for b in 0..3 {
                for a in 0..3 {
                    let p = min + Vec2::new(a as f32, b as f32) * 0.5 * g.cell;
                    let h = terrain.height_at(p);
                    h_lo = h_lo.min(h);
                    h_hi = h_hi.max(h);
                    let rho = terrain.density_at(p);
                    range = [range[0].min(rho), range[1].max(rho)];
                }
            }
            let ground = Aabb {
                min: Vec3::new(min.x, h_lo - margin, min.y),
                max: Vec3::new(min.x + g.cell, h_hi + margin, min.y + g.cell),
            };
            // Bilinear densities between samples: a margin covers a map finer than 3x3 a cell.
            let range = [(range[0] - 0.05).max(0.0), (range[1] + 0.05).min(1.0)];
            (ground, [NONE; 4], cell_blades(i0, j0), range)
        } else {
            let h = side / 2;
            let children = [(0, 0), (h, 0), (0, h), (h, h)]
                .map(|(a, b)| self.build_node(terrain, i0 + a, j0 + b, h, reach, cell_blades));
            let mut ground: Option<Aabb> = None;
            let mut blades = 0;
            let mut range = [f32::INFINITY, f32::NEG_INFINITY];
            for &c in children.iter().filter(|&&c| c != NONE) {
                let n = &self.nodes[c as usize];
                blades += n.blades;
                range = [
                    range[0].min(n.density_range[0]),
                    range[1].max(n.density_range[1]),
                ];
                ground = Some(match ground {
                    None => n.ground,
                    Some(a) => Aabb {
                        min: a.min.min(n.ground.min),
                        max: a.max.max(n.ground.max),
                    },
                });
            }
            let Some(ground) = ground else {
                return NONE;
            };
            (ground, children, blades, range)
        };
        let bounds = Aabb {
            min: ground.min - Vec3::new(overhang, 0.0, overhang),
            max: ground.max + Vec3::new(overhang, height, overhang),
        };
        let center = 0.5 * (bounds.min + bounds.max);
        self.nodes.push(Node {
            rect,
            ground,
            bounds,
            center,
            radius: 0.5 * (bounds.max - bounds.min).length(),
            children,
            blades,
            density_range,
        });
        (self.nodes.len() - 1) as u32
    }

    /// The grid the tree covers.
    pub fn grid(&self) -> &CellGrid {
        &self.grid
    }

    /// Bounds of everything drawn for cell `(i, j)` (for tests), if the cell exists.
    pub fn cell_bounds(&self, i: u32, j: u32) -> Option<Aabb> {
        self.nodes
            .iter()
            .find(|n| n.children == [NONE; 4] && n.rect.i0 == i && n.rect.j0 == j)
            .map(|n| n.bounds)
    }

    /// Walks the tree for one view (Sec. 4.1), filling `out` (cleared first).
    pub fn select(&self, walk: &Walk, out: &mut Selection) {
        out.cells.clear();
        out.macro_cells.clear();
        out.nodes_visited = 0;
        if self.root == NONE {
            return;
        }
        let mut stack = vec![self.root];
        while let Some(k) = stack.pop() {
            let n = &self.nodes[k as usize];
            out.nodes_visited += 1;
            if !walk.frustum.intersects_sphere(n.center, n.radius) {
                continue;
            }
            let near = distance_to_box(walk.eye, &n.ground);
            let far = farthest_in_box(walk.eye, &n.ground);
            let s = Selected {
                rect: n.rect,
                near,
                far,
                blades: n.blades,
                density_range: n.density_range,
                ground_y: [n.ground.min.y, n.ground.max.y],
            };
            let is_leaf = n.children == [NONE; 4];
            let side = n.rect.ni.max(n.rect.nj) as f32 * self.grid.cell;
            if is_leaf {
                // Cells are drawn with geometry: the box, tighter than the sphere, too.
                if walk.frustum.intersects_aabb(&n.bounds) {
                    out.cells.push(s);
                }
            } else if near >= walk.cell_distance && near >= walk.macro_factor * side {
                out.macro_cells.push(s);
            } else {
                stack.extend(n.children.iter().filter(|&&c| c != NONE));
            }
        }
    }
}

/// Distance from `p` to the nearest point of `b` (0 inside).
pub fn distance_to_box(p: Vec3, b: &Aabb) -> f32 {
    (p.clamp(b.min, b.max) - p).length()
}

/// Distance from `p` to the farthest corner of `b`.
pub fn farthest_in_box(p: Vec3, b: &Aabb) -> f32 {
    let c = Vec3::select((p - b.min).cmpgt(b.max - p), b.min, b.max);
    (c - p).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::camera::Camera;
    use grassbench::terrain::{CoveringSource, MapSource, TerrainConfig};
    use proptest::prelude::*;

    fn hills() -> Terrain {
        let config = TerrainConfig {
            size: [60.0, 37.0],
            max_height: 4.0,
            samples_per_metre: 1.0,
            height: MapSource::Procedural {
                frequency: 0.03,
                octaves: 3,
                range: [0.0, 1.0],
                power: 1.0,
            },
            density: MapSource::one(),
            covering: CoveringSource::Grass,
        };
        Terrain::build(&config, 5, std::path::Path::new(".")).unwrap()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Culling never drops a visible cell: every cell whose bounds touch the frustum is
        /// inside exactly one selected node (cell or macro-cell).
        #[test]
        fn culling_never_drops_a_visible_cell(
            x in -40.0f32..40.0, z in -30.0f32..30.0, y in 0.5f32..30.0,
            yaw in 0.0f32..std::f32::consts::TAU, pitch in -1.2f32..0.3, fov in 20.0f32..90.0,
            cell_distance in 0.0f32..20.0, macro_factor in 0.5f32..8.0,
        ) {
            let terrain = hills();
            let grid = CellGrid::new(&terrain, 1.0);
            let tree = Quadtree::build(&terrain, grid, 0.3, 0.6, &|_, _| 1);
            let forward = Vec3::new(yaw.cos() * pitch.cos(), pitch.sin(), yaw.sin() * pitch.cos());
            let eye = Vec3::new(x, terrain.height_at(Vec2::new(x, z)) + y, z);
            let camera = Camera::look_at(eye, eye + forward, fov.to_radians(), 0.1, 300.0, 16.0 / 9.0);
            let walk = Walk { frustum: camera.frustum(), eye, cell_distance, macro_factor };
            let mut sel = Selection::default();
            tree.select(&walk, &mut sel);
            let all: Vec<&Selected> = sel.cells.iter().chain(&sel.macro_cells).collect();
            let mut visible = 0;
            for j in 0..grid.nz {
                for i in 0..grid.nx {
                    let covering = all.iter().filter(|s| s.rect.contains(i, j)).count();
                    prop_assert!(covering <= 1, "cell ({i}, {j}) selected {covering} times");
                    let b = tree.cell_bounds(i, j).unwrap();
                    if walk.frustum.intersects_aabb(&b) {
                        visible += 1;
                        prop_assert_eq!(covering, 1, "visible cell ({}, {}) dropped", i, j);
                    }
                }
            }
            prop_assert!(visible == 0 || !all.is_empty());
        }
    }

    #[test]
    fn far_ground_is_drawn_in_macro_cells() {
        let terrain = Terrain::flat(Vec2::new(105.0, 68.0));
        let grid = CellGrid::new(&terrain, 0.5);
        assert_eq!((grid.nx, grid.nz), (210, 136));
        let tree = Quadtree::build(&terrain, grid, 0.2, 0.2, &|_, _| 1);
        let eye = Vec3::new(-50.0, 1.7, 0.0);
        let camera = Camera::look_at(eye, Vec3::new(0.0, 0.0, 0.0), 0.87, 0.1, 500.0, 16.0 / 9.0);
        let walk = Walk {
            frustum: camera.frustum(),
            eye,
            cell_distance: 4.0,
            macro_factor: 3.0,
        };
        let mut sel = Selection::default();
        tree.select(&walk, &mut sel);
        assert!(sel.cells.iter().all(|s| s.near < 4.0 + 1.0));
        assert!(sel.macro_cells.iter().all(|s| s.near >= 4.0));
        let covered: u64 = sel
            .cells
            .iter()
            .chain(&sel.macro_cells)
            .map(|s| u64::from(s.rect.ni * s.rect.nj))
            .sum();
        // Thousands of cells in view, drawn as a few hundred pieces.
        assert!(covered > 5_000, "{covered}");
        // One blade a cell: a node holds its cells' blades.
        let blades: u64 = sel
            .cells
            .iter()
            .chain(&sel.macro_cells)
            .map(|s| s.blades)
            .sum();
        assert_eq!(blades, covered);
        assert!(sel.cells.len() + sel.macro_cells.len() < 1_000);
        assert!(sel.macro_cells.iter().any(|s| s.rect.ni >= 8));
    }

    #[test]
    fn box_distances() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        assert_eq!(distance_to_box(Vec3::splat(0.5), &b), 0.0);
        assert_eq!(distance_to_box(Vec3::new(3.0, 0.5, 0.5), &b), 2.0);
        assert!((farthest_in_box(Vec3::ZERO, &b) - 3f32.sqrt()).abs() < 1e-6);
    }
}
