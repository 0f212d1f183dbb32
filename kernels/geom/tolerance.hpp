#pragma once
// Every tolerance of ncpath, in one place: name, unit and purpose (STYLE.md habit 5).
// Kernels take these as defaulted parameters; nothing else hard-codes an epsilon.

namespace ncpath::tol {

// mm. Two drop-cutter heights closer than this are "the same" height. The exactness
// contract (accelerated result == brute force) is stated with this tolerance.
inline constexpr double kExactZ = 1e-9;

// mm. Convergence target of numeric contact solvers (bull-nose edge contact): the returned
// tip height is within this of the true maximum.
inline constexpr double kContactSolve = 1e-10;

// mm^2. A facet whose doubled xyz area (|e1 x e2|) is below this is degenerate: it has no
// normal, is skipped by the readers and counted in the statistics.
inline constexpr double kDegenerateArea2 = 1e-18;

// Dimensionless. A facet whose unit normal has |n_z| below this is treated as vertical: it
// has no facet contact with a tool dropped along -Z; its edges and vertices still do.
inline constexpr double kVerticalNormalZ = 1e-12;

// Dimensionless. Relative padding added to float boxes handed to Embree so that float
// rounding can never drop a candidate that double precision would keep.
inline constexpr double kFloatBoxPad = 1e-5;

// mm. A culling bound (tangent plane, profile rise) within this of the best tip so far
// counts as not above it. Bounds are evaluated differently from the kernel, so at exact
// ties (coplanar neighbours of the contact facet) rounding decides; dismissing them costs
// at most this much height, far below kExactZ.
inline constexpr double kBoundTie = 1e-12;

// Dimensionless, relative to the coordinates' magnitude. Slack added when an interval is
// mapped to grid cells (strips, bins) so that rounding can add a cell, never drop one.
inline constexpr double kCellSlack = 1e-9;

// Dimensionless, relative to the polygon's size (longest side of its bounding box). A polygon
// edge shorter than this fraction of the size has zero length: the polygon is rejected as
// not strictly convex (the OFF reader's polygon check).
inline constexpr double kPolygonZeroEdge = 1e-12;

// Dimensionless. A polygon vertex whose turn has |sin(angle)| below this, and that keeps
// going forward, is straight (collinear with its neighbours): it is not a corner, so it is
// neither a turn of the wrong sign nor the apex of a zero-area fan triangle. Likewise a
// polygon whose doubled Newell area is below this times size^2 has no plane (degenerate).
inline constexpr double kPolygonStraightTurn = 1e-12;

// Dimensionless. Added to extent / spacing before rounding down when counting samples, so
// that an extent which is a multiple of the spacing up to rounding (200 / 0.1) keeps its
// last sample.
inline constexpr double kCountSlack = 1e-9;

// mm. Planar offsetting: points closer than this are the same point (intersections,
// joins, stitching of offset pieces), and a point counts as lying on a segment within it.
inline constexpr double kOffsetPoint = 1e-9;

// mm. Two consecutive offset segments share their joint; a computed crossing of theirs
// within this of the joint is that joint seen through rounding (near-tangent crossings are
// ill-conditioned: an error of sqrt(rounding * radius) reaches 1e-7 mm on flat arcs), not
// a self-intersection.
inline constexpr double kOffsetJoint = 1e-6;

// mm. Result loops drop segments shorter than this (slivers left between crossings a few
// micrometres apart, or joins of corners of a few micro-radians) by moving the next joint
// onto the previous one. They would turn back on themselves one offset later.
inline constexpr double kOffsetSliver = 1e-5;

// mm. An offset piece is kept when its distance to the curves it was offset from is at
// least the offset distance minus this. Exact offsets sit at the distance to rounding
// (~1e-13 mm); anything that comes closer by more than this is cut away.
inline constexpr double kOffsetValid = 1e-7;

// mm. A piece of a crude offset loop that comes closer than the offset distance to the input
// by less than this is a marginal miss: its run's validity is then decided by most of the
// run's length, not by that piece alone (kernels/pocket/offset_dissect.cpp).
inline constexpr double kOffsetMarginal = 1e-3;

// mm. Default join tolerance of chain_and_nest (kernels/pocket/chain.hpp): curve end points
// closer than this are the same profile vertex and are snapped together exactly, so that loops
// chain bitwise. Covers the rounding of coordinates written by CAD systems with ~15 digits.
inline constexpr double kProfileJoin = 1e-6;

// mm. Documented larger join tolerance for sloppy drawings (ends that miss by a few
// micrometres, e.g. DXF exported with 4 decimals). Opt-in only: closing a gap this large moves
// geometry, and chain_and_nest reports the largest gap it closed.
inline constexpr double kProfileJoinLoose = 1e-2;

// mm. The profile readers (DXF, TOML) drop an input entity whose length is below this (a line
// with coincident ends, an arc of zero radius or sweep) and count it.
inline constexpr double kProfileZeroLength = 1e-9;

// mm. Chordal tolerance of the polylines chain_and_nest uses only to test input loops for
// nesting and self-intersection, and NURBS loops for orientation; the geometry it returns is
// exact.
inline constexpr double kProfileTestChord = 1e-3;

// Dimensionless. A DXF entity's unit extrusion direction whose |x| and |y| are below this is
// +Z or -Z (the drawing plane, possibly mirrored); the DXF reader skips any other direction.
inline constexpr double kDxfExtrusionAxis = 1e-9;

// ---- NURBS curves (kernels/curves/nurbs_*.cpp) ----

// Dimensionless, relative to the knot range t1 - t0. A parameter within this of an existing
// knot is that knot: knot insertion and splitting raise its multiplicity instead of creating a
// span too short to evaluate reliably.
inline constexpr double kKnotSnap = 1e-12;

// mm. Smallest chordal / offset / arc-fit tolerance the NURBS approximations honour; smaller
// requests are raised to it (below it, rounding of evaluated points would keep refinement
// going until its depth cap).
inline constexpr double kNurbsMinTol = 1e-9;

// Dimensionless, relative to the curve's size (diagonal of its control-point box). A chord
// shorter than this has no direction of its own (tangents fall back on a longer one), and
// curve ends closer than this make the curve closed.
inline constexpr double kNurbsZeroLength = 1e-12;


// Dimensionless, relative to (curve size / knot range). A first derivative shorter than this
// is zero (a cusp or a repeated control point): the tangent is taken from a short chord.
inline constexpr double kNurbsZeroSpeed = 1e-10;

// mm. Newton refinement of a NURBS self-intersection stops when the two curve points are
// closer than this.
inline constexpr double kCurveIntersect = 1e-11;

// Radians. A fitted arc whose |sweep| is below this is emitted as a line: its centre would be
// ill-conditioned (radius ~ chord / sweep) and it differs from its chord by chord * sweep / 8,
// which is included in the measured deviation anyway.
inline constexpr double kArcAsLineSweep = 1e-7;

// mm. A link between loops of consecutive offset levels (or from a clean-up loop to its
// bounding loop) is accepted when it is at most the offset distance plus this long. Offset
// loops sit at their distance to ~1e-9 mm, but sliver removal (kOffsetSliver) may move a
// joint by up to 1e-5 mm.
inline constexpr double kLinkSlack = 2e-5;

// mm^2. An uncut region enclosing less than this is a zero-width remnant (a bridge between
// two corner regions where a band is exactly twice the tool radius wide), not material.
inline constexpr double kUncutArea = 1e-9;

// mm. Uncut regions (kernels/pocket/uncut.cpp) dissect only the stretches of the band's
// crude offset loops that are not certified to lie closer than R - kOffsetValid - this to the
// other level everywhere; the margin covers the offset pieces being cut from their crude
// segments at computed crossings (off the segment by up to ~1e-7 mm where curves cross at
// a glancing angle), so that no piece of a certified segment can pass validation.
inline constexpr double kUncutCertify = 1e-6;

// Sine of the angle below which two curves meeting at a point are taken to touch rather
// than cross (offset dissection): near-tangent crossings are ill-conditioned, and a contact
// that close to tangent moves by at most ~1e-6 mm over the 1 mm around it.
inline constexpr double kTangentCross = 1e-6;

// ---- NURBS surfaces (kernels/surface/*.cpp) ----

// Dimensionless. The height-field check (check_height_field) counts a surface point whose unit
// normal has |n_z| at most this as a vertical tangent plane: the bottom is not single-valued
// over the plan there (or its parameterisation collapses).
inline constexpr double kHeightFieldNz = 1e-9;

// Dimensionless, relative to the surface's plan size (diagonal of its control-point box in
// xy). Chordal tolerance of the border polygon on which check_height_field tests that the
// surface's plan outline does not overlap itself; border stretches closer than this may be
// reported as touching.
inline constexpr double kHeightFieldOutline = 1e-7;

// Dimensionless. A first partial derivative of a surface shorter than this times the other one
// is zero (a pole, where a whole edge of the parameter domain meets in one point): the normal
// there is the limit taken from the mixed second derivative.
inline constexpr double kSurfaceZeroSpeed = 1e-10;

// mm. Ball drop on a NURBS surface (kernels/surface/surface_drop*): a full Newton step on the
// contact shorter than this ends the search; the error left is of order its square over the
// curvature radius (~1e-12 mm in position, far less in height).
inline constexpr double kDropNewtonQuadratic = 1e-6;

// mm. Ball drop: a Newton iterate this close to a maximum already found in the same patch is
// converging to it and is stopped. Two distinct maxima this close would differ in height by
// the order of kDropSameMaximum^2 times f's curvature (~1 / R): 1e-10 mm at R = 1 mm.
inline constexpr double kDropSameMaximum = 1e-5;

// Dimensionless, relative to |f| + 1 (f: ball centre height, mm). Near the maximum a full
// Newton step changes the centre height by less than its rounding; such a step is still taken
// if it lowers the height by at most this, so that the contact position converges too.
inline constexpr double kDropFlatSlack = 1e-14;

// Dimensionless (local Bezier patch parameter in [0, 1]). A Newton iterate this close to a
// side of the patch's parameter square is on it (and is fixed there when the gradient points
// out of the square).
inline constexpr double kDropBoundSnap = 1e-9;

// Dimensionless, relative to a sub-patch's parameter size. A maximum found within this of a
// concave leaf sub-patch's parameter rectangle counts as inside it (rounding of the halved
// parameters).
inline constexpr double kDropInLeaf = 1e-9;

// ---- Offset elements and drive-plane slicing (kernels/mesh/offset_elements, kernels/scan) ----

// Dimensionless (sine of the bend angle). An edge whose two facets' opposite vertices lie
// within this times their distance from the edge of the other facet's plane is flat
// (EdgeKind::kFlat) rather than convex or concave. Informational: every edge is kept.
inline constexpr double kEdgeFlatSine = 1e-12;

// Dimensionless. An edge whose unit direction has a horizontal part shorter than this is
// vertical: it has no cylinder piece in a drive plane (its top vertex's sphere reaches the
// same height), matching the point drop-cutter, which hands vertical edges to their vertices.
inline constexpr double kVerticalEdge = 1e-12;

// Dimensionless (sine of the bend angle). Edges bent less than this keep their cylinder in
// the scan even when concave (kernels/mesh/offset_elements.hpp, element_reachable): it fills
// rounding slivers between the two nearly coplanar offset triangles. Clearly concave edges
// are overlapped by those triangles by about R times the bend, far above rounding.
inline constexpr double kFlatEdgeKeep = 1e-9;

// Dimensionless (sine). Facets joined by edges of two facets whose unit normals are within
// this of a region's first facet form a coplanar region (share_coplanar_offsets): they are
// offset along that one normal, so their offset triangles meet without slivers, and the
// edges and vertices inside the region are dropped. The offset surface moves by at most
// R times twice this (2.5e-11 mm for a 5 mm ball); subdivided and CAD meshes (flat faces
// split into many triangles) have normals equal to ~1e-13.
inline constexpr double kCoplanarSine = 1e-11;

// mm. Input conditioning for the exact slicers (kernels/mesh/condition.hpp): a facet joins a
// planar cluster when its vertices lie within this of the cluster's fitted plane, and a
// cluster's plane is snapped to vertical or to an axis when every vertex stays within this of
// the snapped plane. Noise of exporters (10-13 significant digits, unit conversions, double
// booleans, float32 STL of a 100 mm part: 1e-13 to 1e-5 mm) lies below it. Measured as a
// window, not a bound (docs/performance.md, "Exact curves on every mesh"): at 1e-5 reliefs
// written at 6-7 digits and parts with vertex noise of 1e-5 keep open z-level chains; at 3e-5
// finely tessellated cylinders and spheres (OpenSCAD's examples) cluster into partial planes
// and open chains appear there instead.
inline constexpr double kConditionPlane = 2e-5;

// mm. A vertex is moved onto its clusters' planes only when that moves it at most this far;
// the slicers then run for a ball grown by the largest move made, so no path gouges the part
// as given.
inline constexpr double kConditionMove = 4e-5;

// Dimensionless (relative singular value). Planes whose normals span a direction this weakly
// (about 0.06 degrees apart) count as one direction when a vertex is moved onto several by
// least squares: it then lies between them instead of far off on their crossing.
inline constexpr double kConditionParallel = 1e-3;

// Dimensionless (difference of unit normals). Clusters whose offsets agree within twice
// kConditionPlane but whose normals differ by more than this are not one face
// (condition.cpp unify_planes; the distance of every vertex decides the rest).
inline constexpr double kConditionSameNormal = 1e-4;

// Dimensionless (times R). A slice point of a cylinder or sphere counts as inside its
// wedge / ring cone (the ball there would not cut into a facet) up to this much penetration.
inline constexpr double kTrimSlack = 1e-12;

// Dimensionless (times R). The slack of the trimming test at a nearly flat kept edge (and at
// its vertices), whose wedge is (almost) empty: the kept strip around the common normal is
// about this wide in direction, far wider than rounding, far narrower than a facet.
inline constexpr double kFlatTrimSlack = 1e-7;

// mm. A trimmed cylinder or sphere piece is grown by this into its trimmed-away part, so that
// rounding never leaves a sliver between it and the offset triangle that takes over.
inline constexpr double kTrimExtend = 1e-9;

// Dimensionless, relative to R. An element's y reach (element_y_reach: the extreme y of its
// reachable directions, times R) is padded by this on both sides, so that the rounding of
// the extreme directions never leaves out a plane the element meets; bounds of the reach
// (engine/offset_elements_build.cpp y_reach_bound) pad twice this, over the reach's own
// rounding.
inline constexpr double kReachPad = 1e-9;

// Dimensionless. A candidate extreme direction of a reachable cone (cone_y_extent) shorter
// than this before normalising (a cross product of nearly parallel constraints) is dropped:
// its direction is numerical noise; the constraints' own extremes cover it.
inline constexpr double kConeDirectionMin = 1e-12;

// ---- Upper envelope of a drive plane (kernels/scan/envelope) ----

// mm. Two pieces within this of each other over an interval are tied there: the one with
// the lower element id is kept (the envelope height is off by at most this).
inline constexpr double kEnvelopeTie = 1e-10;

// mm. Intervals narrower than this are decided at their midpoint (ends of crossings that
// bisection cannot separate further).
inline constexpr double kEnvelopeMinWidth = 1e-12;

// mm. Neighbouring envelope spans whose heights differ by more than this at their common x
// are joined by a vertical segment (the tool passes a vertical wall).
inline constexpr double kEnvelopeJump = 1e-9;

// mm. A run of envelope spans narrower than this in all, lying between two spans and not
// above the higher of their facing ends, is a hole: the curve crosses it at that height.
// Pieces that meet in exact arithmetic (a facet's offset edge and its cylinder's wedge side,
// a cylinder's cap and its vertex sphere, an ellipse's vertical tangent and a steep facet)
// get their ends from different formulas, and where the plane meets their edge at a grazing
// angle the ends move apart by rounding / angle (4e-9 mm on a relief): something lower shows
// through. Filling such a hole is one-sided (the tool stays above), and a real dip this
// narrow is a slot the tool fits into within 1e-6 mm, which it then passes over.
inline constexpr double kEnvelopeHole = 1e-6;

// mm. A scan segment on a cylinder's elliptic section whose middle lies within this of its
// chord is written as a line (kind cylinder-line): an edge nearly parallel to the drive plane
// has an ellipse whose centre lies 1e9 mm away, and its centre form could not be evaluated.
inline constexpr double kScanFlatSection = 1e-10;

// Radians. A junction whose two tangent directions differ by less than this is tangent
// (the path continues smoothly from one element to the next).
inline constexpr double kJunctionTangentAngle = 1e-6;

// ---- Z-level contours (kernels/scan/zlevel*) ----

// mm. A point within this of a region's boundary is on it (z-level contours): a curve is
// coincident with another when its points lie this close to it (the lower element id keeps a
// shared stretch), and a line ending this close to another splits it (a T-junction).
// Coincident boundaries of different elements (stacked edges of a wall, duplicated vertices)
// agree to ~1e-14 mm.
inline constexpr double kZLevelOnBoundary = 1e-11;

// mm. Contour piece ends closer than this are one vertex of the planar map of the pieces
// (a piece whose two ends are one vertex is a sliver and left out): split points of one
// vertex computed from different curve pairs, pieces between nearby joints.
inline constexpr double kZLevelLink = 1e-5;

// mm. After linking (kZLevelLink), a contour piece whose end no piece leaves is linked to the
// nearest piece that no piece enters when that one starts within this (where the
// classification, not the faces, decides: see zlevel.hpp step 8).
inline constexpr double kZLevelRepair = 1e-4;

// mm. The pieces at a vertex of the planar map are ordered around it by where they cross a
// circle about it of at least this radius (four times the spread of their ends, when larger):
// well above rounding (two curves leaving one point tangentially are ~kappa r^2 / 2 = 1e-12
// mm apart there at kappa = 2 / mm), well below the features of a contour.
inline constexpr double kZLevelOrderRadius = 1e-6;

// Radians. Pieces crossing that circle at angles closer than this are ordered by how much
// they turn leaving the vertex (a line leaving along an arc's tangent lies on its outer side).
inline constexpr double kZLevelTangentTie = 1e-9;

// Dimensionless. The polyline of a contour arc bulges outwards by at most the chordal
// tolerance, less beside a narrower gap of U's complement (ContourSeg::clearance), but not
// less than this times the tolerance (1e-6 mm at the default 1e-3 mm: the verifier's limit).
inline constexpr double kZLevelMinBulge = 1e-3;

// mm. Two pieces joining the same two vertices of the planar map, one's midpoint this close to
// the other's curve, are one edge (nearly coincident boundaries of different elements: the
// clip lines of nearly coplanar facets, a clip line and a flat edge's ellipse); they would
// bound a face too thin to order around its two vertices consistently.
inline constexpr double kZLevelDuplicate = 1e-7;

// mm. A cell of the z-level pruning grid is interior when it lies this deep inside one region.
inline constexpr double kZLevelCellMargin = 1e-9;

// mm. With a higher level's region known to lie inside U (kernels/scan/zlevel.hpp
// ZLevelInside), regions lying this deep inside it are dropped. Smaller drops more of a steep
// wall's stacked regions (their boundaries step inwards by the wall's run per level) but
// makes the pieces near the known boundary that must be certified shorter (about a quarter of
// this).
inline constexpr double kZLevelInsideDepth = 0.005;

// mm. A curve piece (or grid cell) is certified inside the known region (ZLevelInside) when
// it lies this deep inside the region's polygon: well above the rounding of the contour
// points the polygon is made of (~1e-11 mm), which lie on the exact boundary.
inline constexpr double kZLevelInsideMargin = 1e-6;

// mm. Root isolation on conic arcs stops at sub-arcs shorter than this: two crossings closer
// than this may both be missed (the curves then touch within rounding).
inline constexpr double kZLevelRootLength = 1e-10;
// mm. A crossing isolated on a monotone sub-arc is refined (regula falsi) to this length.
inline constexpr double kZLevelRootPrecision = 1e-13;

// mm. An elliptic contour arc within this of its chord is output as a line (very flat edges
// give ellipses with huge semi-axes whose centre form loses precision).
inline constexpr double kZLevelFlatArc = 1e-10;

// Dimensionless (rise over horizontal length). An edge flatter than this is horizontal for
// z-level contours: the sides of its capsule are straight.
inline constexpr double kZLevelFlatSlope = 1e-12;

// mm. Slack on the z-level kernel's tests that only decide whether work is done, never the
// answer: curve boxes that may overlap (pairs to intersect), crossings just beyond a curve's
// end (the curve that continues it may miss them by rounding; a duplicate split is
// harmless), a point's parameter range on a candidate curve, the cutoff of the deepest-first
// region search. Values at a part's scale carry ~1e-13 mm of rounding.
inline constexpr double kZLevelSlack = 1e-9;

// mm. A tangent joint (where a clip line or capsule side ends tangent to the next element's
// curve) is moved onto the target region's candidate curve passing within this of it: the
// joint is computed from the line's element, its place on the curve to ~sqrt(rounding).
inline constexpr double kZLevelJointSnap = 1e-6;

// mm. The known inside region's polygon edge between two line segments of a contour is exact
// (lies on the contour) when their ends agree within this; a curve piece's end within
// kZLevelOnExactEdge of such an edge lies on the known boundary (less than
// kZLevelInsideMargin deep), so no region inside the known region holds it.
inline constexpr double kZLevelSharedEnd = 1e-12;
inline constexpr double kZLevelOnExactEdge = 1e-10;

// mm. A reference point of the known inside region's grid lies at least this far from every
// polygon edge in its cell, so that parity rays from it never pass an edge within rounding.
inline constexpr double kZLevelRefClearance = 1e-7;

// Dimensionless (cross product of unit directions). Lines closer than this to parallel have
// no crossing of their own (their meeting is found as coincidence or a T-junction); two kept
// pieces of one element's line continue each other (merged into one segment) when their
// tangents are within kZLevelSameDirection.
inline constexpr double kZLevelParallel = 1e-15;
inline constexpr double kZLevelSameDirection = 1e-12;

// Dimensionless. Rounding of the conic implicit function F = Q_D(P_C(s)) relative to the
// squared scale of the differences it is computed from (a circle's diameter; for an edge's
// ellipse, the distance from the edge's end point to C's points plus R, not the ellipse's
// diameter, which is R / slope): root isolation keeps intervals whose bound is within this of
// zero. Newton steps stop below kZLevelStep relative to the point's size.
inline constexpr double kZLevelImplicitRounding = 1e-12;
inline constexpr double kZLevelStep = 1e-15;

// Dimensionless. The pruning grid's cell is at least this times (1 + the candidates' xy
// extent in mm), so that a degenerate extent never makes an unbounded grid.
inline constexpr double kZLevelMinCell = 1e-9;

// ---- Clean-up paths (kernels/cleanup/*) ----

// Dimensionless (difference of |t . n| between two layer families). pencil_keep counts
// crossings this close as a tie (won by the lower family): rounding in the bi-contact vectors
// (~1e-15) must not split a crease at 45 degrees between the x and y lines.
inline constexpr double kPencilFamilyTie = 1e-9;

// Dimensionless (|t . n| of a unit crease tangent t and a layer's unit normal n). A crease
// crossing the layer planes at a smaller sine runs along them: its point on the next plane
// would lie a million spacings away, so the tracing predicts none there (crease_on_plane in
// engine/pencil_crease.cpp).
inline constexpr double kPencilAlongPlane = 1e-6;

// mm. A pencil piece shorter than this is a point, not a path: dropped even when min_length
// is 0 (engine/pencil.cpp).
inline constexpr double kPencilMinPiece = 1e-9;

// mm. A ball centre whose vertical passes this close to the part lies over it
// (engine/pencil_outline.hpp): a crease ending at a vertical side of the part, with a drive
// plane in that side's plane, keeps its point there. Rounding of the distance to a face the
// vertical lies in is far smaller.
inline constexpr double kPencilOutline = 1e-9;

// Dimensionless (cosine). The concave zone's normal cone of a patch (engine/concave_zone.hpp)
// whose normals reach within this of 90 degrees from its axis is unbounded: near a
// hemisphere the cone's axis says nothing.
inline constexpr double kConcaveZoneMinCos = 1e-3;

// rad. The concave zone's cones and angle tests are widened by this for rounding in the
// normals (~1e-15): the screen must never drop a pair at its threshold.
inline constexpr double kConcaveZoneAngle = 1e-9;

// Dimensionless (mean lateral component of a crease's material vector along a path). A path
// whose cut-side score is within this times its xy length of 0 has no material side: a
// symmetric V-groove (b1 + b2 vertical to rounding, ~1e-16) or a vertical corner (no xy
// travel). Such a path is cut climb and conventional alike and keeps its orientation. The
// conditioning (kConditionMove) and exporters' noise tilt a face's fitted plane by up to
// ~1e-5 rad, so a symmetric groove must stay neutral well above that; a crease lopsided by
// 0.06 degrees has no side a machinist could tell.
inline constexpr double kCutSideNeutral = 1e-3;

// Dimensionless (fraction of half the step). Sculptured pockets look for the material their
// passes leave with the band eroded by half the step grown by this much: by exactly half, the
// two levels' offsets coincide along every parallel stretch, which the dissection cannot
// tell from a region; 1 % wider finds only where the loops spread apart by more, and leaves
// at most ~2 % more than the scallop height there (within the surface tolerance delta).
inline constexpr double kScallopBand = 0.01;

// ---- Verifier: profiles (kernels/verify/wall_distance.*, engine/verify_profile.*) ----

// mm. A move that cuts into the part (wall, floor, mesh, bottom) by more than this fails
// the job's verification (status failed_verification).
inline constexpr double kVerifyGouge = 1e-6;

// mm. The chord guard (engine/chord_guard.hpp) clears a move between exact CL points that
// cuts into a mesh by at most this by raising its two ends (one-sided: the tool leaves at
// most this much material there); deeper cuts get a lift-over. A chord 0.1 mm long sags
// L^2 / 8 rho below a CL curve of curvature radius rho: 1.25e-3 mm at rho = 1 mm.
inline constexpr double kChordRaise = 1e-3;

// mm. Resolution of the verifier's distances to NURBS walls: a Bezier piece is subdivided
// until its control polygon lies within half of this of its chord, and the distance reported
// is a lower bound at most this below the truth (conservative: never misses a gouge).
inline constexpr double kVerifyResolution = 1e-7;

// mm. The verifier looks for walls up to this far beyond the tool radius plus stock;
// clearances larger than this are not reported (min_clearance stays +inf).
inline constexpr double kVerifyReach = 1.0;

// Dimensionless (times the ball radius). The verifier cuts a pocket3d bottom into Bezier
// pieces no larger than this: no larger than the ball, so that each piece's distance to a
// move has one minimum for its Newton iteration (bottoms bend far less than the ball).
inline constexpr double kVerifyPiece = 1.0;

// Parameter units (mm of travel for the segment parameter). The verifier's Newton iteration
// on a bottom piece stops when a step moves the parameters less than this (and its damping
// never falls below it): far below any distance the verifier reports.
inline constexpr double kVerifyNewtonStep = 1e-13;

// mm. The verifier's plan inversion (the bottom's height over a grid point) has converged
// when the surface point lies this close to the grid point in plan.
inline constexpr double kVerifyPlanResidual = 1e-11;

// mm. Spacing of the plan grid on which the verifier measures a pocket3d path's scallop.
inline constexpr double kVerifyScallopGrid = 0.5;

// ---- Verifier: swept tool vs meshes (kernels/verify/swept_tool.*, engine/verify_mesh.*) ----

// mm. Contact tolerance of the gouge verifier: a triangle that the swept tool (with stock)
// overlaps by at most this much, measured as Euclidean distance, is touched, not cut. It
// makes "cuts into" a decision that rounding (~1e-12 mm) cannot flip on exact contacts,
// e.g. a cutter sliding along a vertical wall at exactly its radius.
inline constexpr double kVerifyContact = 1e-9;

// mm. A tool whose corner radius plus stock is below this (a flat cutter, with or without a
// hair of stock) is verified as sharp: a cylinder of radius R + stock from stock below the tip,
// whose gouge is computed in closed form. GJK cannot be used there: it resolves distances to
// the curved rim only to ~size * sqrt(machine epsilon) ~ 1e-7 mm when the tool touches, and a
// sharp tool's decisions are all made at distance ~0. The sharp body is larger than the true
// one by at most 0.42 times this, at the rim only (conservative).
inline constexpr double kVerifySharpCorner = 1e-4;

// Dimensionless. A candidate point of the sharp-tool gouge (swept_tool.cpp) whose horizontal
// distance from the tool axis exceeds the radius by at most this fraction is on the rim:
// computed crossings of the rim carry rounding. Moves the gouge by at most this times R times
// the triangle's slope.
inline constexpr double kSharpRimSlack = 1e-12;

// mm. GJK distance (swept_tool.cpp) stops when its support-plane lower bound is within this
// of the distance of its current pair of points. Far below kVerifyContact.
inline constexpr double kGjkDistance = 1e-11;

// Dimensionless. GJK also stops when a step shortens its squared distance by less than this
// fraction: progress at the level of rounding (a tiny distance to a large flat face of the
// Minkowski difference, where the support plane's tilt keeps the lower bound loose).
inline constexpr double kGjkProgress = 1e-13;

// Count. GJK iteration cap: polytopes converge in a few iterations, the cutter's round rim in
// about 20 (the error on a curved support shrinks ~4x per iteration); the bounds stay valid
// when the cap is hit.
inline constexpr int kGjkMaxIterations = 96;

// mm. Default resolution of the verifier's gouge depth (vertical lift): the reported lift
// clears the triangle and is at most this above the smallest lift that does.
inline constexpr double kGougeResolution = 1e-9;

// Count. Cap on the GJK evaluations of one lift search (Newton from above, secant from
// below, bisection otherwise); when hit, the returned lift still clears the triangle.
inline constexpr int kLiftMaxSteps = 120;

// mm. Clean-up operations (engine/surface_check.hpp): a tool tip at most this below the
// drop-cutter surface is on it (rounding, not a gouge): surface_deficit reports 0.
inline constexpr double kSurfaceSlack = 1e-9;

// mm. reachable() (engine/surface_check.hpp): how far a reachable ball below the drop-cutter
// height may be in the part: rounding only. Beside a wall of slope a, a ball in the part by p
// is p / cos(a) below the CL surface, and the verifier measures that vertical depth
// (anchor_dense: 1.5e-7 mm in the part, 1.8e-4 mm deep).
inline constexpr double kReachSlack = kSurfaceSlack;

// mm. lift_swept() (engine/surface_check.hpp) sweeps the ball of radius R - kSweepSlack along
// each chord: a chord is accepted only if its ball nowhere comes closer than that to the mesh.
// Also the height below the drop-cutter surface at which the pencil's crease points count as
// on it.
inline constexpr double kSweepSlack = 1e-7;

// lift_swept() along a point's own direction: the smallest cosine between that direction and
// the contact normal it divides a penetration by (a contact almost square to the direction is
// cleared in a few doubling rounds or not at all, instead of by one huge lift).
inline constexpr double kLiftMinCosine = 0.1;

// mm. Pictures (batch/preview/preview.hpp): the smallest extent a picture is fitted to, so
// that a single point or a straight line still gets a finite scale; and the smallest height
// range a colour ramp spans (a flat part or paths all at one height take its first colour).
inline constexpr double kPreviewMinExtent = 1e-6;
inline constexpr double kPreviewMinZSpan = 1e-9;

}  // namespace ncpath::tol
