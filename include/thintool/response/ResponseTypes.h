// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What the response (response/Response.h) and the last word (response/Separation.h) are told,
/// and what they report, as a program sets and reads them.

#include <thintool/core/Math.h>

namespace thintool {

enum class ResponseKind { Constraint, PaperForce, None };

/// Coulomb friction between the tool and the soft nodes it moves, in position form (after
/// Macklin et al., "Unified particle physics for real-time applications", 2014, §6.1): a moved
/// node's tangential motion relative to the tool's surface is undone while it is within
/// staticCoefficient × the node's normal move (it sticks), and reduced by kineticCoefficient × that
/// move otherwise (it slides). The normal move stands for the normal force, N = m·d/dt². On by
/// default, as stock Bullet's soft–rigid contact has friction; off, it costs nothing.
///
/// The Bullet glue puts its own coefficients in their place by default, stock Bullet's
/// (BulletSettings::frictionFromBodies).
struct FrictionSettings {
  bool enabled = true;
  Real staticCoefficient = 0.8;   ///< μs (>= 0)
  Real kineticCoefficient = 0.6;  ///< μk (>= 0, <= μs)
};

struct ResponseSettings {
  ResponseKind kind = ResponseKind::Constraint;
  /// PaperForce: k of f = k·t (N/m, > 0).
  Real stiffness = 1000;
  /// Constraint: the node guard. Off, only nodes of faces the rays hit are moved.
  bool guardNodes = true;
  /// Constraint only: friction at the moved nodes (in Bullet, see also BulletSettings).
  FrictionSettings friction;
};

/// Net force on the tool (N) and torque about the tool's origin (N·m) from this step's response.
struct Wrench {
  Vec3 force;
  Vec3 torque;
};

struct SeparationSettings {
  /// Runs the stage (in thintool::SoftBodySolver). Off, it costs nothing.
  bool enabled = true;
  /// How far outside the piece a corrected node or face is put (m, > 0): rounding in Bullet's
  /// float build must not carry it back in.
  Real clearance = 1e-5;
  /// Most alternations of node and face moves in a step (>= 1).
  int maxRounds = 32;
  /// Largest turn of the piece between two samples of its arc (radians, > 0).
  Real maxTurnPerSample = Real(5) * kPi / 180;
};

/// What the stage did to one patch, and what it left.
struct SeparationCounts {
  Index nodesMoved = 0;    ///< node moves (a node moved in two rounds counts twice)
  Index facesMoved = 0;    ///< face moves
  Index nodesInside = 0;   ///< left inside the piece by more than half the clearance (expected 0)
  Index facesPierced = 0;  ///< left meeting the piece by more than half the clearance (expected 0)
  /// Nodes and faces, in the first round, that the chord reading takes through a turning piece and
  /// the arc reading spares: where the glue may have to choose between the two.
  Index arcSpared = 0;
  int rounds = 0;

  void accumulate(const SeparationCounts& o) {
    nodesMoved += o.nodesMoved;
    facesMoved += o.facesMoved;
    nodesInside += o.nodesInside;
    facesPierced += o.facesPierced;
    arcSpared += o.arcSpared;
    rounds = rounds > o.rounds ? rounds : o.rounds;
  }
};

}  // namespace thintool
