// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What the force model (force/ContactForce.h) is told and what it reports, as a program sets and
/// reads them.

#include <thintool/core/Math.h>
#include <cstdint>
#include <functional>

namespace thintool {

enum class DeformationMeasure : std::uint8_t { CentroidDisplacement, Indentation };

/// F = k·xⁿ + λ·xⁿ·ẋ, clamped at 0.
struct HuntCrossley {
  Real stiffness = 100;  ///< k (N/mⁿ, >= 0)
  Real damping = 50;     ///< λ (N·s/mⁿ⁺¹, >= 0); λ/k is the model's c (s/m)
  Real exponent = 1.5;   ///< n (> 0): 1 for a flat face pressing, 3/2 for a rounded tip (Hertz)
};

/// The force of one face for a deformation x (m) and its rate ẋ (m/s): a replacement for the
/// Hunt–Crossley law. A negative or non-finite result counts as 0.
using ForceLaw = std::function<Real(Real deformation, Real rate)>;

struct ForceSettings {
  /// Off, no force is computed, reported or applied (a dynamic tool then receives the response's
  /// reaction, see ResponseSettings).
  bool enabled = false;
  DeformationMeasure measure = DeformationMeasure::Indentation;
  HuntCrossley huntCrossley;
  /// Replaces huntCrossley when set.
  ForceLaw law;
  /// How far beyond the skin a soft node still touches the tool (m, >= 0).
  Real touchTolerance = 0.001;
  /// Cut-off frequency (Hz, > 0) of the first-order low-pass filter on ẋ; 0 leaves ẋ unfiltered.
  Real rateCutoff = 30;
  /// The point the reported torque is taken about, in the tool body's frame (m): the grip, say.
  Vec3 torquePoint;
  /// A dynamic tool receives the force as its reaction, in place of the response's.
  bool applyToDynamicTool = true;
};

/// The force of one soft face in contact, on the tool.
struct FaceForce {
  Index softFace = kInvalidIndex;  ///< in the soft body
  Vec3 point;                      ///< world: the face's centroid
  Vec3 force;                      ///< world (N), on the tool
  Real deformation = 0;            ///< x (m)
  Real rate = 0;                   ///< filtered ẋ (m/s)
};

}  // namespace thintool
