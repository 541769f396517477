//! Tolerances of the core, each a named, documented constant. Lengths are relative to the
//! bounding-box diagonal of the input unless stated otherwise.

/// Two pattern points closer than this in normalised uv ([0, 1]^2) are duplicates.
pub const DUPLICATE_UV_TOLERANCE: f64 = 1e-9;

/// Principal curvatures whose difference is below this fraction of their magnitude are
/// treated as equal (an umbilic): the principal frame is then Su-aligned.
pub const UMBILIC_RELATIVE_TOLERANCE: f64 = 1e-12;

/// Largest NURBS degree accepted and evaluated: 11, Rhino's limit (openNURBS allows order 12 at
/// most), so that every surface Rhino can make is read and none that Rhino could not. The basis
/// buffers are fixed-size arrays of this length + 1 (no per-call allocation).
pub const MAX_NURBS_DEGREE: usize = 11;

/// [`crate::Discretisation::sanity_check`]: a facet vertex may lie this far (relative to the
/// bounding-box diagonal of the vertices) from its seed's tangent plane. The vertices are
/// computed in that plane, so this only absorbs rounding.
pub const SANITY_PLANARITY_TOLERANCE: f64 = 1e-9;

/// On the convex path, adjacent facet vertices closer than this (relative to the bounding-box
/// diagonal) are tested for an edge reversed by rounding (the weld pass of the facet stage)
/// and welded when it is. Rounding moves a vertex by far less (about 1e-16 times the
/// coordinates times the condition of its three planes); the bound only spares the test on
/// the ordinary edges.
pub const REVERSAL_CHECK_TOLERANCE: f64 = 1e-6;

// ---- read by planes.rs ----

/// Two tangent planes coincide (a flat region, or one ruling of a developable surface) when
/// the sine of the angle between their normals and the distance of each point from the other
/// plane, relative to the distance between the two points, are both at most this. Rounding
/// of one plane's normal at different parameters is about 1e-16; curved neighbours differ by
/// their spacing times their curvature, far more. Coincident neighbours are separated by the
/// perpendicular bisector of their points in the plane (`planes.rs`).
pub const PLANE_COINCIDENCE: f64 = 1e-10;

// ---- read by closed.rs ----

/// Two sides of the domain coincide (a closed direction), or one side is a single point (a
/// pole), when their samples agree to this fraction of the samples' bounding-box diagonal.
/// Rhino closes surfaces exactly (shared control points), so rounding is all it absorbs.
pub const CLOSURE_TOLERANCE: f64 = 1e-9;

/// Samples per side for the closure and pole tests.
pub const LAYOUT_SAMPLES: usize = 17;

// ---- read by periodic.rs (through discretise.rs) ----

/// Seeds within this many mean spacings of a seam get copies across it, so that the
/// structure decided around the seam is the same on both sides before it is folded
/// (`periodic.rs`); at most half the period.
pub const PERIODIC_BAND: f64 = 6.0;

/// Cut positions tried on either side of the seam when folding the periodic structure
/// (`periodic.rs`), spread over half the band.
pub const PERIODIC_CUTS: usize = 8;

/// Four points around an edge count as cocircular when their in-circle determinant is at most
/// this times the quad's size to the fourth power (its scale): mirrored ghosts make exact and
/// rounded ties, broken the same way on both sides of the seam (`periodic.rs`).
pub const PERIODIC_TIE: f64 = 1e-10;

/// Rounds of the tie breaking over all edges (each round flips only ties).
pub const PERIODIC_TIE_ROUNDS: usize = 8;

/// Seeds whose normal makes at most acos of this with a pole's axis (the mean normal of the
/// ring of seeds round it) take part in the envelope flips around the pole (`periodic.rs`):
/// within 60 degrees, the plane normal to the axis charts a convex cap one to one.
pub const POLE_CAP_COSINE: f64 = 0.5;

/// Envelope flips allowed around a pole, per triangle of the structure: a bound that the
/// flips (each lowering the envelope) never reach, kept so that rounding cannot loop them.
pub const POLE_CAP_FLIPS: usize = 4;

// ---- read by rulings.rs ----

/// A surface's parameter lines are its rulings when, at the layout samples, the normals along
/// each line agree (sine of their angle) and its points lie on one straight line (relative to
/// the samples' bounding-box diagonal) to this. Rounding of exact cylinders and cones is about
/// 1e-15; a surface curved along the lines by 1e-9 of its size is not developable there.
pub const RULING_TOLERANCE: f64 = 1e-9;

/// A seed on the end of its ruling, or closer to it than this fraction of the scale
/// |end point| + |ruling length|, gets its end ghost that far beyond the end wall: nearer, the
/// rounding of the two points (about 1e-16 of their magnitude) would exceed
/// [`PLANE_COINCIDENCE`] of their distance and their planes would no longer count as one.
/// Its strip then ends at most this far beyond the wall.
pub const STRIP_END_MIN_DEPTH: f64 = 1e-6;

/// On a trimmed developable surface the strips' end and side walls move this fraction of the
/// surface's bounding diagonal beyond the domain, so that every vertex on a wall lies
/// clearly outside the trim (whose loops may run along the domain's edges) and the facet
/// stage clips each strip on the trim's wall instead.
pub const STRIP_TRIM_MARGIN: f64 = 0.02;

// ---- read by polysurface.rs ----

/// Two faces of a polysurface share a side when their points at the same parameter along it
/// agree to this fraction of the bounding-box diagonal of all faces (at [`EDGE_MATCH_SAMPLES`]
/// parameters). Rhino joins faces to the model's absolute tolerance, typically 1e-3 mm on
/// models metres across, about 1e-7 of the size; this allows ten times more.
pub const EDGE_MATCH_TOLERANCE: f64 = 1e-6;

/// Samples per side when comparing the sides of two faces, and for the faces' mid-line
/// lengths that set the columns' widths.
pub const EDGE_MATCH_SAMPLES: usize = 9;

// ---- read by analytic.rs ----

/// Largest magnitude accepted for any analytic parameter or rectangle coordinate. Far beyond
/// any model (in any unit), and small enough that no product or square in the formulas
/// overflows, so that evaluation never meets inf - inf or inf / inf.
pub const MAX_ANALYTIC_MAGNITUDE: f64 = 1e50;

/// Smallest radius or semi-axis accepted: keeps the cubes of square roots in the second
/// derivatives clear of underflow.
pub const MIN_ANALYTIC_LENGTH: f64 = 1e-50;

// ---- read by discretise.rs ----

/// Default weld distance of coincident vertices, relative to the bounding-box diagonal.
pub const DEFAULT_WELD_TOLERANCE: f64 = 1e-10;

/// Default flatness threshold: a point is flat when |K| <= this * max(k1^2, k2^2), or when
/// both curvatures are below [`DEFAULT_PLANE_CURVATURE`] / diagonal.
pub const DEFAULT_FLAT_TOLERANCE: f64 = 1e-6;

/// Curvature (times the bounding-box diagonal) below which a point counts as planar.
pub const DEFAULT_PLANE_CURVATURE: f64 = 1e-9;

/// Points whose twice-signed triangle area with the pattern's longest chord from its first
/// point is below this fraction of the chord's squared length count as collinear.
pub const COLLINEAR_TOLERANCE: f64 = 1e-12;

// ---- read by facets.rs ----

/// A triangle vertex farther than this many times the triangle's longest side from the
/// triangle's centroid is ill-conditioned (nearly parallel planes), unless it is an outside
/// vertex of a triangle at the boundary.
pub const DEFAULT_FAR_VERTEX_FACTOR: f64 = 8.0;

/// Interior sample count used to detect an edge that dips into the domain between two
/// outside endpoints.
pub const OUTSIDE_SEGMENT_SAMPLES: usize = 8;

/// A point of a facet edge counts as inside the domain only if its distance from the surface
/// is at most this fraction of its distance from the edge's two pattern points (a facet of
/// size r deviates about k r^2 / 2 from the surface, far less for any sensible panel size).
pub const NEAR_SURFACE_RATIO: f64 = 0.25;

/// Regula falsi iterations for a boundary crossing.
pub const CROSSING_ITERATIONS: usize = 80;

/// A boundary crossing is converged when |inside measure| falls below this (normalised).
pub const CROSSING_TOLERANCE: f64 = 1e-13;

/// A crossing search that ends farther than this from the boundary (normalised) has failed.
pub const CROSSING_ACCEPTANCE: f64 = 1e-9;

/// On a trimmed surface, a trim corner within this arclength (normalised parameters) of a
/// boundary crossing along its loop is that crossing: no vertex of its own.
pub const CORNER_ON_CROSSING: f64 = 1e-9;

/// Where a facet's exit crossing and its next entry crossing lie within this arclength
/// (normalised parameters) of each other along their loop, the entry counts as at the exit
/// even when rounding puts it just behind: an edge that grazes the wall (common on saddles,
/// where facet edges run along the boundary) leaves and re-enters at one point, and must not
/// send the clipped facet once around the whole loop.
pub const GRAZING_CROSSING_SLACK: f64 = 1e-9;

/// Facets clipped on the wall on the any-curvature path: a boundary crossing or corner within
/// this fraction of the mean seed spacing (the bounding diagonal over sqrt(2 n)) of its
/// neighbour in every facet that holds it is merged into that neighbour. The crossing lies on
/// the line of the edge it ends, so the merge keeps every facet exactly planar; the mesh's edge
/// then leaves the wall by at most this much. Without it, a triangle vertex just inside the
/// wall and the crossing just beyond it give a boundary edge thousands of times shorter than
/// the spacing, which the panels' offset (fabrication) cannot follow.
pub const WALL_CLIP_SHORT_EDGE: f64 = 0.01;

/// Quarter-side steps a vertex of a triangle with a ghost that lies inside the region may be
/// moved along its real facets' common line to get past the wall (`facets::extend_to_wall`):
/// at most three quarters of the triangle's longest side. A line that needs farther runs
/// nearly along the wall, and its crossing would be near another side or corner, not at the
/// notch (on samples/saddle.json, moves of 2.5 and 3 sides sent facets around a corner).
pub const WALL_EXTENSION_STEPS: usize = 3;

/// Quarter-side steps a vertex of a triangle with two ghosts (a vertex of one real facet
/// alone) that lies inside the region may be moved along the bisector of the ghosts' wedge,
/// within that facet's plane, to get past the wall (`facets::extend_to_wall`): at most two
/// of the triangle's longest sides. Only that facet's edges on the mesh's edge move. On
/// saddle regions of mixed surfaces the first row of facets along a side can end in a spike
/// reaching a spacing into the region; its vertex needs about a side to get out (a hex
/// pattern of 2000 points on a seeded mixed surface: 3.2 quarter sides), and left inside
/// the spike crosses its neighbour's edge (a non-simple facet). Exact planes only (with
/// adjusted ones such a vertex keeps [`WALL_EXTENSION_STEPS`]).
pub const WALL_EXTENSION_OWN_STEPS: usize = 8;

/// A vertex of a triangle with a ghost is moved out past the wall (`facets::extend_to_wall`)
/// only when its foot lies deeper inside than this fraction of the triangle's reach (the
/// normalised distance of its points from the vertex's first-order foot, about one spacing):
/// nearer the wall the notch is negligible, and whether the vertex is inside at all is decided
/// by rounding (a grid on a hypar puts vertices on the wall), which must not change the mesh
/// between one face and the same face split into a polysurface.
pub const WALL_EXTENSION_MIN_DEPTH: f64 = 0.05;

/// Rounds of facets extended to the wall (`facets::extend_to_wall`) that came out invalid
/// getting their ghost's end back: each round blocks the moves at the facets still invalid
/// and clips again.
pub const WALL_EXTENSION_ROUNDS: usize = 3;

/// Tries of a hybrid clip on the wall (`facets::WallClip::clip`) where the whole clip does
/// not keep the closed facets' shape: the facets to blame keep their closed fans, with a ring
/// of neighbours more after each try that fails; after the last the closed facets are kept
/// everywhere.
pub const WALL_CLIP_HYBRID_ROUNDS: usize = 4;

/// Rounds of wall flips (`facets::wall_flips`): each visits every triangle with a ghost whose
/// vertex stays inside the region.
pub const WALL_FLIP_ROUNDS: usize = 4;

/// Tries of the wall flips (`facets::wall_flips`) before the triangulation is clipped as the
/// validity flips left it: after each try whose clip does not keep the closed facets' shape
/// or leaves a facet near a flip invalid, the flips near those facets are refused.
pub const WALL_FLIP_RETRIES: usize = 3;

/// A wall flip (`facets::wall_flips`) is refused when the largest distance from the surface
/// of the vertices of the facets it can change, clipped on the wall with the flips, exceeds
/// the same facets' largest distance in the unflipped clip by more than this many mean
/// spacings (diagonal / sqrt(2 n)): rounding only, no flip may raise the deviation.
pub const WALL_FLIP_DEVIATION_SLACK: f64 = 1e-9;

/// A wall flip (`facets::wall_flips`) is refused when a corner of the boundary within this
/// many mean spacings of the mesh's edge along the facets it can change lies farther from
/// that edge after the flips than before (by more than [`WALL_FLIP_DEVIATION_SLACK`]
/// spacings): the corner cut off.
pub const WALL_FLIP_CORNER_REACH: f64 = 1.0;

/// Pieces each edge of the mesh's edge is sampled in for its notch after a wall flip
/// (`facets::Notch`: the area between it and the wall, and its depth).
pub const WALL_FLIP_NOTCH_SAMPLES: usize = 4;

/// A wall flip (`facets::wall_flips`) is refused when the notch of the mesh's edge along the
/// facets it can change, clipped with the flips, exceeds the unflipped clip's in area or
/// depth by more than this (normalised parameters): rounding only. The flips' own score is
/// the notch of the chain before the clip, which does not see what the clip does at a
/// corner (on a square hypar, hex patterns, a flip that closed a notch beside a corner cut
/// the corner off).
pub const WALL_FLIP_NOTCH_SLACK: f64 = 1e-12;

/// A facet near a wall flip whose clipped polygon's area is below this fraction of the
/// squared mean spacing (diagonal / sqrt(2 n)) counts as invalid, and the flips near it are
/// refused (`facets::WallClip`): on a hypar the planes along a ruling meet in it, and a flip
/// there can leave a facet collapsed onto the ruling (three collinear vertices).
pub const WALL_FLIP_MIN_AREA: f64 = 1e-3;

/// Doublings of the step when following a hull ray outwards.
pub const RAY_DOUBLINGS: usize = 60;

/// An outside segment end farther than this many neighbour spacings is not used directly:
/// the line is followed from the inside end instead.
pub const RAY_FAR_FACTOR: f64 = 16.0;

/// On the ghost-closed path, a vertex farther than this many triangle sides from its
/// triangle's centroid (or not finite) is unreachable: its facets get stand-ins on their edge
/// lines instead (leaving a small hole); nearer far vertices stay exact and are diagnosed.
pub const UNREACHABLE_VERTEX_FACTOR: f64 = 1e6;

/// With exact planes on the any-curvature path, a facet of real points alone (one closed by a
/// ghost is clipped at the wall later) whose vertices lie farther from its seed than this
/// many times the seeds' bounding-box diagonal, or than [`RUNAWAY_SPACINGS`] local spacings,
/// has run away (no facet of the surface reaches beyond the whole surface; a strip along the
/// rulings of a nearly developable band spans it at most). Where the validity flips leave
/// such facets, they run again from the same triangulation counting them as invalid, and that
/// outcome is kept if it leaves no more invalid facets and fewer runaways, or fewer facets
/// invalid or runaway, and no facet reaching farther (`validity_flips`). Not with adjusted
/// planes, whose adjustment holds every facet within [`MAX_REACH`] local spacings.
pub const RUNAWAY_REACH: f64 = 1.0;

/// With exact planes on the any-curvature path, a triangle whose vertex T_i ∩ T_j ∩ T_k lies
/// farther than this many local spacings (the mean distance from a seed to its neighbours'
/// seeds) from one of its seeds has run away: the validity search's facets reaching farther
/// count as runaways, and the last pass of the search flips such triangles away where the
/// summed excess over this limit drops and no more facets are invalid
/// (`validity_flips::bring_in_runaways`). A valid facet reaches about one spacing (its
/// vertices are the circumcentres of its seed and two neighbours); the quality report flags a
/// vertex beyond [`FAR_VERTEX_SPACINGS`] (the same 3) off the surface. The mixed roof's
/// showcase (samples/mixed-roof.json, hex:30x24) went from a vertex 18 spacings off to 0.5.
pub const RUNAWAY_SPACINGS: f64 = 3.0;

/// The excess in spacings counted for a triangle whose vertex is unreachable (parallel planes):
/// finite, so that sums of excess stay comparable.
pub const UNREACHABLE_RUNAWAY_SPACINGS: f64 = 1e6;

/// A flip that brings runaway vertices in is kept only when their summed excess (in local
/// spacings) drops by more than this: rounding never keeps a flip.
pub const RUNAWAY_EXCESS_MARGIN: f64 = 1e-9;

// ---- read by ghosts.rs ----

/// Width of the band of seeds mirrored across each side, in mean pattern spacings
/// sqrt(area / n) of the triangulation's plane.
pub const GHOST_BAND: f64 = 3.0;

/// A ghost lies at least this many mean spacings beyond its side, so that a seed on the side
/// (or very near it) still gets a ghost apart from itself; see `ghosts::ghost_depth`.
pub const GHOST_MIN_DEPTH: f64 = 0.25;

/// A flat seed (zero Gaussian curvature) at least this many mean spacings inside its side is
/// mirrored exactly across it (`ghosts::augment`), so that its facet ends on the side.
pub const GHOST_FLAT_MIRROR: f64 = 0.02;

// ---- read by neighbours.rs ----

/// Real points a Lawson flip's connectivity guard visits at most from each end of the edge it
/// would remove (`neighbours::isolates_real_points`): a group of real points cut off by ghosts
/// near a corner is a few seeds, while an end that reaches this many real points lies in the
/// body of the mesh.
pub const REAL_LINK_SEARCH: usize = 64;

/// Weight of the isotropic term that keeps the compensation metric definite: each point
/// contributes |II| + METRIC_REGULARISATION max(|k1|, |k2|) I (largest |k| over the quad), so
/// that the metric never degenerates where one principal curvature vanishes.
pub const METRIC_REGULARISATION: f64 = 0.05;

/// Where 1 to [`RETRY_MAX_INVALID`] facets are left invalid on an open patch or a trim
/// (after the validity flips with exact planes, after the plane adjustment with adjusted
/// ones), the neighbours are decided (and the planes adjusted) again with these weights of
/// the isotropic term in turn, until none is left; the attempt with the fewest left is kept
/// (the first of equals). Near a parabolic line, and on strongly anisotropic saddles, the
/// weight decides how long the facets run along the flat direction, and which facets neither
/// flips nor tilts of 5 degrees repair (`structure::decide_again`).
pub const METRIC_REGULARISATION_RETRIES: &[f64] = &[0.15, 0.3, 0.5];

/// The most facets left invalid for which the neighbours are decided again
/// ([`METRIC_REGULARISATION_RETRIES`]): more are left where neither flips nor tilts help (a
/// nearly developable band, exact planes across a parabolic line), and another weight does
/// not change that.
pub const RETRY_MAX_INVALID: usize = 8;

/// Milliseconds a plane adjustment runs before the first attempt of a second decision starts
/// beside it (`structure::any_curvature`; the attempt is dropped if the adjustment leaves
/// none). Most adjustments end sooner and none follows; run beside one of them the attempt
/// only took the second core from the adjustment's parallel parts (samples/mixed28 with
/// 2,000 random points: 1.15 -> 1.32 s). Where a second decision follows, the adjustment
/// took 4 to 9 s at 2,000 points.
pub const SPECULATION_DELAY_MS: u64 = 1000;

/// The isotropic term where all four points of a quad are flat (K = 0 with one curvature
/// left: a developable surface). Small, so that the triangulation follows the limit of TPI as
/// the curvature along the rulings vanishes: the planes (which differ across the rulings)
/// decide first, and only points on one ruling, whose planes coincide, are paired by their
/// distance along it (`planes::meeting_point`).
pub const DEVELOPABLE_METRIC_REGULARISATION: f64 = 1e-4;

/// On strictly convex surfaces off the slope-space path, the isotropic term is this fraction
/// of the summed metric's trace (the envelope test decides after it anyway).
pub const CONVEX_METRIC_REGULARISATION: f64 = 1e-3;

/// A vertex must lie this far (relative to the quad's size) outside a half-space before
/// the envelope test flips: ties (four planes through one point, e.g. a square grid on a
/// paraboloid of revolution) are left alone.
pub const ENVELOPE_FLIP_TOLERANCE: f64 = 1e-10;

/// A hull triangle whose vertex lies farther than this many times its size from its points
/// is numerically degenerate (its points are collinear to rounding) and is trimmed.
pub const DEGENERATE_SLIVER_FACTOR: f64 = 1e8;

/// Smallest cosine between any normal and the mean normal for which a convex surface is
/// treated as a graph over the plane of the mean normal (see `neighbours::gradient_embedding`).
pub const GRADIENT_MIN_COS: f64 = 0.2;

/// Samples per side of the grid whose mean normal is the slope frame's N.
pub const SLOPE_FRAME_SAMPLES: usize = 5;

/// Relative size of the in-circle determinant (against the quad's squared size, squared)
/// below which the compensation test counts four points as cocircular.
pub const COMPENSATION_TIE_TOLERANCE: f64 = 1e-10;

// ---- read by pattern.rs ----

/// Smallest Poisson-disk radius (in normalised units): about 1.3 million points at most.
pub const MIN_POISSON_RADIUS: f64 = 1e-3;

// ---- read by projection.rs ----

/// Newton iterations for a projection (quadratic convergence: 3 to 5 are typical).
pub const MAX_PROJECTION_ITERATIONS: usize = 16;

/// Stop when the Newton step is below this, in normalised parameters.
pub const PROJECTION_STEP_TOLERANCE: f64 = 1e-14;

/// The quality report's projections (deviation) stop after a full-Newton step below this, in
/// normalised parameters: the foot is then off by O(1e-10) and the distance by O(1e-20)
/// (`projection::distance_foot`).
pub const DISTANCE_FOOT_STEP_TOLERANCE: f64 = 1e-5;

/// ... provided the point is this far from the focal surface: (1 - k1 d)(1 - k2 d), the
/// ratio of the full Newton Hessian's determinant to the metric's, at least this.
pub const DISTANCE_FOOT_MIN_FOCAL_FACTOR: f64 = 0.25;

/// A projection that only decides whether a point's foot is outside the domain
/// (`projection::outside_foot`: the facet stage's samples of an edge both of whose ends are
/// outside, the far end of an edge leaving the domain, and the march out along a hull ray;
/// there the foot serves only as the next projection's start) stops once two consecutive Newton steps
/// shrink at least by this factor, q = s_k / s_(k-1) <= 1/2 (the iterates then move by at
/// most s_k q / (1 - q) <= s_k more, for a contraction that holds on) ...
pub const SIDE_DECISION_MAX_CONTRACTION: f64 = 0.5;

/// ... and the current iterate lies outside the domain by more than this multiple of the last
/// step s_k (normalised): four times the estimated remaining movement, so that the estimate
/// may be off by that factor before a sign could change.
pub const SIDE_DECISION_SAFETY: f64 = 4.0;

/// Normalised distance from a pole side within which the report's projection, having
/// stopped there, starts again half a turn round the pole and keeps the nearer foot
/// (`projection::Wrap::across_pole`): the Jacobian vanishes at a pole, and Newton may stop
/// on the wrong side of it.
pub const POLE_RESTART_BAND: f64 = 0.1;

// ---- read by quality.rs ----

/// A vertex within this fraction of an edge's length of the edge's line counts as on it in
/// the separating-line test of `quality::edge_pair_overlaps` (the full test then decides).
pub const SEPARATION_MARGIN: f64 = 1e-9;

// ---- read by adjusted_planes.rs ----

/// Largest tilt of an adjusted plane against the exact tangent plane at its seed, in degrees
/// (`--planes adjusted`). A facet tilted more would stray visibly from the surface's shading.
pub const MAX_PLANE_TILT_DEGREES: f64 = 5.0;

/// The tilts tried, smallest first (degrees, each at most [`MAX_PLANE_TILT_DEGREES`]): the
/// first that helps is kept, so a plane is tilted by about the least amount that works.
pub const PLANE_TILT_STEPS_DEGREES: &[f64] = &[0.25, 0.5, 1.0, 2.0, 3.5, 5.0];

/// The tilts tried together with a flip that does not pay by itself (degrees).
pub const RESCUE_TILT_STEPS_DEGREES: &[f64] = &[1.0, 2.5, 5.0];

/// The offsets of a plane along its exact normal tried where no tilt helps, as fractions of
/// the local spacing of the seeds, smallest first.
pub const PLANE_OFFSET_STEPS: &[f64] = &[0.01, 0.02, 0.05, 0.1];

/// Directions of tilt tried per step, evenly spaced around the exact normal.
pub const PLANE_TILT_DIRECTIONS: usize = 8;

/// A tilt that leaves as many invalid facets around it is still kept when it brings their
/// farthest vertices (relative to the local spacing, summed) to less than this fraction.
pub const REACH_GAIN: f64 = 0.9;

/// With adjusted planes a facet whose vertices lie farther than this many local spacings
/// (mean distance to the neighbouring seeds) from its seed counts as invalid, so that
/// runaway vertices at parabolic lines are pulled in too.
pub const MAX_REACH: f64 = 2.5;

/// Where the adjustment with [`MAX_REACH`] (and its second decisions) leaves facets invalid,
/// the whole adjustment is tried again with this reach, and kept only if it leaves none.
/// On a nearly developable band (K ~ 0 with one principal curvature left) exact TPI facets
/// run along the rulings by several spacings, the flat direction of the |II| metric, and
/// such a long facet lies close to the surface; holding its vertices within 2.5 spacings
/// asks tilts of at most 5 degrees for what they cannot do, and the search then misses the
/// simple, long facet that is there.
pub const FALLBACK_REACH: f64 = 6.0;

/// The adjustments with [`FALLBACK_REACH`] (one per weight of the isotropic term) stop after
/// one that leaves more than this many facets invalid: the escalated restarts did not even
/// start there ([`ESCALATION_MAX_INVALID`]), so that weight and reach are far from a valid
/// mesh, and a failing mesh of 2,000 points spends about 2 M plane changes per adjustment.
/// On the mixed seeds 0-23 no fallback succeeded after such an adjustment; the hopeless
/// meshes (a nearly developable surface with a grid) were spared two or three.
pub const FALLBACK_GIVE_UP: usize = ESCALATION_MAX_INVALID;

/// Random restarts tried around each facet the greedy plane adjustment left invalid.
pub const PLANE_KICKS: usize = 24;

/// Passes of greedy tilts after each random restart.
pub const KICK_REPAIR_PASSES: usize = 4;

/// Passes of random restarts over the facets still invalid at most (another pass only when
/// the last kept one: a kept restart changes the neighbourhood of others).
pub const KICK_ROUNDS: usize = 4;

/// Rounds of plane adjustment at most (each round visits every invalid facet once).
pub const MAX_PLANE_ADJUST_ROUNDS: usize = 40;

/// The plane adjustment stops after this many plane changes (tried or kept) per facet
/// judged, about 10 ms of work per facet. The mixed roof with 2,000 uniform random points
/// needs about 106 per facet and is not cut; real faces with many invalid facets (a head, a
/// car body) use up to 2,500 and come out slightly worse; where tilts cannot help (a
/// developable surface with random seeds, hundreds of invalid facets) the search would
/// otherwise run for minutes (500 points: 1.6 s instead of 170 s).
pub const PLANE_ADJUST_BUDGET: usize = 1000;

/// The plane adjustment also stops after this many plane changes per facet invalid when it
/// starts (whichever bound is lower). Measured needs: up to about 12,700 (the torus band with
/// 2,000 uniform random points, 14 facets invalid at the start), 9,800 on the mixed roof
/// (10,000 random points, 427 invalid); where tilts cannot help (a mug's nearly cylindrical
/// body, hex 40 x 40, 49 facets invalid) the judged-facet bound alone let the search run for
/// 30 s to repair 8 of them.
pub const PLANE_ADJUST_BUDGET_PER_INVALID: usize = 20_000;

/// The escalated restarts (`crate::adjusted_planes`) run only where the kick rounds leave at
/// most this many facets invalid: a few stubborn facets at a parabolic line (the mixed roof
/// with hex 300 at 30 degrees, 2 left), not a surface where tilts cannot help (a mug's nearly
/// cylindrical body leaves dozens).
pub const ESCALATION_MAX_INVALID: usize = 8;

/// Rounds of escalated restarts at most (each a new series per facet still invalid).
pub const ESCALATION_ROUNDS: usize = 8;

/// Random restarts per facet and escalation round.
pub const ESCALATION_KICKS: usize = 16;

/// The escalated restarts stop after this many plane changes per facet invalid when they
/// begin, on top of what the kick rounds spent.
pub const ESCALATION_BUDGET_PER_INVALID: usize = 150_000;

/// Flips towards the isotropic Delaunay triangulation around a facet at most, per
/// restructuring move of the escalation (`crate::adjusted_planes`).
pub const RESTRUCTURE_FLIPS: usize = 24;

/// The restructuring flips ([`RESTRUCTURE_FLIPS`]) leave four points alone whose in-circle
/// determinant is at most this times the quad's edge length to the fourth power: cocircular
/// up to rounding (a square grid), where a flip would only follow rounding.
pub const ISOTROPIC_FLIP_TIE: f64 = 1e-9;

/// A facet whose farthest vertex stands farther from the surface than this many times its
/// local spacing (the mean distance from its seed to the seeds of the facets it shares an
/// edge with) is flagged `FLAG_FAR_VERTEX` by the quality report, which counts such facets;
/// the CLI, the Grasshopper component and the Rhino command warn about them. A
/// TPI vertex deviates about k r^2 / 2 for a facet of circumradius r, so on a convex patch a
/// vertex stays within about one spacing even where a facet spans a radian of the surface;
/// farther ones are runaways of nearly parallel planes, at a parabolic line or at seeds close
/// together, with exact planes (samples/mixed-roof.json with `random:2500`: 49.7 units off a
/// diagonal of 23.6; samples/saddle.json with samples/random-1000.json: 4.0, 8 spacings).
pub const FAR_VERTEX_SPACINGS: f64 = 3.0;

// ---- read by validity_flips.rs ----

/// Rounds of validity flips at most (each round visits every invalid facet once).
pub const MAX_VALIDITY_ROUNDS: usize = 8;

/// Passes of single-flip repairs around a detour flip of the validity repair (a flip kept
/// only together with the repairs it allows): `validity_flips.rs`.
pub const DETOUR_REPAIR_PASSES: usize = 3;

/// Detour flips the validity repair may try: this many per judged point plus
/// [`DETOUR_BUDGET_FLOOR`] (counted, so the result stays deterministic). Hex, grid and
/// Poisson-disk patterns on saddles seldom need more; uniform random points, where many
/// facets cannot be repaired with exact planes, stop here.
pub const DETOUR_BUDGET: f64 = 0.1;

/// Detour flips every run may try whatever its size (small patterns have few facets to
/// spread the search over).
pub const DETOUR_BUDGET_FLOOR: usize = 100;

/// Work the validity repair's detours may spend, per judged point (counted in edges of
/// polygons built and products of edge counts of pairs tested for overlap, from the start
/// of the detours): `validity_flips.rs`.
/// Saddles, torus bands and mixed roofs with hex, grid, Poisson-disk and uniform random
/// patterns of 1k-10k points spend at most 1,200 per point in all, so this never binds
/// there; a pattern made dense around runaway vertices (fans of 150 triangles) spent 44,600
/// per point (16 s for 4,249 points).
pub const DETOUR_WORK_BUDGET: u64 = 4_000;

/// Pair detours (two star or link edges of an invalid facet flipped together, then repairs)
/// the validity repair may try after the single detours: this many per judged point plus
/// [`PAIR_DETOUR_BUDGET_FLOOR`] (counted; the detours' work budget binds them too). Poisson-disk
/// patterns on saddles leave a few facets, mostly within a few spacings of the boundary, that
/// need two flips before any repair pays.
pub const PAIR_DETOUR_BUDGET: f64 = 0.5;

/// Pair detours every run may try whatever its size.
pub const PAIR_DETOUR_BUDGET_FLOOR: usize = 400;

/// Pair detours run only where the single detours leave at most this many invalid facets:
/// on uniform random points (dozens left) pair detours on the mixed roof traded invalid
/// facets for facets reaching beyond 3 spacings that the plane adjustment then could not
/// pull in (7 of them at random:1000).
pub const PAIR_DETOUR_MAX_INVALID: usize = 8;

/// Pair detours tried for one invalid facet whose ring holds seeds of both signs of Gaussian
/// curvature (a parabolic line through it; `validity_flips.rs`). With exact planes most of
/// those stay invalid whatever is flipped: without a limit each took 250 tries (the median)
/// before giving up, while those repaired took 12 (90 % within 116). On the 72 meshes of 300
/// points of `mixed_sweep 12 0 300` (exact planes) the limit took the invalid facets from
/// 643 to 632 (the tries saved go to other facets; the next 12 seeds 1061 -> 1063, 2,000
/// points 2100 both) and the CLI's time on them by 5 %; on surfaces of one sign of K
/// (saddles, domes) it never applies.
pub const PAIR_DETOUR_PARABOLIC_TRIES: usize = 40;

/// Detour work every run may spend whatever its size.
pub const DETOUR_WORK_BUDGET_FLOOR: u64 = 2_000_000;

/// Relative tolerance of the local validity tests: orientations smaller than this times the
/// squared size of the polygons count as collinear, distances smaller than this times the
/// size as zero (rounding of the three-plane vertices is far below it).
pub const VALIDITY_TOLERANCE: f64 = 1e-9;

// ---- read by fabricate/ ----

/// Two facet planes whose unit normals differ by less than this (|m_i - m_j|) count as
/// parallel: their bisector plane is undefined, and the side face between them is cut square
/// to the panel instead of mitred (named by a diagnostic).
pub const FABRICATION_PARALLEL_TOLERANCE: f64 = 1e-9;

/// Three side and offset planes whose 3 x 3 determinant is below this count as dependent
/// (collinear boundary edges): the offset vertex is then taken from two of them.
pub const FABRICATION_SINGULAR_TOLERANCE: f64 = 1e-12;

/// A top edge shorter than this fraction of the bounding-box diagonal counts as zero-length
/// (the split of a vertex where more than three panels meet): it is not checked for
/// collapse and gets no slot.
pub const FABRICATION_SHORT_EDGE: f64 = 1e-12;

/// Flat outline vertices closer than this (relative to the bounding-box diagonal) are one
/// vertex of the cut outline: nesting and the tool-radius offset need edges with a direction.
/// The same distance decides whether a bottom vertex lies outside the top outline.
pub const FABRICATION_OUTLINE_MERGE: f64 = 1e-9;

/// A panel clipped where a bottom edge collapsed (thickness beyond the edge's limit) is the
/// intersection of its half-spaces: a point within this fraction of the bounding-box diagonal
/// of a plane counts as on it (vertices of the cell, faces of the solid), and two cell vertices
/// closer than it are one. Rounding of the three-plane vertices is far below it.
pub const FABRICATION_CLIP_TOLERANCE: f64 = 1e-11;

/// Largest number of panels walked around one vertex before the walk counts as broken
/// (a non-manifold mesh): far above any real valence.
pub const FABRICATION_MAX_VALENCE: usize = 64;

/// Default slot (cleat notch) length along the edge, in panel thicknesses.
pub const DEFAULT_SLOT_LENGTH_FACTOR: f64 = 4.0;

/// Default slot depth into each panel, in panel thicknesses.
pub const DEFAULT_SLOT_DEPTH_FACTOR: f64 = 2.0;

// ---- read by align.rs ----

/// Two points of an aligned lattice are never closer than this, in lattice units (the
/// lattice's own step is 1) measured in the frame at the newer point: proposals of the same
/// lattice site from different parents merge, and a gap wider than 1 + this is filled.
pub const ALIGN_MIN_SEPARATION: f64 = 0.8;

/// Below this fraction of the surface's largest principal curvature a node counts as flat
/// and its lattice is regular on the surface (the curvature no longer decides its facets).
pub const ALIGN_FLAT_CURVATURE: f64 = 1e-3;

/// Largest angle (degrees) of an aligned hexagonal lattice's triangle seen through the
/// curvature metric |II|^(1/2): below 90 the triangle is the |II|-Delaunay one the
/// discretiser picks, so the facet edges are the conjugates the lattice was built for.
pub const ALIGN_MAX_TRIANGLE_ANGLE_DEG: f64 = 80.0;

/// Largest departure (degrees) from a right angle of an aligned square lattice's cell seen
/// through |II|^(1/2).
pub const ALIGN_MAX_SHEAR_DEG: f64 = 30.0;
