// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What every stage of a step reads about it: one tool piece moving over the step, and the skin
/// it keeps. The glue fills one per piece and soft body; the stages take it first.

#include "tool/ToolModel.h"

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
};

}  // namespace thintool
