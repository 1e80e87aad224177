// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Swept (continuous) detection between a tool piece and the soft faces near it, over the motion
/// of one step: the tool from its previous to its current pose, each soft node from its position
/// at the start of the step to its predicted end.
///
/// Beyond the paper, which tests one instant and so lets a tool that moves farther than its
/// thickness per step pass through the tissue. Everything happens in the tool's own frame, where
/// the tool stands still and the soft surface moves; there each soft node's motion is taken as the
/// straight segment between where it starts (seen in the tool's previous pose) and where it ends
/// (seen in its current pose), which is exact for a translating tool and, for a rotating one,
/// replaces the arc by its chord.
///
/// Three kinds of contact, each decided by which side the soft feature came from:
/// - SoftNode: a soft node's segment meets the tool grown by the skin (Cyrus–Beck clipping); its
///   side is the face it enters through, or, for a node already inside, the face it entered
///   through in an earlier step (SideMemory), or failing that the face it is least inside of;
/// - ToolPoint: a tool point (a sample node or a corner of the hull) crosses a moving soft face
///   (root of the coplanarity cubic), or ends within the skin of it; its side is the side of the
///   face the point was on at the start of the step (remembered per face when it starts on it);
/// - Edge: an edge of the tool crosses a moving soft edge (root of the coplanarity quadratic), or
///   ends within the skin of it; its side is the side of the tool edge's line the soft edge was on.
/// Each contact asks the response to return its soft point to that side, the skin away from the
/// tool's surface. The paper's checks have nothing to filter here: the side comes from the motion.

#include "core/StepStamps.h"
#include "detection/Detection.h"

#include <cstdint>
#include <vector>

namespace thintool {

/// Which side of the tool each soft node and soft face was on, carried across steps by a
/// (tool piece, soft body) pair. Sized to the soft body; forgetting is O(1).
class SideMemory {
 public:
  void resize(Index softNodes, Index softFaces);
  /// Starts a step: what was recorded in the previous step stays readable during this one.
  void beginStep() {
    m_nodeStamps.beginStep();
    m_faceStamps.beginStep();
  }
  /// Forgets everything, for a pair that separated.
  void forget() {
    m_nodeStamps.forget();
    m_faceStamps.forget();
  }

  /// The tool face a soft node entered through, or kInvalidIndex.
  Index nodeSide(Index softNode) const {
    return softNode < m_nodeStamps.size() && m_nodeStamps.stampedRecently(softNode) ? m_nodePlane[softNode]
                                                                                   : kInvalidIndex;
  }
  void setNodeSide(Index softNode, Index plane) {
    if (softNode < m_nodeStamps.size()) {
      m_nodePlane[softNode] = plane;
      m_nodeStamps.stamp(softNode);
    }
  }
  /// +1 or -1: the side of the soft face's own normal the tool was on; 0 when unknown.
  int faceSide(Index softFace) const {
    return softFace < m_faceStamps.size() && m_faceStamps.stampedRecently(softFace) ? m_faceSideSign[softFace] : 0;
  }
  void setFaceSide(Index softFace, int side) {
    if (softFace < m_faceStamps.size()) {
      m_faceSideSign[softFace] = static_cast<std::int8_t>(side);
      m_faceStamps.stamp(softFace);
    }
  }

 private:
  std::vector<Index> m_nodePlane;
  StepStamps m_nodeStamps;
  std::vector<std::int8_t> m_faceSideSign;
  StepStamps m_faceStamps;
};

/// Scratch memory of swept detection, reused by every step and pair.
class SweptWorkspace {
 private:
  friend void detectSwept(const StepContext&, const SoftPatch&, SideMemory&, SweptWorkspace&, DetectionResult&);
  std::vector<Vec3> m_start;  ///< patch vertices at the start of the step, in the tool's previous frame
  std::vector<Vec3> m_end;    ///< at the end, in its current frame
  std::vector<std::uint8_t> m_valid;
  std::vector<Pose> m_arc;  ///< the piece along its arc, when detection follows it (StepContext)
};

/// Finds the contacts of the tool piece moving from the context's previousPose to its pose against
/// the soft patch (positions at the end of the step, previousPositions at its start), keeping the
/// context's skin. Allocates nothing once the workspace and the result have grown.
void detectSwept(const StepContext& step, const SoftPatch& patch, SideMemory& memory, SweptWorkspace& workspace,
                 DetectionResult& out);

}  // namespace thintool
