// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "response/Separation.h"

#include "geometry/Ccd.h"

#include <thintool/core/Assert.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace thintool {

namespace {

// A path that leaves the piece through a face whose normal is turned more than 60° from the one it
// entered by went through the piece, not round a corner of it.
constexpr Real kTurnedAway = Real(0.5);
constexpr int kMostSamples = PieceMotion::kMostSamples;

struct NodeVerdict {
  bool fix = false;
  Index plane = kInvalidIndex;  // the face the node goes back in front of
  bool sparedByArc = false;     // the chord alone would take it back: the arc reading spared it
};

// Reads a node's path through the piece (see the file comment of Separation.h) and says whether,
// and through which face, it must go back out. When the piece turns, where the node went in
// between is not known, and there are two readings of it: straight in the piece's frame (the
// chord: a node that rode on a face stays on it) and straight in the world with the piece on its
// arc (a node the piece never reached is left alone). A node that ends outside was carried through
// only if both readings take it through; one that ends inside leaves by the face the chord entered
// by, else the arc's, else the nearest. Without a turn the two readings are one.
NodeVerdict judgeNode(const ToolModel& piece, const PieceMotion& motion, const Pose* poses, const Vec3& start,
                      const Vec3& end, bool enclosed, Real clearance, Vec3& outEndLocal) {
  const std::vector<Plane>& planes = piece.planes;
  // A node of the surface may ride round a piece's rounded side, in by one face and out by the
  // next; a node enclosed by the surface cannot, and any way through is a way across (interior
  // nodes of tetrahedral boxes went through balls 0.1 to 73 mm deep in one step, out by faces less
  // than 60° from the way in: generated seeds 577 and 1280 with --bullet-kinds).
  const auto carries = [&](Index enter, Index leave) {
    return enter != kInvalidIndex && leave != kInvalidIndex &&
           (enclosed || dot(planes[enter].normal, planes[leave].normal) < kTurnedAway);
  };
  // On the arc the node may go in and come back out by the same face: it went through when, inside,
  // it came nearer to a face turned away from the one it entered by than to that face, where the
  // nearest face would have sent it out on the far side (generated seed 11856: a jaw turning 179°
  // a step took a node 86 % of the way through its thickness and back, the chord through it).
  // Plane distances are linear along a sample interval, and its inside part begins on the entry
  // face or where the last one ended, so the end of each inside part is the only point to test.
  const auto pastMidSurface = [&](Index enter, const Vec3& inside) {
    if (enter == kInvalidIndex) return false;
    const Real entryDistance = planes[enter].signedDistance(inside);
    for (const Plane& plane : planes) {
      if (dot(planes[enter].normal, plane.normal) < kTurnedAway && plane.signedDistance(inside) > entryDistance) {
        return true;
      }
    }
    return false;
  };
  const Vec3 startLocal = motion.start().applyInverse(start);
  const Vec3 endLocal = motion.end().applyInverse(end);
  outEndLocal = endLocal;
  const ClipResult chord = clipSegmentConvex(planes, 0, startLocal, endLocal);
  Index entered = chord.hit ? chord.enterPlane : kInvalidIndex;
  const bool chordCarried = chord.hit && carries(chord.enterPlane, chord.leavePlane);
  bool carried = chordCarried;
  const int samples = motion.samples();
  if (samples > 1) {
    Vec3 previous = startLocal;
    Index arcEntered = kInvalidIndex;
    bool arcCarried = false;
    for (int k = 1; k <= samples; ++k) {
      const Real t = Real(k) / Real(samples);
      const Vec3 current = k == samples ? endLocal : poses[k].applyInverse(start + (end - start) * t);
      const ClipResult clip = clipSegmentConvex(planes, 0, previous, current);
      if (clip.hit) {
        if (clip.enterPlane != kInvalidIndex) arcEntered = clip.enterPlane;
        arcCarried = arcCarried || carries(arcEntered, clip.leavePlane) ||
                     pastMidSurface(arcEntered, previous + (current - previous) * clip.leave);
      }
      previous = current;
    }
    if (entered == kInvalidIndex) entered = arcEntered;
    carried = carried && arcCarried;
  }
  Index nearest = 0;
  if (outsideDistance(planes, endLocal, &nearest) < 0) {
    return {true, entered != kInvalidIndex ? entered : nearest};
  }
  const bool behindEntry = chordCarried && planes[chord.enterPlane].signedDistance(endLocal) < clearance;
  if (carried && behindEntry) return {true, chord.enterPlane};
  return {false, kInvalidIndex, behindEntry};
}

// Calls visit(axis) with the triangle's own candidate separating axes against the piece, unnormalised:
// its normal and the cross products of its edges with the piece's; stops when visit returns true,
// and says whether it did. The piece's face normals are the caller's to add. An axis that repeats
// one already visited, or its opposite, could change nothing the visits find: each piece edge
// direction is taken once.
template <typename Visit>
bool visitTriangleAxes(const ToolModel& piece, const Vec3* triangle, Visit&& visit) {
  const Vec3 edges[3] = {triangle[1] - triangle[0], triangle[2] - triangle[1], triangle[0] - triangle[2]};
  if (visit(cross(edges[0], triangle[2] - triangle[0]))) return true;
  for (const Vec3& direction : piece.featureEdgeDirections) {
    for (const Vec3& e : edges) {
      if (visit(cross(direction, e))) return true;
    }
  }
  return false;
}

bool hasPinnedNode(const SeparationPatch& patch, const std::array<Index, 3>& face) {
  return !(patch.inverseMasses[face[0]] > 0 && patch.inverseMasses[face[1]] > 0 && patch.inverseMasses[face[2]] > 0);
}

// The separating-axis test of a triangle against the piece, both in the piece's frame: the
// piece's face normals, the triangle's normal, and the cross products of their edges. With the
// triangle's place at the start of the step as well (in the piece's frame then), it also says
// whether the triangle kept its side, that is, whether some axis separates it from the piece on
// the same side at both ends of the step. A face that kept no side went into or through the piece
// during the step, even if it no longer meets it, and goes back to a side it had at the start:
// along the axis of such a side that best trades the length of the move against how well it
// points back the way the triangle came (`back`, its motion relative to the piece reversed),
// cost / (kAlignmentFloor + cos). The shortest move alone lets two faces that share an edge along
// a needle push that edge to opposite sides, round after round; the way back agrees for both.
// A face that still meets the piece goes straight back along `back` instead, until it clears,
// when that is shorter than the chosen side's move, so that a face whose only side at the start
// lies across a long piece is not sent along the piece's length, tens of centimetres in one step.
// Shorter, not better scored: the way back of a face jittering against a held plate points
// anywhere, and following it feeds the jitter (a held dense ball's kinetic energy doubles).
class TriangleAxes {
 public:
  TriangleAxes(const ToolModel& piece, const Vec3* end, const Vec3* start, Real tolerance, const Vec3& back = {})
      : m_piece(piece), m_end(end), m_start(start), m_tolerance(tolerance), m_back(back) {
    for (const AxisExtent& planeAxis : m_piece.planeAxes) {
      if (planeAxis.axis != Vec3{} && visitUnit(planeAxis.axis, planeAxis.low, planeAxis.high)) return;
    }
    const auto visitAxis = [this](const Vec3& axis) { return visit(axis); };
    if (visitTriangleAxes(m_piece, end, visitAxis)) return;
    // The triangle's own axes at the start as well: a large face that turns during the step can
    // be separated at the start only along one of them, and without them it seems to have kept no
    // side (generated seed 1856: a needle's faces lost their side and let it into the body). They
    // say whether it kept one, and give the side to go back to only when none of the end's axes
    // had it at the start: along an axis of the start, a face that turned since can be tens of
    // centimetres from clearing (seed 1840).
    if (start != nullptr) {
      m_keepEndSide = m_bestConsistent < std::numeric_limits<Real>::max();
      visitTriangleAxes(m_piece, start, visitAxis);
    }
  }

  /// The triangle meets the piece at the end of the step, by more than the tolerance on every axis.
  bool meets() const { return m_meets; }
  /// Some axis separates the triangle from the piece on one side at the start and at the end.
  bool keptItsSide() const { return m_kept; }
  /// The move (piece frame) that puts the triangle back on a side it had at the start, or straight
  /// back the way it came out of the piece when that is shorter, clearance included; with neither,
  /// the move to the side it was nearest to at the start. Zero when none is due.
  Vec3 move(Real clearance) const {
    if (m_kept) return {};
    const bool canRewind = m_meets && m_rewind < std::numeric_limits<Real>::max();
    const bool rewindIsShorter = canRewind && m_rewind < m_bestConsistent;
    if (m_bestConsistent < std::numeric_limits<Real>::max() && !rewindIsShorter) {
      return m_consistentDirection * (m_bestConsistent + clearance);
    }
    if (canRewind) return m_back * (m_rewind + clearance);
    if (!m_meets) return {};
    return m_anyDirection * (m_bestAny + clearance);
  }

 private:
  // Returns true when nothing more can be learnt: the axis separates the triangle and there is
  // no start to compare with, or it kept its side.
  bool visit(const Vec3& rawAxis) {
    const Real axisLength = length(rawAxis);
    if (!(axisLength > Real(1e-12))) return false;
    const Vec3 axis = rawAxis / axisLength;
    const std::vector<Vec3>& corners = m_piece.mesh.vertices;
    Real pieceLow = 0;
    Real pieceHigh = 0;
    projectedInterval(axis, corners.data(), corners.size(), pieceLow, pieceHigh);
    return visitUnit(axis, pieceLow, pieceHigh);
  }

  // visit with the axis unit and the piece's extent along it known.
  bool visitUnit(const Vec3& axis, Real pieceLow, Real pieceHigh) {
    Real low = 0;
    Real high = 0;
    projectedInterval(axis, m_end, 3, low, high);
    const Real alongPlus = pieceHigh - low;   // the move along +axis that clears the piece
    const Real alongMinus = high - pieceLow;  // the move along -axis that does
    const bool separated = std::min(alongPlus, alongMinus) <= m_tolerance;
    m_meets = m_meets && !separated;
    if (m_start == nullptr) return separated;

    Real low0 = 0;
    Real high0 = 0;
    projectedInterval(axis, m_start, 3, low0, high0);
    // On this side at the start, within rounding of where the last step left a face.
    if (low0 - pieceHigh >= -kStartSlack) consider(axis, alongPlus);
    if (pieceLow - high0 >= -kStartSlack) consider(-axis, alongMinus);
    // Met the piece at the start too: back the way it came, as far as it takes (the ray along
    // `back` leaves the Minkowski difference of piece and triangle at the smallest
    // along / cos over the axes, its facets' normals being among them) ...
    const Real towards = dot(axis, m_back);
    if (towards > kLeastCosine) m_rewind = std::min(m_rewind, alongPlus / towards);
    if (towards < -kLeastCosine) m_rewind = std::min(m_rewind, alongMinus / -towards);
    // ... or, without a motion to go back along, to the side it was nearest to being on then.
    if (low0 - pieceHigh > m_bestStartGap) {
      m_bestStartGap = low0 - pieceHigh;
      m_bestAny = alongPlus;
      m_anyDirection = axis;
    }
    if (pieceLow - high0 > m_bestStartGap) {
      m_bestStartGap = pieceLow - high0;
      m_bestAny = alongMinus;
      m_anyDirection = -axis;
    }
    return m_kept;
  }

  void consider(const Vec3& direction, Real along) {
    if (along <= m_tolerance) m_kept = true;
    if (m_keepEndSide) return;
    const Real score = along / (kAlignmentFloor + std::max(Real(0), dot(direction, m_back)));
    if (score < m_bestScore) {
      m_bestScore = score;
      m_bestConsistent = along;
      m_consistentDirection = direction;
    }
  }

  static constexpr Real kStartSlack = 1e-6;
  static constexpr Real kAlignmentFloor = Real(0.1);
  static constexpr Real kLeastCosine = Real(1e-3);
  const ToolModel& m_piece;
  const Vec3* m_end;
  const Vec3* m_start;
  Real m_tolerance;
  Vec3 m_back;
  bool m_keepEndSide = false;
  bool m_meets = true;
  bool m_kept = false;
  Real m_bestScore = std::numeric_limits<Real>::max();
  Real m_bestConsistent = std::numeric_limits<Real>::max();
  Real m_bestAny = std::numeric_limits<Real>::max();
  Real m_bestStartGap = -std::numeric_limits<Real>::max();
  Real m_rewind = std::numeric_limits<Real>::max();
  Vec3 m_consistentDirection;
  Vec3 m_anyDirection;
};

// Twice what the step explains for a face: the path of the piece's farthest-going corner (travel)
// and the face's largest own move in the soft solve. No move of the last word takes a node of the
// face further than that on its own account.
Real explainedReach(const SeparationPatch& patch, const std::array<Index, 3>& face, Real travel) {
  Real ownMove = 0;
  for (Index v : face) {
    if (patch.inverseMasses[v] > 0) {
      ownMove = std::max(ownMove, length(patch.solvedPositions[v] - patch.startPositions[v]));
    }
  }
  return 2 * (travel + ownMove);
}

// Moves a face by `move` (world) at its centroid: each node by its share of inverse mass, the
// smallest mass-weighted change that moves the centroid that far (a plain translation when the
// masses are equal). Rounds of faces that share nodes add their moves up, to half a metre in a
// step on a pinned sheet (generated seed 877): a node that would end further from where the solver
// left it than both its place at the start of the step, carried along with the piece, and this
// move's own length goes to that place instead. Each node is judged alone: sending the face's other
// nodes to their places too took nodes that the move left near where the solver put them back to
// where they stood beside a moving piece, step after step, so that they rode along with it: a
// pinned sheet's nodes rode 5 cm above a plate until a face stretched across its rim (generated seed
// 65030). A move's own length counts only up to explainedReach: a face stretched across a needle
// turning 78° a step is as wide as the needle is long, and the way off the needle within its plane
// took its far nodes metres in a step, one to 7.7 km/s by the ground truth's reading (generated seed
// 185 in the deformable world). False when every node is pinned.
bool moveFace(SeparationPatch& patch, const std::array<Index, 3>& face, const Vec3& move, const PieceMotion& motion,
              Real travel) {
  Real weights = 0;
  for (Index v : face) weights += patch.inverseMasses[v];
  if (!(weights > 0)) return false;
  const Real explained = explainedReach(patch, face, travel);
  const Vec3 direction = normalizedOrZero(move);
  for (Index v : face) {
    if (!(patch.inverseMasses[v] > 0)) continue;
    const Vec3 share = move * (3 * patch.inverseMasses[v] / weights);
    const Vec3& solved = patch.solvedPositions[v];
    const Vec3 moved = patch.positions[v] + share;
    const Vec3 carried = motion.end().apply(motion.start().applyInverse(patch.startPositions[v]));
    const bool beyondCarried = lengthSquared(moved - solved) >
                               std::max(lengthSquared(carried - solved),
                                        std::min(lengthSquared(share), explained * explained));
    patch.directions[v] = beyondCarried ? normalizedOrZero(carried - patch.positions[v]) : direction;
    patch.positions[v] = beyondCarried ? carried : moved;
    patch.moved[v] = 1;
  }
  return true;
}

// Whether a face kept a side of a turning piece on its arc: in every sample interval, the face
// moving straight in the world and the piece at the interval's two poses, some axis separates the
// two on one side at both ends. Straight in the piece's frame (the chord) a face beside a piece that
// turns a quarter turn or more seems to keep no side, though the piece never came near it, and
// went back round, metres in a step (generated seed 30: a blade at 137° a step). A face that ends
// clear went through only if both readings say so, as for a node (judgeNode).
bool keptItsSideAlongArc(const ToolModel& piece, const PieceMotion& motion, const Pose* poses,
                         const SeparationPatch& patch, const std::array<Index, 3>& face) {
  Vec3 previous[3];
  for (int k = 0; k < 3; ++k) previous[k] = poses[0].applyInverse(patch.startPositions[face[k]]);
  for (int sample = 1; sample <= motion.samples(); ++sample) {
    const Real t = Real(sample) / Real(motion.samples());
    Vec3 current[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& start = patch.startPositions[face[k]];
      current[k] = poses[sample].applyInverse(start + (patch.positions[face[k]] - start) * t);
    }
    if (!TriangleAxes(piece, current, previous, 0).keptItsSide()) return false;
    for (int k = 0; k < 3; ++k) previous[k] = current[k];
  }
  return true;
}

// A face with a pinned node cannot translate: shares of a translation move only its free nodes,
// the part of it by the pinned node stays where it was, and round after round the same move leaves
// it pierced (generated seed 1969: a sheet's corner face across a plate's rim). Its free nodes go
// instead just beyond a plane that every pinned node of the face is beyond already and the whole
// piece is behind, the plane that asks the least total move of them, each along that plane's
// normal, on a path that stays out of the piece and leaves the node outside every plane it is
// outside of (round an edge of the piece is where the node's other faces would pierce it: seed
// 1969's next round). The planes are the piece's face planes and, through each of its edges,
// planes turned between the edge's two faces: a face wrapped round a rim, its pinned node under
// the piece and a free node above it, comes clear only by a plane through the rim (seed 4127).
// Those come only with aboutEdges (in the last round, or once shares of a translation would go too
// far: sharesGoTooFar), when no face plane serves, and only for a piece with no other near it:
// turned about an edge, a face between two jaws swings out of one into the other, pass after pass
// (seeds 3461 and 1032).
// The whole triangle then lies beyond the plane, within half the clearance at a pinned node: a
// dynamic tool stopped at a pinned node ends on it, rounding a hair inside (generated seed 4352).
// False when no plane serves: a pinned node in the piece, or a free node inside it, which the node
// pass moves first.
bool swingAboutPinnedNodes(SeparationPatch& patch, const std::array<Index, 3>& face, const ToolModel& piece,
                           const Pose& end, const Vec3 (&local)[3], Real clearance, bool aboutEdges) {
  const std::vector<Plane>& planes = piece.planes;
  Plane best;
  Real bestCost = std::numeric_limits<Real>::max();
  const auto consider = [&](const Plane& plane) {
    Real cost = 0;
    for (int k = 0; k < 3; ++k) {
      const Real distance = plane.signedDistance(local[k]);
      if (!(patch.inverseMasses[face[k]] > 0)) {
        if (!(distance >= -clearance / 2)) return;
      } else if (distance < clearance) {
        const Vec3 to = local[k] + plane.normal * (clearance - distance);
        if (clipSegmentConvex(planes, 0, local[k], to).hit) return;
        for (const Plane& other : planes) {
          if (other.signedDistance(local[k]) > 0 && !(other.signedDistance(to) > 0)) return;
        }
        cost += clearance - distance;
      }
    }
    if (cost < bestCost) {
      bestCost = cost;
      best = plane;
    }
  };
  for (const Plane& plane : planes) consider(plane);
  // Turned about an edge from one of its faces to the other, in steps of a sixteenth of the way.
  constexpr int kTurns = 16;
  const bool useEdges = aboutEdges && bestCost == std::numeric_limits<Real>::max();
  for (std::size_t e = 0; useEdges && e < piece.featureEdges.size(); ++e) {
    const Vec3& onEdge = piece.mesh.vertices[piece.featureEdges[e][0]];
    const std::array<Vec3, 2>& sides = piece.featureEdgeNormals[e];
    for (int turn = 1; turn < kTurns; ++turn) {
      const Real t = Real(turn) / Real(kTurns);
      const Vec3 normal = normalizedOrZero(sides[0] * (1 - t) + sides[1] * t);
      if (normal == Vec3{}) continue;
      consider(Plane{normal, dot(normal, onEdge)});
    }
  }
  if (bestCost == std::numeric_limits<Real>::max()) return false;
  for (int k = 0; k < 3; ++k) {
    const Index v = face[k];
    const Real distance = best.signedDistance(local[k]);
    if (!(patch.inverseMasses[v] > 0) || distance >= clearance) continue;
    patch.positions[v] = end.apply(local[k] + best.normal * (clearance - distance));
    patch.directions[v] = end.applyToDirection(best.normal);
    patch.moved[v] = 1;
  }
  return true;
}

// The translations t·direction, for t in (enter, leave), that leave a triangle meeting the piece
// grown by some length; none when enter >= leave.
struct TranslationInterval {
  Real enter = -std::numeric_limits<Real>::max();
  Real leave = std::numeric_limits<Real>::max();
};

// Appends the separating axes of a triangle (piece frame) against the piece, unit, with the
// extents of both along each and the piece's grown by `grow`: the piece's face normals, the
// triangle's normal, the cross products of their edges. A translation changes neither the axes
// nor the extents, only where the triangle's lie, so these serve every direction the group is
// tried along.
void appendSeparatingAxes(const ToolModel& piece, const Vec3 (&triangle)[3], Real grow,
                          std::vector<SeparatingAxis>& out) {
  for (const AxisExtent& planeAxis : piece.planeAxes) {
    if (planeAxis.axis == Vec3{}) continue;
    SeparatingAxis extents;
    extents.axis = planeAxis.axis;
    extents.pieceLow = planeAxis.low - grow;
    extents.pieceHigh = planeAxis.high + grow;
    projectedInterval(extents.axis, triangle, 3, extents.low, extents.high);
    out.push_back(extents);
  }
  const std::vector<Vec3>& corners = piece.mesh.vertices;
  visitTriangleAxes(piece, triangle, [&](const Vec3& rawAxis) {
    const Real axisLength = length(rawAxis);
    if (!(axisLength > Real(1e-12))) return false;
    SeparatingAxis extents;
    extents.axis = rawAxis / axisLength;
    projectedInterval(extents.axis, corners.data(), corners.size(), extents.pieceLow, extents.pieceHigh);
    extents.pieceLow -= grow;
    extents.pieceHigh += grow;
    projectedInterval(extents.axis, triangle, 3, extents.low, extents.high);
    out.push_back(extents);
    return false;
  });
}

// The meeting interval of a triangle that translates along direction, from its axes
// (appendSeparatingAxes). Exact: the separating axes of a triangle that only translates stay the same.
TranslationInterval meetingInterval(const SeparatingAxis* axes, const SeparatingAxis* axesEnd,
                                    const Vec3& direction) {
  TranslationInterval meeting;
  for (const SeparatingAxis* extents = axes; extents != axesEnd; ++extents) {
    const Real speed = dot(extents->axis, direction);
    if (std::abs(speed) < Real(1e-12)) {
      if (extents->low >= extents->pieceHigh || extents->high <= extents->pieceLow) return {0, 0};
    } else {
      Real first = (extents->pieceLow - extents->high) / speed;
      Real second = (extents->pieceHigh - extents->low) / speed;
      if (speed < 0) std::swap(first, second);
      meeting.enter = std::max(meeting.enter, first);
      meeting.leave = std::min(meeting.leave, second);
    }
    // Empty: no other axis can change that.
    if (meeting.enter >= meeting.leave) return meeting;
  }
  return meeting;
}

bool anyInGroup(const SeparationPatch& patch, const std::array<Index, 3>& face) {
  return patch.inCluster[face[0]] != 0 || patch.inCluster[face[1]] != 0 || patch.inCluster[face[2]] != 0;
}

// The face in the piece's frame, its nodes in the group (patch.inCluster) moved by shift.
void shiftedFace(const SeparationPatch& patch, const Pose& end, const std::array<Index, 3>& face, const Vec3& shift,
                 Vec3 (&out)[3]) {
  for (int k = 0; k < 3; ++k) {
    out[k] = end.applyInverse(patch.positions[face[k]]) + (patch.inCluster[face[k]] != 0 ? shift : Vec3{});
  }
}

// The axes (appendSeparatingAxes) of every face all of whose nodes are in the group
// (patch.inCluster), then of every node of it, each one's run ending at patch.groupAxesEnd.
void gatherGroupAxes(const ToolModel& piece, const Pose& end, Real clearance, SeparationPatch& patch) {
  patch.groupAxes.clear();
  patch.groupAxesEnd.clear();
  for (const std::array<Index, 3>& face : patch.faces) {
    if (patch.inCluster[face[0]] == 0 || patch.inCluster[face[1]] == 0 || patch.inCluster[face[2]] == 0) continue;
    Vec3 triangle[3];
    shiftedFace(patch, end, face, {}, triangle);
    appendSeparatingAxes(piece, triangle, clearance, patch.groupAxes);
    patch.groupAxesEnd.push_back(patch.groupAxes.size());
  }
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    if (patch.inCluster[v] == 0) continue;
    const Vec3 point = end.applyInverse(patch.positions[v]);
    const Vec3 node[3] = {point, point, point};
    appendSeparatingAxes(piece, node, clearance, patch.groupAxes);
    patch.groupAxesEnd.push_back(patch.groupAxes.size());
  }
}

// The smallest t ≥ least that moves the group by t·direction (piece frame) clear of the piece,
// grown by the clearance: outside the meeting interval of every face all of whose nodes are in
// the group, and of every node of it (their axes gathered by gatherGroupAxes).
Real shortestClearingShift(const SeparationPatch& patch, const Vec3& direction, Real least) {
  Real shift = least;
  const SeparatingAxis* axes = patch.groupAxes.data();
  for (bool raised = true; raised;) {
    raised = false;
    std::size_t begin = 0;
    for (const std::size_t axesEnd : patch.groupAxesEnd) {
      const TranslationInterval meeting = meetingInterval(axes + begin, axes + axesEnd, direction);
      begin = axesEnd;
      if (!(meeting.enter < shift && shift < meeting.leave)) continue;
      shift = meeting.leave;
      raised = true;
    }
  }
  return shift;
}

// Along the normal of one of the piece's face planes, the shift that takes the group's nodes of
// each face with a pinned node beyond that plane, when its pinned nodes are beyond it already: the
// group swings such a face clear as swingAboutPinnedNodes does one face.
Real swingShift(const Plane& plane, const Pose& end, const SeparationPatch& patch, Real clearance) {
  Real shift = 0;
  for (const std::array<Index, 3>& face : patch.faces) {
    if (!hasPinnedNode(patch, face) || !anyInGroup(patch, face)) continue;
    bool pinnedBeyond = true;
    for (Index v : face) {
      if (!(patch.inverseMasses[v] > 0)) {
        pinnedBeyond = pinnedBeyond && plane.signedDistance(end.applyInverse(patch.positions[v])) >= 0;
      }
    }
    if (!pinnedBeyond) continue;
    for (Index v : face) {
      if (patch.inCluster[v] == 0) continue;
      shift = std::max(shift, clearance - plane.signedDistance(end.applyInverse(patch.positions[v])));
    }
  }
  return shift;
}

// How many faces with a pinned node and a node in the group still meet the piece once the group
// has moved by `shift` (piece frame): no growth of the group can clear them.
int heldFaces(const ToolModel& piece, const Pose& end, const SeparationPatch& patch, const Vec3& shift) {
  int held = 0;
  for (const std::array<Index, 3>& face : patch.faces) {
    if (!hasPinnedNode(patch, face) || !anyInGroup(patch, face)) continue;
    Vec3 moved[3];
    shiftedFace(patch, end, face, shift, moved);
    held += TriangleAxes(piece, moved, nullptr, 0).meets() ? 1 : 0;
  }
  return held;
}

// The length of the path the piece's farthest-going corner takes in the step, along its arc.
Real farthestPath(const ToolModel& piece, const PieceMotion& motion, const Pose* poses) {
  Real farthest = 0;
  for (const Vec3& corner : piece.mesh.vertices) {
    Real path = 0;
    for (int k = 0; k < motion.samples(); ++k) path += length(poses[k + 1].apply(corner) - poses[k].apply(corner));
    farthest = std::max(farthest, path);
  }
  return farthest;
}

// Whether moving a face with a pinned node by shares of `move` would take a free node further than
// twice what the step can explain: the path of the piece's farthest-going corner (travel) and the
// face's largest own move in the soft solve. A pinned corner face that a slow plate had reached,
// moved by shares round after round, went up to 1.18 m a move while the plate went 3.4 mm, and
// threw nodes at 71 m/s (generated seed 9082). Such a face swings about an edge of a lone piece at
// once, where it would otherwise wait for the last round, or is left to slidePinnedFacesClear, whose
// slide is no longer than twice the travel.
bool sharesGoTooFar(const SeparationPatch& patch, const std::array<Index, 3>& face, const Vec3& move, Real travel) {
  Real weights = 0;
  Real heaviest = 0;
  for (Index v : face) {
    weights += patch.inverseMasses[v];
    heaviest = std::max(heaviest, patch.inverseMasses[v]);
  }
  const Real longestShare = weights > 0 ? length(move) * 3 * heaviest / weights : 0;
  return longestShare > explainedReach(patch, face, travel);
}

// Adds the face's movable nodes to the group (patch.inCluster); says whether any was new.
bool joinGroup(SeparationPatch& patch, const std::array<Index, 3>& face) {
  bool grew = false;
  for (Index v : face) {
    if (patch.inverseMasses[v] > 0 && patch.inCluster[v] == 0) {
      patch.inCluster[v] = 1;
      grew = true;
    }
  }
  return grew;
}

// Whether moving the group by shift (piece frame) would leave one of its nodes carried through the
// piece since the start of the step (judgeNode).
bool groupGoesThrough(const ToolModel& piece, const PieceMotion& motion, const Pose* poses,
                      const SeparationPatch& patch, const Vec3& shift, Real clearance) {
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    if (patch.inCluster[v] == 0) continue;
    Vec3 ignored;
    const Vec3 moved = patch.positions[v] + motion.end().applyToDirection(shift);
    const bool enclosed = patch.enclosed[v] != 0;
    if (judgeNode(piece, motion, poses, patch.startPositions[v], moved, enclosed, clearance, ignored).fix) return true;
  }
  return false;
}

// Whether moving the group by shift (piece frame) would carry a face it touches across the piece:
// clear of it at the start of the step and at the end, but on no one side at both. judgeNode never
// sees it when the piece passes between the face's nodes: a needle 1.8 mm wide ended a step inside
// a pressure ellipsoid, no node crossed, no face pierced, after the shortest translation took a
// face its tip was in over the tip (generated seed 6220 with friction). Read on the chord, and
// only for a piece that turns no farther than one sample of its arc: under a larger turn the chord
// alone misreads faces the piece never reached (keptItsSideAlongArc).
bool groupCarriesAFaceAcross(const ToolModel& piece, const PieceMotion& motion, const SeparationPatch& patch,
                             const Vec3& shift) {
  if (motion.samples() > 1) return false;
  for (const std::array<Index, 3>& face : patch.faces) {
    if (!anyInGroup(patch, face)) continue;
    Vec3 start[3];
    for (int k = 0; k < 3; ++k) start[k] = motion.start().applyInverse(patch.startPositions[face[k]]);
    if (TriangleAxes(piece, start, nullptr, 0).meets()) continue;
    Vec3 moved[3];
    shiftedFace(patch, motion.end(), face, shift, moved);
    const TriangleAxes after(piece, moved, start, 0);
    if (!after.meets() && !after.keptItsSide()) return true;
  }
  return false;
}

// Whether moving the group by shift (piece frame) would leave a face it touches meeting a near
// piece that the face did not meet before. Two jaws with a sheet wound round both each found
// faces of the same group stuck, and each moved it about half a metre clear of itself and on
// round the other, pass after pass: 4.8 m in one step (generated seed 6610).
bool pushesIntoNearPiece(const std::vector<NearPiece>& near, const Pose& end, const SeparationPatch& patch,
                         const Vec3& shift) {
  const Vec3 worldShift = end.applyToDirection(shift);
  for (const NearPiece& other : near) {
    if (!isFinite(other.end)) continue;
    for (const std::array<Index, 3>& face : patch.faces) {
      if (!anyInGroup(patch, face)) continue;
      Vec3 before[3];
      Vec3 after[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3& position = patch.positions[face[k]];
        before[k] = other.end.applyInverse(position);
        after[k] = patch.inCluster[face[k]] != 0 ? other.end.applyInverse(position + worldShift) : before[k];
      }
      const bool metBefore = TriangleAxes(*other.model, before, nullptr, 0).meets();
      if (!metBefore && TriangleAxes(*other.model, after, nullptr, 0).meets()) return true;
    }
  }
  return false;
}

// Moves the group by shift (piece frame), each node's contact direction along `direction`; returns
// how many nodes moved.
Index shiftGroup(const Pose& end, const Vec3& shift, const Vec3& direction, SeparationPatch& patch) {
  Index moved = 0;
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    if (patch.inCluster[v] == 0) continue;
    patch.positions[v] += end.applyToDirection(shift);
    patch.directions[v] = end.applyToDirection(direction);
    patch.moved[v] = 1;
    patch.movedInRound[v] = std::max(patch.movedInRound[v], 0);
    ++moved;
  }
  return moved;
}

// Whether a point (world) lies within clearance of one of the near pieces.
bool liesInNearPiece(const std::vector<NearPiece>& near, const Vec3& point, Real clearance) {
  return std::any_of(near.begin(), near.end(), [&](const NearPiece& other) {
    return outsideDistance(other.model->planes, other.end.applyInverse(point)) < clearance;
  });
}

// A movable node that judgeNode sends back goes out by its face, the clearance beyond it.
NodeVerdict putNodeOutside(const ToolModel& piece, const PieceMotion& motion, const Pose* poses, Real clearance,
                           Index v, SeparationPatch& patch, const std::vector<NearPiece>* nearPieces) {
  Vec3 local;
  const NodeVerdict verdict =
      judgeNode(piece, motion, poses, patch.startPositions[v], patch.positions[v], patch.enclosed[v] != 0, clearance,
                local);
  if (!verdict.fix) return verdict;
  const Pose& end = motion.end();
  const Plane& plane = piece.planes[verdict.plane];
  const Vec3 inFront = end.apply(local + plane.normal * (clearance - plane.signedDistance(local)));
  // A node goes back in front of the face it entered by, where the solve took it along that face:
  // a node the solve pulls through the piece towards its neighbours then slides round the piece
  // step by step. A node on no face that would land there in another piece near this one goes
  // back where it was in the piece's frame at the start instead, outside every piece of the tool,
  // which shares that motion: in front of the face it entered, a node of a box and a ball side by
  // side went into the box, and pass after pass the two pieces sent it into each other (generated
  // seed 1881 with --bullet-kinds). Sent back there whatever lay near, an interior node of a
  // tetrahedral box ahead of a blade at 34 m/s was carried along 25 steps while the solve pulled
  // it through towards its neighbours; its links stretched to 1.1 m, and when the blade turned away
  // it leapt back at 1,066 m/s (seed 53119). Without the near pieces (keepNodesOutside) it goes
  // back to its start.
  if (patch.enclosed[v] != 0 && (nearPieces == nullptr || liesInNearPiece(*nearPieces, inFront, clearance))) {
    const Vec3 atStart = motion.start().applyInverse(patch.startPositions[v]);
    if (outsideDistance(piece.planes, atStart) >= clearance) {
      patch.positions[v] = end.apply(atStart);
      patch.moved[v] = 1;
      patch.directions[v] = normalizedOrZero(patch.positions[v] - end.apply(local));
      return verdict;
    }
  }
  patch.positions[v] = inFront;
  patch.moved[v] = 1;
  patch.directions[v] = end.applyToDirection(plane.normal);
  return verdict;
}

// When the rounds run out with faces still pierced, their movable nodes move together, by one
// translation that clears every face among them and leaves each of the nodes outside: faces that
// want a shared node on opposite sides (the fan of faces round a node a needle runs through,
// generated seed 225) then move as one, the way none of them alone can. The translation is the
// shortest along the piece's face normals and the faces' way back (shortestClearingShift); it
// must not take a node through the piece since the step's start (judgeNode), nor a face across it
// (groupCarriesAFaceAcross), and a face with only some of its nodes in the group must come clear
// too, else its nodes join the group and the search runs again. A face with a pinned node comes
// clear only beyond a plane its pinned node is beyond (swingShift), and the direction that leaves
// fewest of those pierced (heldFaces) goes first: on pinned sheets, the shortest translation left
// the corner faces across the tool (seed 1804). Nor may a translation, however short, leave a
// face in a near piece that it did not meet before (pushesIntoNearPiece): the pieces' passes do
// not settle that. Between jaws on pinned sheets, such faces were still in the other jaw at the
// end of the step (seed 8609 with friction; seeds 13671, 26887, 35337, 39901, 46844, 47422 and
// 48347, jaws turning 43 to 154° a step).
// Each face that a translation leaves pierced brings its nodes in; on a sheet a needle whirls
// through (seeds 623 and 1603, needles turning 124° and 75° a step), a group took one more node
// with each translation and needed up to 16 of them, as many as carryFacesWithPiece allows.
// Nothing moves when no translation serves.
void moveStuckFacesTogether(const ToolModel& piece, const PieceMotion& motion, const Pose* poses, Real clearance,
                            const std::vector<NearPiece>& near, SeparationPatch& patch) {
  constexpr int kMostGrowths = 16;
  const Pose& end = motion.end();
  const Index vertexCount = patch.vertexCount();
  patch.inCluster.assign(vertexCount, 0);
  Vec3 back;
  for (const std::array<Index, 3>& face : patch.faces) {
    Vec3 now[3];
    shiftedFace(patch, end, face, {}, now);
    if (!TriangleAxes(piece, now, nullptr, 0).meets()) continue;
    joinGroup(patch, face);
    for (int k = 0; k < 3; ++k) back += motion.start().applyInverse(patch.startPositions[face[k]]) - now[k];
  }
  back = normalizedOrZero(back);

  for (int growth = 0; growth < kMostGrowths; ++growth) {
    gatherGroupAxes(piece, end, clearance, patch);
    Real bestShift = std::numeric_limits<Real>::max();
    Vec3 bestDirection;
    int bestHeld = std::numeric_limits<int>::max();
    for (std::size_t candidate = 0; candidate <= piece.planes.size(); ++candidate) {
      const bool alongNormal = candidate < piece.planes.size();
      const Vec3 direction = alongNormal ? piece.planes[candidate].normal : back;
      if (direction == Vec3{}) continue;
      const Real least = alongNormal ? swingShift(piece.planes[candidate], end, patch, clearance) : 0;
      const Real shift = shortestClearingShift(patch, direction, least);
      const int held = heldFaces(piece, end, patch, direction * shift);
      if (held > bestHeld || (held == bestHeld && !(shift < bestShift))) continue;
      if (groupGoesThrough(piece, motion, poses, patch, direction * shift, clearance)) continue;
      if (groupCarriesAFaceAcross(piece, motion, patch, direction * shift)) continue;
      if (pushesIntoNearPiece(near, end, patch, direction * shift)) continue;
      bestShift = shift;
      bestDirection = direction;
      bestHeld = held;
    }
    if (bestShift == std::numeric_limits<Real>::max()) return;
    const Vec3 shift = bestDirection * bestShift;
    bool grew = false;
    for (const std::array<Index, 3>& face : patch.faces) {
      if (!anyInGroup(patch, face)) continue;
      Vec3 moved[3];
      shiftedFace(patch, end, face, shift, moved);
      if (TriangleAxes(piece, moved, nullptr, 0).meets()) grew = joinGroup(patch, face) || grew;
    }
    if (grew) continue;
    shiftGroup(end, shift, bestDirection, patch);
    return;
  }
}

// A face with a pinned node that the rounds and the last resort leave pierced lies across a rim of
// the piece: the piece swept past the pinned node close enough that the node's neighbours, pushed
// by its face or carried with it, ended on its other side (generated seeds 2851 and 3440: plates
// turning 96° and 116° a step beside a sheet's pinned corner). No plane the pinned node is beyond
// takes such a face clear (swingAboutPinnedNodes), and carrying it with the piece is what left it
// there. Its free nodes slide instead, together, by the shortest translation along one of the
// piece's face normals or halfway between two of them that clears every face they touch and keeps
// each of them outside: along the piece's face and past its rim, a node stays on its side and the
// face's edge to the pinned node passes beyond the rim. A face left meeting the piece brings its
// free nodes into the group, as in moveStuckFacesTogether. No slide is taken that takes a node
// through the piece since the start of the step (judgeNode), nor one longer than twice the path of
// the piece's farthest-going corner: a node the rim swept along went no further than the rim, and
// going back round it takes it at most as far again. Longer slides, half a metre in a step where a
// plate ran into a sheet's pinned corner, fling the sheet (generated seeds 8052 and 9275: nodes at
// 272 and 209 m/s). Along each direction the shortest slide is bracketed on a grid over the
// piece's size and the first group's longest edge, then bisected: how far a face is from clearing
// does not fall steadily with the slide. The group grows until the slide leaves none of its faces
// meeting the piece, a few nodes at a time round a whirling tool: 36 growths and 89 nodes in one
// step of generated seed 623 (a needle turning 124° a step through a pinned sheet), where 32
// left a face pierced. Returns how many nodes moved; none when no slide serves.
Index slidePinnedFacesClear(const ToolModel& piece, const PieceMotion& motion, const Pose* poses, Real clearance,
                            SeparationPatch& patch) {
  constexpr int kMostGrowths = 128;
  constexpr int kGridSteps = 64;
  constexpr int kBisections = 10;
  constexpr int kMostDirections = 64;
  // Halfway directions for a piece of few planes, one per triangle: a wedge blade's eight. A box's
  // twelve slide along its face normals alone, which keeps a slid node on its side of the rim
  // (Separation.TheLastResortSlidesAFaceWithAPinnedNodePastTheRim); many planes are their own.
  constexpr std::size_t kMostPlanesForHalfways = 8;
  const Pose& end = motion.end();
  const Index vertexCount = patch.vertexCount();
  const std::vector<Plane>& planes = piece.planes;
  patch.inCluster.assign(vertexCount, 0);
  const auto meetsSlid = [&](const std::array<Index, 3>& face, const Vec3& slide) {
    Vec3 moved[3];
    shiftedFace(patch, end, face, slide, moved);
    return TriangleAxes(piece, moved, nullptr, -clearance).meets();
  };
  // A pinned node in the piece keeps its faces there whatever the others do.
  const auto pinnedOutside = [&](const std::array<Index, 3>& face) {
    bool pinned = false;
    for (Index v : face) {
      if (patch.inverseMasses[v] > 0) continue;
      pinned = true;
      if (outsideDistance(planes, end.applyInverse(patch.positions[v])) < clearance / 2) return false;
    }
    return pinned;
  };
  bool any = false;
  for (const std::array<Index, 3>& face : patch.faces) {
    if (pinnedOutside(face) && meetsSlid(face, {})) any = joinGroup(patch, face) || any;
  }
  if (!any) return 0;
  const Real travel = farthestPath(piece, motion, poses);
  if (!(travel > 0)) return 0;

  Vec3 directions[kMostDirections];
  int directionCount = 0;
  for (std::size_t i = 0; i < planes.size() && directionCount < kMostDirections; ++i) {
    directions[directionCount++] = planes[i].normal;
  }
  for (std::size_t i = 0; i < planes.size() && planes.size() <= kMostPlanesForHalfways; ++i) {
    for (std::size_t j = i + 1; j < planes.size() && directionCount < kMostDirections; ++j) {
      if (dot(planes[i].normal, planes[j].normal) < Real(-0.5)) continue;
      directions[directionCount++] = normalizedOrZero(planes[i].normal + planes[j].normal);
    }
  }
  // Faces whose free nodes are all in the group: where they end is known.
  const auto settled = [&](const std::array<Index, 3>& face) {
    for (Index v : face) {
      if (patch.inverseMasses[v] > 0 && patch.inCluster[v] == 0) return false;
    }
    return true;
  };
  const auto clears = [&](const Vec3& slide) {
    for (const std::array<Index, 3>& face : patch.faces) {
      if (anyInGroup(patch, face) && settled(face) && meetsSlid(face, slide)) return false;
    }
    for (Index v = 0; v < vertexCount; ++v) {
      if (patch.inCluster[v] == 0) continue;
      if (outsideDistance(planes, end.applyInverse(patch.positions[v]) + slide) < clearance) return false;
    }
    return true;
  };
  Real longestEdge = 0;
  for (const std::array<Index, 3>& face : patch.faces) {
    if (!anyInGroup(patch, face)) continue;
    for (int k = 0; k < 3; ++k) {
      longestEdge = std::max(longestEdge, length(patch.positions[face[k]] - patch.positions[face[(k + 1) % 3]]));
    }
  }
  const Real reach = length(piece.bounds.max - piece.bounds.min) + longestEdge;
  for (int growth = 0; growth < kMostGrowths; ++growth) {
    Real best = std::numeric_limits<Real>::max();
    Vec3 bestDirection;
    for (int d = 0; d < directionCount; ++d) {
      const Vec3& direction = directions[d];
      // A bracket that starts at twice the travel or beyond could only give a slide too long.
      const auto inReach = [&](int step) {
        return step <= kGridSteps && reach * Real(step - 1) / kGridSteps < 2 * travel;
      };
      int step = 1;
      while (inReach(step) && !clears(direction * (reach * Real(step) / kGridSteps))) ++step;
      if (!inReach(step)) continue;
      Real low = reach * Real(step - 1) / kGridSteps;
      Real high = reach * Real(step) / kGridSteps;
      if (!(low < best)) continue;
      for (int i = 0; i < kBisections; ++i) {
        const Real middle = (low + high) / 2;
        (clears(direction * middle) ? high : low) = middle;
      }
      if (!(high < best) || high > 2 * travel) continue;
      if (groupGoesThrough(piece, motion, poses, patch, direction * high, clearance)) continue;
      best = high;
      bestDirection = direction;
    }
    if (best == std::numeric_limits<Real>::max()) return 0;
    const Vec3 slide = bestDirection * best;
    bool grew = false;
    for (const std::array<Index, 3>& face : patch.faces) {
      if (anyInGroup(patch, face) && !settled(face) && meetsSlid(face, slide)) grew = joinGroup(patch, face) || grew;
    }
    if (grew) continue;
    return shiftGroup(end, slide, bestDirection, patch);
  }
  return 0;
}

// Whether the face meets the piece (grown by tolerance) at the end of the step, the group's nodes
// (patch.inCluster) at patch.carried and the others where they are.
bool meetsWithGroupCarried(const ToolModel& piece, const Pose& end, const SeparationPatch& patch,
                           const std::array<Index, 3>& face, Real tolerance) {
  Vec3 local[3];
  for (int k = 0; k < 3; ++k) {
    const Index v = face[k];
    local[k] = end.applyInverse(patch.inCluster[v] != 0 ? patch.carried[v] : patch.positions[v]);
  }
  return TriangleAxes(piece, local, nullptr, tolerance).meets();
}

int facesMeetingWithGroupCarried(const ToolModel& piece, const Pose& end, const SeparationPatch& patch,
                                 Real tolerance) {
  int meeting = 0;
  for (const std::array<Index, 3>& face : patch.faces) {
    meeting += meetsWithGroupCarried(piece, end, patch, face, tolerance) ? 1 : 0;
  }
  return meeting;
}

// What is left at the end of the step, measured as the judge would: half the clearance forgives
// rounding. Nodes and faces `known` to be outside are not measured.
template <typename KnownNode, typename KnownFace>
void countWhatIsLeft(const ToolModel& piece, const Pose& end, const SeparationPatch& patch, Real tolerance,
                     const KnownNode& knownOutside, const KnownFace& knownClear, SeparationCounts& counts) {
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    if (knownOutside(v)) continue;
    if (outsideDistance(piece.planes, end.applyInverse(patch.positions[v])) < -tolerance) ++counts.nodesInside;
  }
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    if (knownClear(f)) continue;
    Vec3 now[3];
    for (int k = 0; k < 3; ++k) now[k] = end.applyInverse(patch.positions[patch.faces[f][k]]);
    if (TriangleAxes(piece, now, nullptr, tolerance).meets()) ++counts.facesPierced;
  }
}

// The last resort, when the faces still pierced after the rounds and moveStuckFacesTogether have no
// place they can all take: their movable nodes are carried with the piece, each to where it stood
// in the piece's frame at the start of the step. There every face of theirs was clear, so a face
// whose nodes all go along is clear again, whatever the turn; a face with some nodes left behind
// brings them along, and the group grows until no face it touches meets the piece. The nodes move
// as the tool's surface does, no faster; none can have passed through the piece, which they never
// moved against. Applied only if fewer faces then meet the piece than before, and, with
// sparePinnedFaces, only if no face the group touches has a pinned node: such a face cannot come
// along, and another piece of the tool, which this one cannot see, may then find it in its way.
// joinsFirst(f) picks faces the group starts from besides those that meet the piece; with
// noMoreMeeting the carry is applied when no more faces then meet the piece than before.
template <typename JoinsFirst>
Index carryFacesWithPiece(const ToolModel& piece, const PieceMotion& motion, Real tolerance, bool sparePinnedFaces,
                          bool noMoreMeeting, const JoinsFirst& joinsFirst, SeparationPatch& patch) {
  constexpr int kMostGrowths = 16;
  const Pose& end = motion.end();
  const Index vertexCount = patch.vertexCount();
  patch.inCluster.assign(vertexCount, 0);
  patch.carried.resize(vertexCount);
  const auto join = [&](const std::array<Index, 3>& face) {
    bool grew = false;
    for (Index v : face) {
      if (patch.inverseMasses[v] > 0 && patch.inCluster[v] == 0) {
        patch.inCluster[v] = 1;
        patch.carried[v] = end.apply(motion.start().applyInverse(patch.startPositions[v]));
        grew = true;
      }
    }
    return grew;
  };
  const int before = facesMeetingWithGroupCarried(piece, end, patch, tolerance);
  if (before == 0 && !noMoreMeeting) return 0;
  bool any = false;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    Vec3 now[3];
    shiftedFace(patch, end, patch.faces[f], {}, now);
    if (TriangleAxes(piece, now, nullptr, tolerance).meets() || joinsFirst(f)) any = join(patch.faces[f]) || any;
  }
  if (!any) return 0;
  for (int growth = 0; growth < kMostGrowths; ++growth) {
    bool grew = false;
    for (const std::array<Index, 3>& face : patch.faces) {
      if (anyInGroup(patch, face) && meetsWithGroupCarried(piece, end, patch, face, tolerance)) {
        grew = join(face) || grew;
      }
    }
    if (!grew) break;
  }
  const int after = facesMeetingWithGroupCarried(piece, end, patch, tolerance);
  if (noMoreMeeting ? after > before : after >= before) return 0;
  if (sparePinnedFaces) {
    for (const std::array<Index, 3>& face : patch.faces) {
      if (anyInGroup(patch, face) && hasPinnedNode(patch, face)) return 0;
    }
  }
  Index carried = 0;
  for (Index v = 0; v < vertexCount; ++v) {
    if (patch.inCluster[v] == 0) continue;
    patch.directions[v] = normalizedOrZero(patch.carried[v] - patch.positions[v]);
    patch.positions[v] = patch.carried[v];
    patch.moved[v] = 1;
    patch.movedInRound[v] = std::max(patch.movedInRound[v], 0);
    ++carried;
  }
  return carried;
}

const auto noOthers = [](std::size_t) { return false; };

// carryFacesWithPiece alone, on a patch the rounds have not seen, with what it leaves counted.
template <typename JoinsFirst>
SeparationCounts carryAndCount(const ToolModel& piece, const PieceMotion& motion, const SeparationSettings& settings,
                               bool sparePinnedFaces, bool noMoreMeeting, const JoinsFirst& joinsFirst,
                               SeparationPatch& patch) {
  SeparationCounts counts;
  const Index vertexCount = patch.vertexCount();
  THINTOOL_ASSERT(patch.consistent());
  if (vertexCount == 0) return counts;
  const Real tolerance = settings.clearance / 2;
  patch.movedInRound.assign(vertexCount, -1);
  counts.nodesMoved =
      carryFacesWithPiece(piece, motion, tolerance, sparePinnedFaces, noMoreMeeting, joinsFirst, patch);
  const auto nothingKnown = [](auto) { return false; };
  countWhatIsLeft(piece, motion.end(), patch, tolerance, nothingKnown, nothingKnown, counts);
  return counts;
}

}  // namespace

bool triangleMeetsPiece(const ToolModel& piece, const Vec3& a, const Vec3& b, const Vec3& c, Real tolerance) {
  const Vec3 triangle[3] = {a, b, c};
  return TriangleAxes(piece, triangle, nullptr, tolerance).meets();
}

SeparationCounts separateFromPiece(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch,
                                   const std::vector<NearPiece>& nearPieces) {
  const bool alone = nearPieces.empty();
  SeparationCounts counts;
  const Index vertexCount = patch.vertexCount();
  THINTOOL_ASSERT(patch.consistent());
  if (vertexCount == 0) return counts;
  const Real clearance = settings.clearance;
  const Pose& end = motion.end();
  const Pose& start = motion.start();
  Pose poses[kMostSamples + 1];
  motion.samplePoses(poses);
  const Aabb near = piece.bounds.expanded(clearance);
  const Real travel = farthestPath(piece, motion, poses);

  // Each round moves the faces, then the nodes, so that when the rounds run out the nodes have
  // had the last say: a face left pierced is counted, a node is never left carried through.
  // After the first round only what the previous round moved is looked at again: a face with a
  // vertex moved since, a node a face moved in this round.
  patch.movedInRound.assign(vertexCount, -1);
  patch.faceMet.assign(patch.faces.size(), 0);
  const auto touched = [&](const std::array<Index, 3>& face, int since) {
    return patch.movedInRound[face[0]] >= since || patch.movedInRound[face[1]] >= since ||
           patch.movedInRound[face[2]] >= since;
  };
  for (int round = 0; round < std::max(1, settings.maxRounds); ++round) {
    bool changed = false;
    counts.rounds = round + 1;
    for (std::size_t f = 0; f < patch.faces.size(); ++f) {
      const std::array<Index, 3>& face = patch.faces[f];
      if (round > 0 && !touched(face, round - 1)) continue;
      Vec3 now[3];
      Vec3 before[3];
      Aabb reach;
      for (int k = 0; k < 3; ++k) {
        now[k] = end.applyInverse(patch.positions[face[k]]);
        before[k] = start.applyInverse(patch.startPositions[face[k]]);
        reach.include(now[k]);
        reach.include(before[k]);
      }
      // Where the triangle was, seen from the piece, on the way along the arc.
      for (int k = 1; k < motion.samples(); ++k) {
        const Real t = Real(k) / Real(motion.samples());
        for (Index v : face) reach.include(poses[k].applyInverse(patch.startPositions[v] + (patch.positions[v] - patch.startPositions[v]) * t));
      }
      if (!near.overlaps(reach)) continue;
      const Vec3 back = normalizedOrZero((before[0] + before[1] + before[2]) - (now[0] + now[1] + now[2]));
      const TriangleAxes axes(piece, now, before, 0, back);
      if (round == 0) patch.faceMet[f] = axes.meets() ? 1 : 0;
      const Vec3 move = axes.move(clearance);
      if (move == Vec3{}) continue;
      if (!axes.meets() && motion.samples() > 1 && keptItsSideAlongArc(piece, motion, poses, patch, face)) {
        if (round == 0) ++counts.arcSpared;
        continue;
      }
      const bool pinned = hasPinnedNode(patch, face);
      // A face whose pinned node passed the piece went round it, not through: it has no side it
      // could go back to, and it is left alone unless it meets the piece at the end.
      if (pinned && !axes.meets()) continue;
      const bool aboutEdges = alone && round + 1 == std::max(1, settings.maxRounds);
      bool swung = pinned && swingAboutPinnedNodes(patch, face, piece, end, now, clearance, aboutEdges);
      if (!swung && pinned && sharesGoTooFar(patch, face, move, travel)) {
        // Shares would fling the face: about an edge, if any, is the only move it has.
        swung = alone && !aboutEdges && swingAboutPinnedNodes(patch, face, piece, end, now, clearance, true);
        if (!swung) continue;
      }
      if (!swung && !moveFace(patch, face, end.applyToDirection(move), motion, travel)) continue;
      for (Index v : face) {
        if (patch.inverseMasses[v] > 0) patch.movedInRound[v] = round;
      }
      ++counts.facesMoved;
      changed = true;
    }
    for (Index v = 0; v < vertexCount; ++v) {
      if (!(patch.inverseMasses[v] > 0) || (round > 0 && patch.movedInRound[v] != round)) continue;
      const NodeVerdict verdict = putNodeOutside(piece, motion, poses, clearance, v, patch, &nearPieces);
      if (round == 0 && verdict.sparedByArc) ++counts.arcSpared;
      if (!verdict.fix) continue;
      patch.movedInRound[v] = round;
      ++counts.nodesMoved;
      changed = true;
    }
    if (!changed) break;
    if (round + 1 == std::max(1, settings.maxRounds)) {
      moveStuckFacesTogether(piece, motion, poses, clearance, nearPieces, patch);
    }
  }

  const Real tolerance = clearance / 2;
  if (counts.rounds == std::max(1, settings.maxRounds)) {
    counts.nodesMoved += carryFacesWithPiece(piece, motion, tolerance, false, false, noOthers, patch);
  }
  counts.nodesMoved += slidePinnedFacesClear(piece, motion, poses, clearance, patch);
  // A movable node the first round judged and left, and nothing moved since, is outside; a face
  // that met nothing in the first round, none of whose nodes moved since, still meets nothing.
  countWhatIsLeft(
      piece, end, patch, tolerance,
      [&](Index v) { return patch.movedInRound[v] < 0 && patch.inverseMasses[v] > 0; },
      [&](std::size_t f) { return patch.faceMet[f] == 0 && !touched(patch.faces[f], 0); }, counts);
  return counts;
}

SeparationCounts carryMeetingFaces(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch) {
  Pose poses[kMostSamples + 1];
  motion.samplePoses(poses);
  SeparationCounts counts = carryAndCount(piece, motion, settings, true, false, noOthers, patch);
  // Another piece's last pass may have pushed a node through this one after this one's passes had
  // judged it: it ends outside, carried through by both readings, and no face of it meets the piece
  // (generated seed 2098: jaws turning 173° a step took turns to push a node across each other,
  // and the second jaw's last pass left it across the first). Its faces go along with the piece.
  const auto carriedThrough = [&](std::size_t f) {
    for (Index v : patch.faces[f]) {
      Vec3 local;
      if (patch.inverseMasses[v] > 0 &&
          judgeNode(piece, motion, poses, patch.startPositions[v], patch.positions[v], patch.enclosed[v] != 0,
                    settings.clearance, local).fix) {
        return true;
      }
    }
    return false;
  };
  bool anyCarriedThrough = false;
  for (std::size_t f = 0; f < patch.faces.size() && !anyCarriedThrough; ++f) anyCarriedThrough = carriedThrough(f);
  if (anyCarriedThrough) {
    const SeparationCounts through = carryAndCount(piece, motion, settings, true, true, carriedThrough, patch);
    if (through.nodesMoved > 0) {
      const Index moved = counts.nodesMoved;
      counts = through;
      counts.nodesMoved += moved;
    }
  }
  if (counts.facesPierced == 0) return counts;
  const Index slid = slidePinnedFacesClear(piece, motion, poses, settings.clearance, patch);
  if (slid == 0) return counts;
  counts.nodesMoved += slid;
  counts.nodesInside = 0;
  counts.facesPierced = 0;
  const auto nothingKnown = [](auto) { return false; };
  countWhatIsLeft(piece, motion.end(), patch, settings.clearance / 2, nothingKnown, nothingKnown, counts);
  return counts;
}

SeparationCounts keepNodesOutside(const ToolModel& piece, const PieceMotion& motion,
                                  const SeparationSettings& settings, SeparationPatch& patch) {
  SeparationCounts counts;
  THINTOOL_ASSERT(patch.consistent());
  Pose poses[kMostSamples + 1];
  motion.samplePoses(poses);
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    if (!(patch.inverseMasses[v] > 0)) continue;
    if (putNodeOutside(piece, motion, poses, settings.clearance, v, patch, nullptr).fix) ++counts.nodesMoved;
  }
  const auto nothingKnown = [](auto) { return false; };
  countWhatIsLeft(piece, motion.end(), patch, settings.clearance / 2, nothingKnown, nothingKnown, counts);
  return counts;
}

SeparationCounts carryCrossedFaces(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch) {
  Pose poses[kMostSamples + 1];
  motion.samplePoses(poses);
  const auto crossed = [&](std::size_t f) {
    const std::array<Index, 3>& face = patch.faces[f];
    if (motion.samples() > 1) return !keptItsSideAlongArc(piece, motion, poses, patch, face);
    Vec3 now[3];
    Vec3 before[3];
    for (int k = 0; k < 3; ++k) {
      now[k] = motion.end().applyInverse(patch.positions[face[k]]);
      before[k] = motion.start().applyInverse(patch.startPositions[face[k]]);
    }
    return !TriangleAxes(piece, now, before, 0).keptItsSide();
  };
  return carryAndCount(piece, motion, settings, false, true, crossed, patch);
}

std::string validateSeparationSettings(const SeparationSettings& settings) {
  if (!(settings.clearance > 0) || !std::isfinite(settings.clearance)) {
    return "separation.clearance must be positive and finite (m)";
  }
  if (settings.maxRounds < 1) return "separation.maxRounds must be at least 1";
  if (!(settings.maxTurnPerSample > 0) || !std::isfinite(settings.maxTurnPerSample)) {
    return "separation.maxTurnPerSample must be positive and finite (radians)";
  }
  return {};
}

}  // namespace thintool
