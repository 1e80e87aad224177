// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Ground truth for the evaluation suite, from positions alone: it never calls ThinTool's
/// detection, tool model or response, so that it judges stock Bullet and ThinTool by the same
/// rule. It works on the tool's exact convex pieces (a box, or a hull's own triangles) and the soft
/// body's surface as Bullet holds it after each step.
///
/// - Penetration: the exact signed distance from soft-surface samples (every node and every face's
///   centroid) to each convex piece; a sample inside a piece penetrates by minus that distance.
/// - Crossing: a node crosses when, between two steps and in the piece's frame, it passes the
///   piece's mid-surface (the plane through the piece's centre across its thinnest axis) at a point
///   inside the piece and deeper than the tolerance inside its rim (the faces turned more than 60°
///   from the thin axis). A node pushed round the tool's rim never counts, nor one that slid along
///   the rim within the tolerance of it (as a face that reaches no deeper pierces nothing); one that
///   went through does, however far it went, near a blade's edge too.
///   When a piece turns between two steps, where a node went in between is not known, and two
///   readings are each wrong for some node: straight in the piece's frame (the test above, the
///   chord) has a node the turning plate never reached pass through it, and straight in the world
///   with the piece on its arc (the step split into sub-intervals of at most 5°, the tool's
///   translation linear and its rotation by slerp, each tested as above) has a node that rode on
///   the plate's face round the arc lag behind it and pass through it. A node crosses a turning
///   piece only when both readings say so: no path that either takes went round. A step without
///   rotation is one interval, the two readings the same, the test above unchanged.
/// - Tool inside: the centre of a piece lies inside the closed soft surface, by the generalised
///   winding number (Jacobson et al. 2013), which, unlike ray parity, has no unlucky directions.
///   The winding number speaks for a surface that does not pass through itself; Bullet does not
///   keep a soft body from doing so (self-collision is off by default), and a body folded through
///   itself round a tool winds round it with no face of it ever crossing the tool. A step whose
///   surface passes through itself (an edge through a face that shares no node with it) therefore
///   counts apart, as selfIntersecting, not as tool inside; it is tested only in the steps the
///   winding number says inside. A tool found inside that way stays so attributed while it stays
///   inside: the fold that wrapped it may untangle with the tool within.
/// - Pierced face: at the end of a step, a soft triangle reaches deeper than the tolerance into a
///   piece. This catches what the node and centroid samples miss: a needle's tip through the middle
///   of a large face, or a blade's edge through a face whose corners all lie outside. It is the
///   intersection of the two solids measured by depth: a solid's edge crossing the triangle's
///   interior, or the triangle's edge passing through the solid, counts when the part of the
///   triangle inside the solid goes deeper than the tolerance; found exactly by clipping the
///   triangle against the piece's face planes moved inward by the tolerance. Closed surfaces and
///   sheets alike; only faces whose bounding box meets the piece's bounding sphere are clipped.

#include <thintool/core/Math.h>

#include <array>
#include <vector>

namespace thintool::eval {

using Triangle = std::array<int, 3>;

/// A closed convex triangle mesh in its own frame, counter-clockwise seen from outside.
struct ConvexSolid {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;

  static ConvexSolid box(const Vec3& halfExtents);
};

/// Distance queries against one convex solid. Throws thintool::Error when the mesh is not a closed
/// convex solid with finite coordinates.
class SolidDistance {
 public:
  explicit SolidDistance(ConvexSolid solid);

  /// Negative inside: minus the depth to the nearest face plane; outside: the exact distance to
  /// the nearest triangle.
  double signedDistance(const Vec3& local) const;
  /// The centre of the solid's bounding box, its half extents, and its thinnest axis (0, 1 or 2).
  const Vec3& centre() const { return m_centre; }
  const Vec3& halfExtents() const { return m_halfExtents; }
  int thinAxis() const { return m_thinAxis; }
  /// No point farther than this from centre() is inside the solid.
  double boundingRadius() const { return m_radius; }
  const ConvexSolid& solid() const { return m_solid; }
  /// One plane per triangle (coplanar triangles repeat theirs): unit outward normals and offsets,
  /// n·x = offset on the face, n·x < offset inside.
  const std::vector<Vec3>& faceNormals() const { return m_normals; }
  const std::vector<double>& faceOffsets() const { return m_offsets; }

 private:
  ConvexSolid m_solid;
  std::vector<Vec3> m_normals;   // unit, outward
  std::vector<double> m_offsets;  // n·x = offset on the face
  Vec3 m_centre;
  Vec3 m_halfExtents;
  int m_thinAxis = 1;
  double m_radius = 0;  // of the bounding sphere about m_centre
};

/// Squared distance from p to triangle (a, b, c), exact for any triangle, degenerate ones included.
double distanceSquaredToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Whether some edge of the surface passes through a face that shares no node with it; the faces
/// are binned in a uniform grid of their mean edge length, so the test is near linear in faces.
bool surfaceIntersectsItself(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles);

/// The generalised winding number of a closed surface about p: 1 inside, 0 outside, whatever the
/// surface's orientation (its sign follows it; callers compare |w| with 0.5).
double windingNumber(const Vec3& p, const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles);

/// A tool's convex piece placed in the tool's frame.
struct GroundTruthPiece {
  SolidDistance solid;
  Pose inTool;    ///< the piece's frame relative to the tool body
  int tool = 0;   ///< which of the scene's tools it belongs to
  /// Whether nothing the soft body does can move it (a kinematic or static tool): then a pinned
  /// node it reaches is a contact no method can keep, and judging ends there.
  bool immovable = false;
};

/// What the ground truth saw after one step.
struct GroundTruthStep {
  int crossings = 0;          ///< nodes that passed through a tool this step
  int piercedFaces = 0;       ///< soft faces reaching deeper than the tolerance into a tool at the step's end
  bool toolInside = false;    ///< a piece's centre is inside the closed soft surface, which does not pass through itself
  bool selfIntersecting = false;  ///< the winding number said inside, but the surface passes through itself
  /// An immovable piece reached a pinned node: it lies inside the piece, or the piece passed it.
  bool pinnedReached = false;
  double maxPenetration = 0;  ///< m, deepest surface sample inside a tool
  double sumSquaredPenetration = 0;  ///< m², over the penetrating samples
  int penetratingSamples = 0;
};

/// What it saw over a run.
///
/// Neither a pinned node nor an immovable piece can give way, so from the step one reaches the
/// other no contact method can keep the surface out of the tool: the faces round the node are held
/// across it. The run counts those steps apart, in unjudgedSteps; the other fields cover the steps
/// before.
struct GroundTruthRun {
  int steps = 0;
  int unjudgedSteps = 0;       ///< steps from the one where an immovable piece reached a pinned node
  int pinnedReachedStep = 0;   ///< that step (1 = the first), or 0
  int crossedNodes = 0;       ///< distinct nodes that passed through a tool at least once
  int stillCrossed = 0;       ///< of those, at the end on the far side of the first piece they crossed, within it
  int toolInsideSteps = 0;
  bool endsInside = false;
  int selfIntersectingSteps = 0;  ///< steps whose inside verdict a self-intersecting surface voided
  double maxPenetration = 0;  ///< m
  double rmsPenetration = 0;  ///< m, over every penetrating sample of every step (0 when none)
  int piercedSteps = 0;       ///< steps that ended with at least one pierced face
  int maxPiercedFaces = 0;    ///< most pierced faces at the end of one step
};

/// Follows a soft surface against a scene's tools step by step.
class GroundTruth {
 public:
  /// A face pierces a piece only when it reaches deeper than this (m): 0.1 mm, well below any
  /// tool's half thickness (0.5 mm at the thinnest), and above the rounding of float positions.
  static constexpr double kDefaultTolerance = 1e-4;
  /// A piece turning more than this (radians) between two steps is followed along its arc in
  /// sub-intervals of at most this turn each.
  static constexpr double kMaxTurnPerInterval = 5 * kPi / 180;

  /// closedSurface: whether the soft surface encloses a volume (a sheet does not: no tool-inside).
  /// tolerance: m, the depth beyond which a face counts as pierced.
  GroundTruth(std::vector<GroundTruthPiece> pieces, bool closedSurface, double tolerance = kDefaultTolerance);

  /// The state before the first step: toolPoses[t] is tool t's body pose. pinned: the nodes that
  /// never move (zero inverse mass), by index.
  void start(const std::vector<Pose>& toolPoses, const std::vector<Vec3>& nodes, const std::vector<Triangle>& faces,
             std::vector<int> pinned = {});
  const GroundTruthStep& update(const std::vector<Pose>& toolPoses, const std::vector<Vec3>& nodes,
                                const std::vector<Triangle>& faces);
  /// Nodes the soft body gained between two steps, as a cut gains them (Bullet's
  /// btSoftBody::cutLink appends them): followed from where they are now. nodes: every node, the
  /// ones it had first, as they were at the last update. Throws when it has fewer.
  void addNodes(const std::vector<Vec3>& nodes);
  const GroundTruthStep& lastStep() const { return m_step; }
  GroundTruthRun run() const;

 private:
  void measurePenetration(const Vec3& world, const std::vector<Pose>& piecePoses);
  void countCrossings(const std::vector<Vec3>& nodes);
  int crossingAlongArc(std::size_t piece, std::size_t node, const std::vector<Pose>& arc, const Vec3& nodeAfter) const;
  void followArc(std::size_t piece, const std::vector<Pose>& toolPoses, const std::vector<Pose>& poses,
                 std::vector<Pose>& arc) const;
  bool reachesPinnedNode(const std::vector<Pose>& poses, const std::vector<Vec3>& nodes) const;
  bool pierces(const Vec3& a, const Vec3& b, const Vec3& c, std::size_t piece, const Pose& pose);
  std::vector<Pose> piecePoses(const std::vector<Pose>& toolPoses) const;

  std::vector<GroundTruthPiece> m_pieces;
  bool m_closedSurface;
  double m_tolerance;
  std::vector<Pose> m_previousToolPoses;
  std::vector<Pose> m_previousPoses;
  std::vector<Vec3> m_previousNodes;
  std::vector<int> m_crossedPiece;   // per node: the first piece it went through, or -1
  std::vector<signed char> m_sideBeforeCrossing;  // per node: its side of that piece before
  std::vector<int> m_pinned;
  std::vector<std::vector<Pose>> m_arcs;  // per piece: its poses along this step's turn (followArc)
  GroundTruthStep m_step;
  bool m_wrappedByFold = false;  // the tool is inside since a step whose surface passed through itself
  GroundTruthRun m_run;
  double m_sumSquared = 0;
  long m_samples = 0;
  std::vector<Vec3> m_clipped;  // the clipped triangle, kept to reuse its storage
  std::vector<Vec3> m_clipScratch;
};

}  // namespace thintool::eval
