// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What every stage of a step reads about it: one tool piece moving over the step, and the skin
/// it keeps. The glue fills one per piece and soft body; the stages take it first.

#include "tool/PieceMotion.h"
#include "tool/ToolModel.h"

#include <limits>

namespace thintool {

struct StepContext {
  const ToolModel& model;  ///< the piece, in its own frame
  Pose previousPose;       ///< where the piece was at the start of the step (world)
  Pose pose;               ///< where it is at the end (world)
  Real dt = 0;             ///< the step (s, > 0)
  Real skin = 0;           ///< the margin kept in front of the piece's faces this step (m, >= 0)
  /// How fast a soft point that began the step inside the skin, outside the tool, is put back out
  /// to the full skin (m/s, > 0; infinite: at once). See ToolOptions::skinGrowthSpeed.
  Real skinGrowthSpeed = 1;
  /// Where the piece sits on the body that carries it, which turns it about the body's origin.
  Pose inBody{};
  /// Swept detection follows a turning piece's arc in samples of at most this turn (radians);
  /// 0 reads its motion as the chord alone.
  Real maxTurnPerSample = 0;

  /// The piece's motion along its arc (one sample, the chord, when maxTurnPerSample is 0).
  PieceMotion motion() const {
    const Pose outOfBody{inBody.rotation.transposed(), inBody.rotation.transposeTimes(-inBody.translation)};
    const Real perSample = maxTurnPerSample > 0 ? maxTurnPerSample : std::numeric_limits<Real>::max();
    return PieceMotion(previousPose * outOfBody, pose * outOfBody, perSample, inBody);
  }
};

}  // namespace thintool
