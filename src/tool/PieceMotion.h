// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A tool piece's motion over one step, read along its arc: what the last word and swept
/// detection sample when the tool turns.

#include <thintool/core/Math.h>

namespace thintool {

/// How a piece moves during the step. The body that carries it goes from its pose at the start to
/// its pose at the end, its origin in a straight line and its turn about one fixed axis; the piece
/// rides on it at inBody, so a piece off the body's origin (a jaw) swings round that origin as
/// the body turns. samples() keeps each sample's turn under the settings' largest.
class PieceMotion {
 public:
  /// Samples of the arc: a turn of 180° at 5° a sample needs 36; the cap only guards settings.
  static constexpr int kMostSamples = 64;

  PieceMotion(const Pose& bodyStart, const Pose& bodyEnd, Real maxTurnPerSample, const Pose& inBody = Pose{});
  /// The same motion read along the chord alone: one sample, so that a node or face that the
  /// straight path in the piece's frame takes through goes back, whatever the arc says. For a
  /// piece that ended inside a closed body it was outside of at the start, the arc reading is the
  /// wrong one.
  PieceMotion alongChord() const;
  /// The piece's pose at fraction t of the step.
  Pose at(Real t) const;
  /// The piece's pose at each sample of the arc, start and end included: samples() + 1 of them
  /// into out, which holds at least kMostSamples + 1.
  void samplePoses(Pose* out) const;
  int samples() const { return m_samples; }
  const Pose& start() const { return m_start; }
  const Pose& end() const { return m_end; }
  Real turn() const { return m_angle; }
  /// The body's pose at the start: the piece turns round its origin.
  const Pose& bodyStart() const { return m_bodyStart; }

 private:
  Pose m_bodyStart;
  Pose m_bodyEnd;
  Pose m_inBody;
  Pose m_start;  // the piece's
  Pose m_end;
  Vec3 m_axis{1, 0, 0};  // in the body's start frame
  Real m_angle = 0;
  int m_samples = 1;
};

}  // namespace thintool
