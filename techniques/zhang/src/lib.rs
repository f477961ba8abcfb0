//! # `zhang`: physically based prairie with billboards far away
//!
//! Zhang Xia, *Physically Based Animation and Fast Rendering of Large-Scale Prairie* (MSc thesis,
//! 2006). Wind comes from a Navier-Stokes (Stam "stable fluids") simulation; each blade is a cubic
//! Bezier curve over four control points moved by that wind with Verlet integration and length
//! constraints; flowers are petal quads on heavier points. The camera grid and its eight neighbours
//! draw these single plants; every other grass grid draws billboards of six rectangles whose length
//! doubles with the grid offset (Ch. 4, Sec. 5.2), and beyond `far_groups` grids (ours) blocks of
//! `2^k x 2^k` grids draw one billboard each, so the cost of a frame does not grow with the
//! terrain. Grids are culled against the view frustum, single plants of the near grids too (Sec.
//! 5.3); everything is drawn far to near and blended (Sec. 5.4), and grids crossing between the two
//! representations fade (Sec. 6.1); the scene's moving object pushes blades aside (Sec. 6.2), and
//! the covering map's gaps, trees and stones leave the grass out (Sec. 5.5.2). The blades are the
//! scene's: the same blades, at the same places, as the reference's.
//!
//! The trees and stones themselves (Sec. 5.5.2's simple meshes) were drawn here until issue 19;
//! they are part of the scene, so the core now draws them for every technique
//! (`grassbench::scene::props`), and `zhang` draws grass only.
//!
//! ## Algorithm
//! - **Wind (Ch. 2, Sec. 3.2.2).** Whatever [`WindField`](grassbench::wind::WindField) the scene
//!   has; with `[wind] model = "fluid"` that is the core's
//!   [`FluidWind`](grassbench::wind::FluidWind): the thesis' 8³ Stam solver, one solution tiled
//!   over the grass grids with per-grid offsets (Sec. 5.1), sampled trilinearly. Each moving
//!   control point of a drawn blade reads the wind at its own position every frame (one batched
//!   `inputs.wind.velocities(points, time)` call per thread's share; the breeze computes its
//!   per-time constants once and reuses its noise cells, bit for bit equal to `velocity`); blades
//!   animated but not drawn read it once, at `P2` (see Animation).
//! - **Prairie (Sec. 3.1.2, 5.1, [`prairie`]).** Grass grids of `n x n` lattice points, and the
//!   lattice is the scene's population: lattice point `(i, j)` is stratum `(i, j)` of the scene's
//!   [`BladeField`](grassbench::grass::BladeField) (cells of `1/density` m², one candidate blade
//!   each), its plant that stratum's candidate (root, height, width, facing, lean, stiffness,
//!   colour variation, density threshold), and it grows exactly where the shared rule says (on the
//!   terrain, covering map grass, threshold below the density map). So `zhang`'s single plants are
//!   the reference's blades, one for one, and its population follows `grass.density` and both maps
//!   like every technique's. Why: the thesis plants a fixed 32 x 32 jittered lattice per grid (Sec.
//!   3.1.2, 5.1), and so did `zhang` until issue 19: `(16·32)² = 262 144` candidates whatever the
//!   scene asked, about 41 blades/m² on the meadow whose scene asks for 90 (a full image at
//!   `grass.density = 0`, the same one at 30 and at 90), and part of its speed-up over the
//!   reference was fewer blades; a comparison must differ in how the blades are drawn, not in how
//!   many there are. The grids are square, `n` strata a side: the whole number of strata nearest
//!   `grid_size` metres (5.1 by default; see Deviations), or with `grid_size = 0` the thesis'
//!   count, `n = ⌈cells/grids⌉` for `grids` (16) along the terrain's longer side; never more than
//!   the shorter side has; as many grids along each side as it takes to cover it, the grid origin
//!   on the strata lattice; the last row and column of grids reach past the terrain and hold fewer
//!   plants. The meadow (80 m at 90 blades/m², 760 strata a side) has 16 x 16 grids of 48 x 48
//!   (5.06 m) either way; the prairie flyover (240 m at 14) 48 x 48 of 19 x 19 (5.08 m; the thesis'
//!   count: 16 x 16 of 57 x 57, 15.2 m), the football field (105 x 68 m at 40) 21 x 14 of 32 x 32
//!   (5.06 m; the count: 16 x 11 of 42 x 42, 6.6 m), and 433 720, 449 282 and 285 605 blades grow
//!   on them, the reference's counts exactly; `grass.density = 0` has no grids and draws nothing.
//!   Flowers, the thesis' addition to the grass, are hashed per lattice point. `blades_per_side >
//!   0` plants the thesis' lattice instead (`grids x grids` grids of `blades_per_side²` jittered
//!   candidates fitted over the terrain, sizes from the scene's `[grass]` ranges, thinned by the
//!   same rule, whatever `grid_size`), for paper-like figures.
//! - **Blade (Sec. 3.1.1, Fig. 5).** Four control points `P0..P3`; `P0` is the root (inverse mass
//!   0, Sec. 3.4). The vertex shader samples the backbone at `n` points with Eq. (5) (`t =
//!   i/(n−1)`) and extends each backbone point sideways into two segment points along the
//!   horizontal width axis; consecutive pairs form the quads of one triangle strip. A procedural
//!   blade texture with alpha (tapering outline, midrib, streaks) cuts the blade out of the quads
//!   (Fig. 5b), by alpha test (and alpha-to-coverage under MSAA).
//! - **Animation (Sec. 3.2.3-3.2.5), on the CPU in `update`.** Per moving control point, Verlet
//!   (Eq. 7): `x' = x + keep·(x − x'') + a·dt²` with `a = wind_response · height · w(x) / mass +
//!   spring · stiffness · (rest − x)`, the point reflected above the ground as the thesis'
//!   `abs(y)`; then the length constraints bottom-up (`P_i -= (P_i − P_{i−1})·(l' − l)/l'`, Sec.
//!   3.2.4); then the rotation θ of Sec. 3.2.5 (segment points of backbone point `i` turn by
//!   `θ·i/(n−1)` around up). `prepare` uploads `P1..P3` and θ (48 bytes a blade) of the blades
//!   drawn. Blades the level of detail animates without drawing them this frame (culled grids,
//!   grids two away, anchors beyond the drawn step's) are *hidden*: kept in motion every other
//!   frame (half of them each frame) by one Verlet step of two frames' time with the wind at `P2`
//!   for all three points, and no instance data ([`animate::StepRanges::hidden`]); a blade coming
//!   into view is then within 2 % of its height of where full steps would have put it. Blades and
//!   anchors are stepped together, one equal share per core (scoped threads).
//! - **Culling (Sec. 5.3, [`culling`]).** Blades are planted grid by grid, so each grass grid is a
//!   contiguous instance range with a conservative box (widened for the billboards' anchor plants);
//!   `update` keeps the grids whose box meets the frustum. With sorting, the single plants of the
//!   near grids are culled one by one as well (bounding spheres), since they are visited one by one
//!   anyway; without, near grids are drawn whole as merged instance ranges. `culling = false` draws
//!   every grid.
//! - **Billboards (Sec. 4.1-4.2, [`billboard`], [`billboard_texture`]).** A grid `g` grids from the
//!   camera grid (`g = max(|Δx|, |Δz|)`) is cut into `n' x n'` blocks of `l' = 2·2^⌊log2 g⌋ + 1`
//!   plants per side (Eq. 8-9: for the thesis' `n = 32`, 8 x 8 blocks of 5 at `g = 2, 3`, 4 x 4 of
//!   9 at `g = 4..7`, 2 x 2 of 17 beyond; for the meadow's `n = 48`, 12 x 12, 6 x 6 and 3 x 3; the
//!   last block of a row shorter, and in a grid that the terrain's edge cuts short, the last block
//!   ends at its last stratum). Each block's billboard is six rectangles ("wings") joined at a
//!   vertical middle line on the block's centre plant, reaching to the middles of its four edges
//!   and two opposite corners. Every wing corner is a lattice plant ("anchor"), so a wing joins the
//!   root and top points of two plants as Sec. 4.2 says; anchors are animated like blades (only
//!   their top points are drawn), and the anchors of step `2s` are a prefix of those of `s`, so a
//!   grid animates just the prefix its step needs. Far billboards sway `1 + billboard_sway·(g − 2)`
//!   times their plants' displacement. The texture (Fig. 11) is composed at start-up from the blade
//!   and petal textures with the scene's blade sizes, one layer per step with `s/(2+√2)` blades per
//!   spacing (what a billboard standing for `s²` plants on `(2+√2)·s` spacings of wings must show),
//!   the spacing being the lattice's (the scene's strata: one blade per `spacing²`), so a billboard
//!   shows as many blades as grow in its block; its texels carry luminance, a density threshold,
//!   colour variation or petal colour, and alpha, so wings are coloured like blades and thinned by
//!   the density map with the shared threshold rule. Gaps, trees and stones in the covering map
//!   drop the wings that touch them, splitting billboards (Sec. 5.5.2); a block where no plant
//!   grows has no billboard. A billboard stands for the plants growing in its block
//!   (`blades_represented` counts those of the blocks drawn; a grid fading both ways counts once,
//!   as its single plants, which `blades_drawn` counts). Each wing is cut down at start-up to the
//!   texels it can show ([`wing_trim`]; see Deviations), and lit per vertex by the ambient and the
//!   sun, per pixel by the point light.
//! - **Far groups (ours, [`billboard::GroupLevel`], [`frame::Plan`]).** With `far_groups = F` (16
//!   by default, 0 in `paper`), groups of `2^k x 2^k` grids aligned on multiples of `2^k` are drawn
//!   as one billboard each once their nearest grid is at least `T_k = ⌈F·2^((k−1)/2)⌉` grids from
//!   the camera grid (16, 23, 32, 46, 64, ...): Eq. 8's doubling continued across grids, but with
//!   the side doubling every `√2` in distance rather than every 2, so the groups in a ring of the
//!   view get fewer outwards (a bounded sum) where Eq. 8's would stay as many per ring, a count
//!   growing with the logarithm of the terrain. A group's billboard is built like a grid's (six
//!   wings on lattice plants, [`billboard`]) on the lattice of the whole group, its middle line on
//!   the group's middle plant (of the part on the terrain, in an edge group), one texture layer per
//!   group level with the blades per spacing of its span, so it stands for every plant growing in
//!   the group (`blades_represented`). Gaps do not drop a group's wings: each is thinned by the
//!   mean of density times "is grass" at 16 points along it (a gap at the middle plant would
//!   otherwise take tens of metres of grass away), and dropped only where no grass lies along it.
//!   Each frame the groups are found from the coarsest level down: a group far enough is drawn (or
//!   culled by its box), any other split into its four children, and the grids reached below the
//!   finest level are planned one by one as before; since children are never nearer than their
//!   group and `T_k` grows with `k`, every grid is drawn by exactly one grid or group (tested over
//!   random eyes, with the population conserved), and grids inside a drawn or culled group are
//!   never visited. Level changes between grids and groups, like Eq. 8's steps, are not faded. A
//!   group's anchors are animated (in full) only while it is drawn; no group is drawn on a terrain
//!   that no grid offset of `T_1` or more fits in (the meadow at 80 m: 16 grids), so there nothing
//!   changes.
//! - **Level of detail (Sec. 5.2, [`lod`], [`frame`]).** `g ≤ 1`: single plants; otherwise
//!   billboards (and far groups, above). Blades are animated in the grids up to two away and
//!   anchors at the step one grid closer, so a grid whose level changes at a border crossing is
//!   already in motion; the far blades are not animated at all (the bulk of part 1's CPU time). Of
//!   what is animated, only what the frame draws gets the full step; the rest is hidden (see
//!   Animation).
//! - **Far to near (Sec. 5.4, [`order`]).** `sorting = "sort"`: grids by squared grid offset
//!   (quicksort), billboards by the pre-computed orders of the nine sections of Fig. 17, the camera
//!   grid's plants quicksorted by distance, the surrounding grids' plants line by line (Table 1)
//!   with each line walked from its far end towards the eye. Blended with Eq. (10) (`C = S·S_a +
//!   D·(1 − S_a)`), depth written, alpha cut at 0.05; the sorted single plants are copied into
//!   their own instance buffers in draw order. Petals are alpha-tested and drawn first (they need
//!   no order). `sorting = "alpha_to_coverage"`: no sorting, alpha test with depth writes (and
//!   alpha to coverage under MSAA); the `sort_ms` counter gives the CPU cost of ordering to
//!   compare.
//! - **Fades (Sec. 6.1, [`fade`]).** Within `fade_radius` grid sizes of a grid border, the grids
//!   whose level differs across it are drawn both ways with complementary alphas (the other side's
//!   at `½·(1 − r1/r0)`), blended when sorting, dissolved (per-blade threshold) otherwise.
//! - **Sphere-plant interaction (Sec. 6.2, `BladeState::interact`).** The scene's moving object
//!   (`[object]`, shared with every technique) is the interaction sphere. After each frame's Verlet
//!   steps, a blade whose root lies under the sphere has its first backbone point inside it moved
//!   out to the surface along the ray from the centre, the length constraint applied, and the
//!   points above continued in that direction, tangent to the sphere. Where that would leave a
//!   point inside (a blade right under the centre) the rest of the blade points away from the
//!   centre. Pushed points lose their velocity; the spring brings the blade back after the sphere
//!   has passed. Only animated (near) blades react: billboards do not.
//! - **Flowers (Sec. 3.3-3.4).** A `flower_fraction` of blade positions also carry a flower: a
//!   petal point at `0.65 · height` (±10 %) on an invisible stalk, animated like a blade's top
//!   point with mass `flower_mass` (the wind push divided by it), drawn as a square petal
//!   perpendicular to the stalk (horizontal at rest) with one of six procedural petal textures.
//!
//! ## Deviations and interpretations
//! - The population is the scene's (see Prairie), not the thesis' 32 x 32 lattice per grid: the
//!   grids are as many, but each holds the strata of the scene's blade field that fall in it (`n x
//!   n` of them), so the grid size and the billboards' blocks scale with the density
//!   (`blades_per_side = 32` gives the thesis' lattice back). Billboards of blocks where no plant
//!   grows are left out: they would stand for nothing.
//! - Grass grids have a size in metres, not the thesis' fixed count (`grid_size = 5.1`; `grid_size
//!   = 0` keeps Sec. 5.1's 16 x 16, as `paper` does): with 16 x 16 grids whatever the terrain, the
//!   camera grid and its eight neighbours (single plants) cover 75 x 75 m of a 400 m terrain and
//!   the billboard blocks grow with the grid, so zhang cost 4.7x as much GPU time at 400 m as at 80
//!   m on `experiments/scaling.toml`'s meadow (20 blades/m², 480x270: 393 k triangles against 27 k;
//!   CPU update 11x). 5.1 m keeps the meadow's grids at 80 m (48 strata at 90 blades/m², 23 at 20:
//!   pixel for pixel the thesis count's frame, `tests/tests/gpu_zhang.rs`) and the football field's
//!   about as wide, but the prairie flyover's 15.2 m grids become 5.1 m ones: seen from its 32 m
//!   altitude the single plants (within a grid of the camera's ground point) are out of view and
//!   its whole frame is billboards, whose regular lattice shows in the foreground; measured there
//!   (640x360, frame 3 of 3 after 2 warm-up frames, one run, loaded host): 13.8 k triangles against
//!   126 k, GPU 58 against 141 ms, FLIP against the reference 0.0689 against 0.0606; on the
//!   football field 11.1 k against 26.7 k triangles, FLIP 0.0179 against 0.0187; the meadow
//!   identical. `grid_size = 15` gives the prairie its old grids back.
//! - Far groups (above) are ours: Sec. 5.2 draws every far grid at Eq. 8's length, which keeps as
//!   many billboards in each doubling of the distance, so a larger terrain seen to its edge costs
//!   more. Measured on `experiments/scaling.toml` with zhang alone (meadow at 20 blades/m²,
//!   480x270, 2 warm-up and 5 frames, 3 repetitions; a host loaded by other sessions, 1.2-1.4 of
//!   its 2 cores busy besides, so compare within a configuration), from 80 m to 160, 240 and 400 m:
//!   triangles 26.7 k → 19.9 k, 20.1 k, 27.4 k (1.03x at 400 m; with the thesis' count 393 k,
//!   14.7x), GPU wall 49.4 → 45.0, 49.0, 59.5 ms (1.21x; with the count 46.6 → 236.3 ms, 5.07x), of
//!   which the core's background pass (sky, ground mesh over the whole heightmap, props; the core
//!   draws the ground in chunks since, and the sweep of `results/scaling/` at `2dd4b96`, on a
//!   2.6 GHz AMD EPYC (Zen 4) virtual machine, has zhang at 17 → 19 ms, 1.13x; 56 → 64 ms,
//!   1.13x, on a 2.0 GHz EPYC at `487fc0a`; 16 → 20 ms, 1.18x, on the Xeon at `00e5090`) 11.2 →
//!   17.5 ms and zhang's own passes 38.1 → 42.0 ms (1.10x); CPU update 7.4 →
//!   9.3, 17.4, 16.2 ms (2.2x; with the count 9.4 → 115.6 ms, 12.3x). In an earlier sweep 5.1 m
//!   grids without groups gave 41.8 k triangles (1.57x) and 1.72x the GPU time. What still grows in
//!   the update is bounded by `far_groups`, not by the terrain: the grids nearer than `T_1` (up to
//!   31 x 31 of them, against the 16 x 16 of the whole 80 m meadow) are planned one by one and
//!   animate their anchors (hidden at half rate where not drawn); with `far_groups = 8` the update
//!   stayed at the 80 m figure in one sweep. Below 80 m the metric grids are larger than the
//!   count's (1 m grids on a 16 m terrain), so more is drawn as single plants: 16 m 3.5 k triangles
//!   against 2.4 k, 36 m 7.1 k against 3.1 k. The picture: at 400 m far groups against every grid
//!   on its own FLIP 0.0029 (0.0026 at 1/4; `tests/tests/gpu_zhang.rs`).
//! - The thesis' Verlet step has no restoring force and no damping: blades return only when the
//!   (random, zero-mean) fluid wind pushes them back, and a steady wind of any other model would
//!   lay them flat. We add a spring to the rest pose (`spring`, scaled by the blade's stiffness)
//!   and damping (`damping`, `keep = exp(−damping·dt)`); with both set to 0 the step is exactly Eq.
//!   (7).
//! - Eq. (7) is driven by the wind *velocity* (the thesis' `SetForce(temp)` stores the interpolated
//!   velocity as the acceleration); `wind_response · height` converts m/s to m/s² so blades of all
//!   heights bend by similar angles.
//! - Sec. 3.2.5 computes `θ = acos(wind · blade)`, yet asks for the blade to end up perpendicular
//!   to the wind; we rotate by the signed angle to the nearer perpendicular and fade the rotation
//!   in for blades whose tip moved less than 10 % of their height (an upright blade's wind
//!   direction is undefined).
//! - The Bezier evaluation and the segment points are computed in the vertex shader from the
//!   control points (the thesis does it on the CPU): same geometry, 48 instead of `24·n` bytes of
//!   upload per blade. `blade::bezier` and `blade::bezier_tangent` write Eq. (5) and its derivative
//!   on the CPU; nothing draws or animates with them: they are the shader's twins, tested against
//!   the Bernstein form of the thesis' curve at interior parameters, and `tests/tests/twins.rs`
//!   runs the shader's `bezier` and `bezier_tangent` against them.
//! - The ground under a blade is the plane through its root; flowers attach to a blade position
//!   rather than being sprinkled independently.
//! - Sec. 4.2 raises the *velocity* of far billboards with distance; we scale their top points'
//!   displacement from rest instead (faster and wider sway: the anchors' Verlet state is shared by
//!   all steps, so their time cannot run faster per grid).
//! - Sec. 6.1's fade reaches alpha 1 at the border, so it needs the camera's direction of motion
//!   (Fig. 20) and pops when the camera stops or turns there; we spread the same ramp over both
//!   sides of the border (continuous for any motion, no state between frames).
//! - Table 1's fixed in-line arrows cannot be far to near for a camera standing beside a line; we
//!   walk each line from its far end towards the camera (tested exhaustively).
//! - Billboard textures and the single plants' colours come from the scene's grass colours, not
//!   from separate photographs.
//! - A wing is drawn as the part of its rectangle that holds the texels it can show (ends moved in
//!   to the first and last such column, top down to the highest such row; [`wing_trim`],
//!   `trim_wings = false` draws whole ones), not the whole rectangle as tall as the scene's tallest
//!   blade: the same texels where a wing is planar, a quarter less fill on the meadow's walk and
//!   half on the prairie's flight, 8 % off zhang's frame on the meadow on lavapipe (A/B,
//!   `results/zhang_lod/README.md`).
//! - Wings are shaded per vertex for the ambient and the sun (exact: over a wing only the ambient
//!   occlusion varies, affinely with the height, so the sum interpolates exactly) and for the fog
//!   (across a wing, at most 1.8 m deep for the coarsest diagonal ones, `1 − exp(−k·d)` departs
//!   from a line by at most `k²·1.8²/8`, 2·10⁻⁶ at the default `k` = 0.002/m), per pixel for the
//!   point light (a second pipeline, drawn only in frames that have one). The per-pixel
//!   `shade_leaf` made zhang's frame 17 % longer on the meadow on lavapipe (13 k wings with `n =
//!   32`, five screens of fill); the blades keep it.
//! - The thesis steps every animated blade every frame with the wind at each control point. Blades
//!   that are animated but not drawn this frame (about two thirds of them on the meadow: grids
//!   behind the camera, grids two away, the finer billboard step's extra anchors) take one step
//!   every other frame, of two frames' time (`ω·dt` ≤ 0.48 at the default spring, well inside
//!   Verlet's stability bound of 2), with one wind sample at `P2`: they only have to be moving
//!   plausibly when they come into view, and their tips stay within 2 % of the blade height of
//!   fully stepped ones (tested; what remains decays with the damping once they are drawn).
//!   `hidden_half_rate = false` (the `paper` variant) steps them in full every frame, as the thesis
//!   does.
//!
//! ## Cost model
//! CPU per frame: animated are the blades of the (at most 5 x 5) grids up to two away, their
//! flowers, and the anchors of the far grids (289 per grid at `l' = 5`, 81 at 9, 25 at 17, for `n =
//! 32`; 625, 169 and 49 for the meadow's `n = 48`) nearer than the far groups, and the drawn
//! groups' (at most 9 each). The drawn ones (`B_draw`: the visible near grids' blades and the
//! anchors the visible wings read) cost 3 wind samples + Verlet + 3 length constraints each (and
//! one `acos` for θ, blades only); the hidden ones (`B_hid`) half of one sample + Verlet each
//! frame. On the meadow walk with the thesis' lattice (16 x 16 grids of `n = 32`, before issue 19):
//! 21 320 blades and 31 117 anchors animated, of which 6 256 blades and 11 183 anchors drawn, 15
//! 064 and 19 934 hidden, so about 70 k wind samples and 35 k Verlet steps a frame (part 2 took 157
//! k and 52 k); the scene's population (`n = 48`) has 2.25 times the blades and about twice the
//! anchors per grid, and costs about that much more. A breeze sample (3 `sin`, 2 value noises,
//! mostly from the cached cell) costs about as much as a blade's Verlet step; both are spread over
//! the cores, and so are the wings (13 k on the meadow with `n = 32`, 30 k with the scene's `n =
//! 48`: one top point per anchor per grid, then 80 bytes each). Sorting: a quicksort of the camera
//! grid's `≤ n²` plants, line walks of the surrounding grids, a sort of the visible grids (0.2-0.3
//! ms measured on the meadow with `n = 32`, 0.57 ms in one frame with `n = 48`). Measured `update`
//! on the meadow at 640x360 with `n = 32` (2 shared vCPUs, lavapipe, another engineer's jobs
//! running: load average 1.5-1.9; 13 runs of 30 frames per binary, alternating): median of the
//! runs' medians 5.2 ms against 13.4 ms before hidden blades and batched breeze samples (at load
//! 3.5-3.8: 8.6 against 21.8 ms; the quiet-machine figure before was 10.0 ms,
//! `results/zhang_lod/README.md`). With the scene's population (`n = 48`, issue 19) it takes about
//! 2.3 times as long: in alternating runs of 20 frames (640x360, a load average of 9-10 on the 2
//! vCPUs from other sessions' builds and tests, so every figure is inflated) 72-82 ms against 29-39
//! ms with `blades_per_side = 32`, and 915-919 ms of GPU wall against 500-503 ms; in one
//! interleaved run at that load zhang took 774 ms a frame against the reference's 4 769 on the
//! meadow (6.2x) and 456 against 3 783 on the prairie flyover (8.3x). Upload `48·B_draw +
//! 32·F_anim` bytes, 80 bytes per wing, and with sorting 80 bytes per drawn single plant. GPU:
//! `2(n−1)` triangles (8 at `n = 5`) per visible near blade, 2 per petal and 2 per wing (at most
//! `6·n'²` wings per far grid); 3-5 draws. With far groups (default) the billboards beyond `T_1 =
//! far_groups` grids are at most six wings per group, and the groups in view stay about as many
//! however large the terrain: 148 drawn (342 culled) with 8.9 k wings in all on the 400 m meadow of
//! the scaling sweep (Deviations). On a software rasteriser the wings' fill dominates: on the
//! meadow's walk at 640x360 with `n = 32` they covered 5.4 screens whole and 4.0 cut (on the
//! prairie's flight 1.1 and 0.6; measured before issue 19's population), most of it in the nearest
//! billboards (`l' = 5`). Memory: `80·B + 32·F` bytes of instances, 80 per wing, 80 per sorted
//! single plant (16 near grids' worth), 91 KB of textures plus 128 KB per billboard layer (3 on the
//! canonical scenes). Measured numbers: `README.md`, `results/zhang_lod/`.
//!
//! ## Known artifacts
//! - Textures are sampled at mip level 0 (a cut-out's alpha would blur away with distance) and the
//!   billboard texture nearest (its channels are ids): far billboards alias and shimmer.
//! - Billboards are more uniform than the blades they replace, and about as light (rows 110-170 of
//!   `results/default`'s meadow frame 3, the billboard band: mean colour 95/111/80 against the
//!   reference's 99/115/82; saved frames looked paler before the read-back dropped the alpha that
//!   Eq. 10 blends into the target, `src/target.rs`); the step changes of Eq. 8 (5 → 9 → 17) are
//!   not faded (the thesis fades only billboards ↔ single plants) and show as faint seams along
//!   grid borders; petals in billboards are full-size specks that read as more flowers far away.
//! - Sorting is by roots and block centres: leaning blades and swaying wings can still overlap out
//!   of order; the near grids' fading billboards are drawn in the wing pass, before the blades of
//!   farther fading grids. Petals of a fading grid appear and vanish at once.
//! - Without sorting and MSAA the alpha test gives hard, aliased outlines.
//! - A swaying wing whose two tops move apart is not planar; its cut rectangle's diagonal is not
//!   the whole one's, so a nearest-texel lookup lands a texel off here and there (8.6 % of the
//!   pixels differ at the meadow's frame 30, FLIP 0.018 between the two; both are about as far from
//!   the finest image, FLIP 0.042).
//! - Hidden blades (animated, not drawn) are up to 2 % of their height off the pose full steps
//!   would give. With the default fades a grid's blades are drawn, and so stepped in full, from the
//!   start of the fade band, about a second before they are half opaque, and the difference has
//!   decayed by then; with `fade_radius = 0` the blades of a grid that switches to single plants
//!   show it for the first second (at the meadow's frame 30 the mean absolute difference from the
//!   finest image grows from 2.2 to 2.7 levels of 255; with fades it stays at 3.1) and a grid
//!   turning into view shows it either way.
//! - A far group's anchors are animated only while it is drawn, and a grid's only while it is
//!   nearer than the groups: when the camera moves so that a group splits into grids (or grids
//!   merge into a group), the newly drawn anchors start from where they were last left (at rest at
//!   first) and take about a second to sway with the wind. They are at least `T_1` grids (80 m by
//!   default) away, where the sway is below a pixel at the scenes' resolutions. Switches between
//!   grids and groups are not faded (as Eq. 8's steps are not). A group's billboard is thinned by
//!   the gaps along its wings instead of split by them, so a gap far away shows as thinner grass
//!   rather than bare ground.
//! - With the tiled fluid wind the same motion repeats every grass grid (offset per grid, Sec.
//!   5.1); the thesis accepts this.
//!
//! ## Code
//! This file holds the registry entry and the [`GrassTechnique`] impl, which delegate to:
//! [`plants`] (what persists between frames: the planted grids, the blades' and anchors' animation,
//! the billboards, the lookups of sorting), [`frame_plan`] (what `update` works out for a frame and
//! the buffers it reuses), [`gpu`] (the buffers, upload and draw calls) and [`pipelines`] (the
//! shaders, textures and pipelines). [`shader_data`] holds the plain records the shaders read and
//! imports nothing of the crate; the remaining modules are the thesis' pieces named above.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod animate;
pub mod billboard;
pub mod billboard_texture;
pub mod blade;
pub mod culling;
pub mod fade;
pub mod flower;
pub mod frame;
pub mod frame_plan;
pub mod gpu;
pub mod lod;
pub mod order;
pub mod paper;
pub mod params;
pub mod pipelines;
pub mod plants;
pub mod prairie;
pub mod shader_data;
pub mod textures;
pub mod wing_trim;

use grassbench::gpu::GpuEstimate;
use grassbench::technique::{LevelBlades, Technique, TechniqueEntry, Variant, Variants};
use grassbench::{
    Error, FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result, Scene,
    TechniqueInfo, TechniqueStats,
};

pub use animate::Animation;
pub use params::Params;
pub use pipelines::{BILLBOARD_SHADER, SHADER};
pub use shader_data::{BladeDynamic, BladeStatic, FlowerInstance, ParamsUniform, WingInstance};

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Zhang>();

/// The technique.
pub struct Zhang {
    params: Params,
    /// The prairie between frames: grids, animation, billboards.
    plants: plants::Plants,
    /// Buffers, textures and pipelines.
    gpu: gpu::PrairieGpu,
    /// This frame's plan (`update` → `prepare`, `encode`, the statistics).
    frame: frame_plan::FramePlan,
}

impl Technique for Zhang {
    type Params = Params;

    const INFO: TechniqueInfo = TechniqueInfo {
        id: "zhang",
        name: "Zhang 2006 (Navier-Stokes wind, Bezier blades, flowers)",
        paper: "Zhang Xia 2006, Physically Based Animation and Fast Rendering of Large-Scale Prairie",
        gpu_state: false,
        debug_views: &[],
    };

    // Single plants everywhere (level of detail off, Sec. 5.2). No `no_transitions` variant:
    // `fade_radius = 0` switches without fading, but the comparison suite's popping check
    // (a 0.25 m/frame dolly) cannot see zhang's switch under the parallax of near blades and
    // sees more change with the fade band's two layers (peak 8.3 against 7.7 measured); the
    // switch itself is measured by `gpu_zhang`'s crossing test instead.
    const VARIANTS: Variants = Variants {
        finest: "lod = false",
        others: &[Variant {
            name: grassbench::technique::PAPER,
            params: paper::VARIANT,
        }],
    };

    /// Plants the prairie, builds the animation state, textures and pipelines.
    fn new(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        let scene = ctx.scene;
        let (layout, planted) =
            prairie::plant(&params, &scene.blades, &scene.terrain, scene.config.seed);
        // The per-frame control points of every blade must fit in one buffer.
        let per_frame = (planted.len() * std::mem::size_of::<BladeDynamic>()) as u64;
        let max = ctx.gpu.device.limits().max_buffer_size;
        if per_frame > max {
            return Err(Error::Technique {
                technique: Self::INFO.id.into(),
                message: format!(
                    "{} blades need {per_frame} bytes of instance data but this adapter allows buffers of {max} bytes; lower grass.density (or zhang.blades_per_side on the thesis' lattice)",
                    planted.len()
                ),
            });
        }
        let (plants, texture) = plants::Plants::new(&params, scene, layout, &planted);
        let gpu = gpu::PrairieGpu::new(ctx, &params, &plants, &planted, &texture);
        let frame = frame_plan::FramePlan::new(&params, &plants);
        Ok(Self {
            params,
            plants,
            gpu,
            frame,
        })
    }

    fn estimate(scene: &Scene, params: &Params) -> Result<GpuEstimate> {
        Ok(gpu::estimate(params, scene))
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl Zhang {
    /// The animation state (for inspection).
    pub fn animation(&self) -> &Animation {
        &self.plants.blades
    }
}

impl GrassTechnique for Zhang {
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        self.frame.update(&self.params, &mut self.plants, inputs);
        Ok(())
    }

    /// Uploads what this frame animated: the blades and flowers of the grids up to two away
    /// (all of them without LOD) and the far grids' wings.
    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        self.gpu.upload(gpu, &self.frame, &self.plants.blades);
        Ok(())
    }

    /// Without sorting: wings, then the near grids' blade ranges, then petals (all
    /// alpha-tested). Sorting (Sec. 5.4): petals first (alpha-tested, they need no order),
    /// then the wings and the single plants far to near, blended (Eq. 10).
    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        self.gpu
            .encode(encoder, &self.frame, self.params.backbone_points);
    }

    /// Grass grids drawn and culled (Sec. 5.3), single plants drawn, billboards drawn by
    /// length `l'` (Eq. 8), and with far groups the groups drawn and culled.
    fn counters(&self) -> Vec<(&'static str, f64)> {
        let plan = &self.frame.plan;
        let billboards = &self.plants.billboards;
        let mut c = vec![
            ("grids_drawn", plan.grids as f64),
            ("grids_culled", plan.culled as f64),
            ("single_plants", self.frame.blade_count() as f64),
        ];
        let mut by_level = vec![0u64; billboards.steps.len()];
        for f in &plan.far {
            by_level[f.level] +=
                u64::from(billboards.level_of(f.group, f.grid, f.level).billboards);
        }
        let grid_levels = billboards.grid_levels();
        for (&step, &n) in billboards.steps.iter().zip(&by_level).take(grid_levels) {
            c.push((billboard_counter(step), n as f64));
        }
        if !billboards.groups.is_empty() {
            // Far groups (ours): one billboard each.
            c.push(("groups_drawn", plan.groups as f64));
            c.push(("groups_culled", plan.groups_culled as f64));
        }
        c.push(("wings", self.frame.wings.len() as f64));
        c.push(("fading_grids", plan.fading as f64));
        if self.frame.sorted.is_some() {
            c.push(("sort_ms", self.frame.sort_ms));
        }
        c
    }

    /// Blades drawn as single plants (Bezier geometry), and those the billboards drawn stand
    /// for (`billboard_blades`: a billboard stands for the plants growing in its block, each
    /// counted once; a grid fading between both counts as its single plants).
    fn stats(&self) -> TechniqueStats {
        let blades = self.frame.blade_count();
        let flowers = self.frame.plan.flower_count();
        TechniqueStats {
            blades_drawn: blades,
            blades_represented: self.frame.plan.billboard_blades,
            triangles: blades * u64::from(2 * (self.params.backbone_points - 1))
                + 2 * flowers
                + 2 * self.frame.wings.len() as u64,
            gpu_bytes: self.gpu.bytes,
        }
    }

    /// Single plants (Bezier blades) and the blades the billboards drawn stand for.
    fn levels(&self) -> Vec<LevelBlades> {
        vec![
            LevelBlades {
                level: "single_plants",
                blades: self.frame.blade_count(),
            },
            LevelBlades {
                level: "billboards",
                blades: self.frame.plan.billboard_blades,
            },
        ]
    }
}

/// The counter name of billboards of step `step` (`billboards_l5` for `l' = 5`, ...).
fn billboard_counter(step: u32) -> &'static str {
    match step {
        4 => "billboards_l5",
        8 => "billboards_l9",
        16 => "billboards_l17",
        32 => "billboards_l33",
        64 => "billboards_l65",
        128 => "billboards_l129",
        256 => "billboards_l257",
        512 => "billboards_l513",
        _ => "billboards_other",
    }
}
