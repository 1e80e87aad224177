// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The last word: after the soft solver has moved the nodes for the step (links, pressure, its
/// own contacts), every soft feature near a tool piece is put back on its side of the piece, so
/// that no soft node ends a step inside a tool and no tool feature ends it through a soft face.
///
/// Sources: the moves are position projections after Müller et al., "Position based dynamics"
/// (2007), a face's move shared by its nodes in proportion to inverse mass; whether a triangle
/// meets a convex piece is the separating-axis test (Gottschalk, Lin and Manocha, "OBBTree", 1996:
/// the piece's face normals, the triangle's normal, and the cross products of their edges).
/// Deviations, and why:
/// - A node's side is read from its own path, not from the nearest face: its straight move from the
///   start of the step to where the solver left it, seen from the piece (a turning piece on its
///   arc, the rotation interpolated about one axis and sampled every `maxTurnPerSample`). A node
///   inside the piece leaves through the face its path entered by; a node whose path went in by one
///   face and out by a face turned away from it (carried through) goes back in front of the face it
///   entered by; a node on no face of its body (a tetrahedral body's interior node) cannot ride
///   round a piece's rounded side: any way through counts. It goes back in front of the face it
///   entered by too, unless it would land there in another piece near this one: then where it was
///   in the piece's frame at the start, outside every piece of its tool. On the arc a path can
///   come back out by the face it entered by; it was carried through when, inside, it came nearer
///   to a face turned away from that one (past a plate's mid-plane). Under a turn the node goes
///   back only when both readings of the path, straight in the piece's frame and straight in the
///   world against the arc, take it through (either alone is wrong for some node: the first for
///   one the turning piece never reached, the second for one that rode on its face). The nearest
///   face would send a node that crossed more than half the piece's thickness out of the far side.
///   Where both readings are wrong together, a piece that ends inside a closed body it was outside
///   of, the glue reads the motion along the chord alone (PieceMotion::alongChord) or carries the
///   faces crossed on the arc (carryCrossedFaces).
/// - A face must keep a side it had at the start of the step: some separating axis (the piece's
///   face normals, the triangle's normal at either end, the cross products of their edges)
///   separates it from the piece on the same side at both ends; under a turn, a face that ends
///   clear must also have kept one in every sample of the arc, else the piece never reached it.
///   One that does not (pierced, or gone through a thin piece between its nodes) is translated
///   back to such a side along the axis that best trades the move's length against how well it
///   points back the way the face came, length / (0.1 + cos): the shortest move alone lets two
///   faces that share an edge along a needle push it to opposite sides round after round. A face
///   that still meets the piece goes instead straight back along its own motion relative to the
///   piece, until it clears, when that is the shorter
///   move: a face whose only side at the start lay across a long needle went along the needle's
///   length. A face that already met the piece at the start goes back that way; without such a
///   motion, to the side it was nearest to.
/// - A face move that would take one of its nodes further from where the solver left it than both
///   the node's place at the start of the step, carried along with the piece, and the move's own
///   length (counted up to twice what the step explains: the piece's farthest path and the face's
///   own move in the solve) puts that node there instead, where it was beside the piece then; the
///   face's other nodes take their shares. Faces that share nodes otherwise add their rounds' moves
///   up, half a metre in a step on a pinned sheet, and a face stretched across a turning needle
///   leaves it within its own plane, as far as the needle is long. Sending the whole face back made
///   the nodes beside a moving piece ride along with it.
/// - A face with a pinned node cannot translate: its free nodes go beyond a face plane of the
///   piece that its pinned nodes are beyond. Moved by shares of a translation instead, they go no
///   further than twice what the step explains (the path of the piece's farthest-going corner and
///   their own move in the solve); past that the face swings about an edge of a lone piece, or
///   waits for the slide below.
/// - Face moves and node moves alternate (Gauss–Seidel) for at most `maxRounds`, nodes last. When
///   the rounds run out with faces still pierced (faces that want a shared node on opposite
///   sides), their nodes move together by the shortest translation that clears them all, carries
///   none of their faces across the piece and pushes none into another piece near it (the other
///   jaw), where the two would move the group on and on.
/// - A face with a pinned node left pierced after that lies across a rim: the piece swept past the
///   pinned node and left its neighbours on the far side. Its free nodes slide together, along the
///   piece's face and past the rim, by the shortest translation (along a face normal of the piece
///   or halfway between two) that clears every face they touch, never through the piece and never
///   further than twice the path of the piece's farthest-going corner in the step. What is still
///   violated then is counted, never hidden.

#include "tool/PieceMotion.h"
#include "tool/ToolModel.h"

#include <thintool/response/ResponseTypes.h>

#include <array>
#include <string>
#include <vector>

namespace thintool {

/// A unit separating axis (piece frame) with the extents along it of the piece, grown by a length,
/// and of a triangle.
struct SeparatingAxis {
  Vec3 axis;
  Real pieceLow = 0;
  Real pieceHigh = 0;
  Real low = 0;
  Real high = 0;
};

/// The soft features near one tool piece, in the world frame, gathered by the glue.
struct SeparationPatch {
  std::vector<Vec3> positions;       ///< where each node is: the solver's place, corrected in place
  std::vector<Vec3> startPositions;  ///< where each node began the step
  std::vector<Vec3> solvedPositions;  ///< where the solver left each node (positions before the stage)
  std::vector<Real> inverseMasses;   ///< 0: pinned, never moved
  /// 1: the node is on no face of its body, inside a volume's surface (a tetrahedral body's
  /// interior node). It never lies against a piece: any path of it through one went through.
  std::vector<unsigned char> enclosed;
  std::vector<std::array<Index, 3>> faces;  ///< patch vertex indices
  std::vector<Index> nodeIds;        ///< the caller's ids, one per vertex
  /// Output: the stage moved the vertex, and the direction of its last move (world, unit): the
  /// contact normal the glue needs to make the node's velocity agree with the move.
  std::vector<unsigned char> moved;
  std::vector<Vec3> directions;
  /// Scratch of the stage: the round that last moved each vertex (-1: none), and which faces met
  /// the piece in the first round.
  std::vector<int> movedInRound;
  std::vector<unsigned char> faceMet;
  /// Scratch of the stage: the vertices moved together when the rounds leave faces pierced.
  std::vector<unsigned char> inCluster;
  std::vector<Vec3> carried;  ///< scratch: where the last resort would carry each node of the group
  /// Scratch of the translation that moves stuck faces together: the separating axes of each face
  /// and node of the group, each run ending at its groupAxesEnd entry.
  std::vector<SeparatingAxis> groupAxes;
  std::vector<std::size_t> groupAxesEnd;

  Index vertexCount() const { return static_cast<Index>(positions.size()); }
  /// The per-vertex arrays agree and every face's vertices are in range: what addVertex and the
  /// glue's gather guarantee the stage (checked by THINTOOL_ASSERT, core/Assert.h).
  bool consistent() const {
    const std::size_t n = positions.size();
    if (startPositions.size() != n || solvedPositions.size() != n || inverseMasses.size() != n ||
        enclosed.size() != n || nodeIds.size() != n || moved.size() != n || directions.size() != n) {
      return false;
    }
    for (const std::array<Index, 3>& face : faces) {
      for (Index v : face) {
        if (v >= n) return false;
      }
    }
    return true;
  }
  Index addVertex(Index id, const Vec3& start, const Vec3& end, Real inverseMass, bool isEnclosed = false) {
    nodeIds.push_back(id);
    startPositions.push_back(start);
    solvedPositions.push_back(end);
    positions.push_back(end);
    inverseMasses.push_back(inverseMass);
    enclosed.push_back(isEnclosed ? 1 : 0);
    moved.push_back(0);
    directions.push_back({});
    return static_cast<Index>(positions.size() - 1);
  }
  void clear() {
    positions.clear();
    startPositions.clear();
    solvedPositions.clear();
    inverseMasses.clear();
    enclosed.clear();
    faces.clear();
    nodeIds.clear();
    moved.clear();
    directions.clear();
    movedInRound.clear();
    faceMet.clear();
    inCluster.clear();
  }
};

/// Another piece near the one the stage separates from (the other jaw, another tool), where it
/// ends the step. A pose that is not finite stands for a piece whose place is unknown.
struct NearPiece {
  const ToolModel* model = nullptr;
  Pose end;
};

/// Puts the patch's nodes and faces back on their side of the piece (see the file comment).
/// Writes positions and moved; returns what it did and what is left. nearPieces: the other pieces near
/// this one. With none, a face may swing about an edge of it; with some, the translation that moves
/// stuck faces together pushes no face into one of them that it did not meet before.
SeparationCounts separateFromPiece(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch,
                                   const std::vector<NearPiece>& nearPieces = {});

/// The last resort alone, for a tool whose pieces keep undoing each other's moves (two jaws with a
/// face between them): the movable nodes of the faces that meet the piece at the end of the step
/// go where they stood in the piece's frame at its start, with the nodes of the faces that would
/// then meet it, as separateFromPiece does when its rounds run out. The pieces of one rigid body
/// share that motion, so a node carried by one is where every other piece left it room at the
/// start. A group that touches a face with a pinned node stays, since that face cannot come along
/// and another piece may meet it; the free nodes of a face with a pinned node that still meets the
/// piece then slide past its rim, as separateFromPiece's do. So do the nodes of a face with a node
/// that ends outside the piece but was carried through it by both readings of its path (another
/// piece's last pass pushed it across this one), when no more faces then meet the piece. Writes
/// positions and moved; returns what it did and what is left.
SeparationCounts carryMeetingFaces(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch);

/// The nodes' last say over a tool whose pieces took turns until the passes ran out: every movable
/// node that ends inside the piece, or was carried through it by both readings of its path, goes
/// back out by the face it entered by, as in separateFromPiece's rounds. Within one piece the nodes
/// move last; across pieces, another piece's face moves and the last resort come after this
/// piece's rounds, and a face move of one jaw left a node inside the other (generated seed 14597:
/// jaws 54 mm apart turning 148° a step through a sheet of 82 mm faces). A face this leaves
/// pierced is counted; a node is not left inside. Writes positions and moved; returns what it did
/// and what is left.
SeparationCounts keepNodesOutside(const ToolModel& piece, const PieceMotion& motion,
                                  const SeparationSettings& settings, SeparationPatch& patch);

/// The repair for a piece that ended the step inside a closed soft body it was outside of at the
/// start, which the glue finds by the winding number of the piece's centre, when reading the paths
/// along the chord did not keep it out: a path that neither reading takes through the piece let it
/// in (a needle turning half a turn a step meets a face on its arc and ends beyond it, the face
/// beyond the same end of the needle in its frame at both ends of the step). The movable nodes of
/// every face that lost its side along the arc (along the chord without a turn), and of every face
/// that meets the piece, are carried with the piece to where they stood in its frame at the start,
/// as the last resort carries faces, with the nodes of the faces that would then meet it; applied
/// when no more faces then meet the piece than before. Writes positions and moved; returns what it
/// did and what is left.
SeparationCounts carryCrossedFaces(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch);

/// Whether triangle (a, b, c) and the piece, all in the piece's frame, overlap by more than
/// tolerance along every separating axis.
bool triangleMeetsPiece(const ToolModel& piece, const Vec3& a, const Vec3& b, const Vec3& c, Real tolerance);

/// Describes the first invalid setting, or returns an empty string.
std::string validateSeparationSettings(const SeparationSettings& settings);

}  // namespace thintool
