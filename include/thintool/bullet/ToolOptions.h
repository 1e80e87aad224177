// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Everything a tool can be told, grouped by pipeline stage. The defaults suit the paper's scene
/// (a 0.8 × 0.02 × 0.8 m plate into a 128-face ball of radius 1 m) and scale with the tool's size.

#include <thintool/detection/Detection.h>
#include <thintool/force/ContactForce.h>
#include <thintool/response/Response.h>
#include <thintool/response/Separation.h>
#include <thintool/tool/ToolModel.h>

#include <string>

namespace thintool {

struct ToolOptions {
  /// Names the tool in error messages and reports; empty picks "tool <n>".
  std::string name;

  SamplingSettings sampling;
  AssociationSettings association;
  /// Deepest a soft face is looked for below a tool node (m, >= 0); 0 picks the tool's thickness.
  Real probeDepth = 0;
  /// Contact margin kept between the tool's faces and the soft surface (m). Negative uses each
  /// soft body's own collision margin (btSoftBody::getCollisionShape()->getMargin()), as Bullet's
  /// stock soft–rigid contact does.
  Real skin = -1;
  /// How fast (m/s) a pair that begins with soft nodes already inside the skin (a body created
  /// within the tool's margin, a tool registered or set down onto tissue) grows its skin from the
  /// closest node's distance to the full skin. Pushed out to the full skin in one step, those nodes
  /// would leave at up to skin/dt: 15 m/s from Bullet's default 0.25 m margin at 60 Hz. Infinite:
  /// at once.
  Real skinGrowthSpeed = 1;

  /// Swept detection (detection/SweptDetection.h): contacts over the whole motion of a step, so a
  /// tool moving farther than its thickness per step never passes through. Off, the paper's
  /// discrete rays and checks run at the end of the step only, as in the paper.
  bool swept = true;
  /// The paper's filters; used by the discrete detection only (swept detection knows each
  /// contact's side from the motion).
  FilterSettings filters;
  ResponseSettings response;
  /// The last word (response/Separation.h): after Bullet's soft solver, no soft node is left
  /// inside the tool and no soft face pierced by it. Runs only in a world whose soft-body solver is
  /// a thintool::SoftBodySolver.
  SeparationSettings separation;
  /// The tissue's force on the tool (force/ContactForce.h): off by default.
  ForceSettings force;

  /// The paper's algorithm as published: discrete rays, association, both checks, and no last
  /// word after the soft solver (set separation.enabled for the paper's detection with it).
  static ToolOptions paper() {
    ToolOptions options;
    options.swept = false;
    options.separation.enabled = false;
    options.response.friction.enabled = false;  // the paper's response is frictionless
    return options;
  }
  /// The paper's Fig. 7 (right) ablation: discrete rays only, without association and both checks.
  static ToolOptions rayOnly() {
    ToolOptions options = paper();
    options.association.enabled = false;
    options.filters.check1 = false;
    options.filters.check2 = false;
    return options;
  }
};

/// Describes the first invalid option, or returns an empty string.
std::string validateToolOptions(const ToolOptions& options);

}  // namespace thintool
