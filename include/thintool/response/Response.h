// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What the soft body does about this step's contacts.
///
/// - ResponseKind::Constraint (default): a position projection. Every node of every hit soft face
///   is moved, along the contact's normal, to the entry side of the tool face the contact came
///   through, plus the skin. Contacts are applied in order (Gauss–Seidel), so a node under two
///   faces of the tool (a rim) ends outside both planes. A projection has no stiffness and no
///   time-step limit: the node is where it must be at the end of the step, and its velocity
///   follows from the move. The equivalent force on the tool is Σ m·Δx/dt².
/// - ResponseKind::PaperForce: the paper's eq. (2), f = k·t along the contact normal, t being the
///   penetration into the tool's skin, spread over the face's nodes by the hit's barycentric
///   weights. Bullet's classic solver clears node forces before collisions are processed, so a
///   force added then is lost, and one added after the step acts a step late. We apply f as the
///   displacement it causes within the step under Bullet's symplectic Euler, Δx = f·m⁻¹·dt², so
///   it acts in the step it was found in. Like any explicit penalty it is stable only while
///   k·dt²/m stays small (about < 1 for a node alone); the stiff-case tests chart where it fails.
/// - ResponseKind::None: contacts are reported, nothing is moved.

#include <thintool/detection/Detection.h>

#include <cstdint>
#include <vector>

namespace thintool {

enum class ResponseKind { Constraint, PaperForce, None };

struct ResponseSettings {
  ResponseKind kind = ResponseKind::Constraint;
  /// PaperForce: k of f = k·t (N/m, > 0).
  Real stiffness = 1000;
  /// Constraint: also give Bullet's soft solver a contact (btSoftBody::RContact) for each moved
  /// node, carrying the same entry-side plane, so that links and pressure pulling the node back
  /// into the tool during the solver's iterations are corrected there too.
  bool solverContacts = true;
  /// Fraction of the remaining penetration each solver iteration removes (Bullet's kKHR for
  /// static and kinematic bodies, kCHR for dynamic ones), in (0, 1].
  Real solverHardness = 1;
};

/// A soft node's move, and the plane the move put it on.
struct NodeCorrection {
  Index vertex = kInvalidIndex;  ///< index in SoftPatch::positions
  Vec3 displacement;             ///< world (m)
  Vec3 planeNormal;              ///< world, unit, out of the tool
  Real planeOffset = 0;          ///< dot(x, planeNormal) + planeOffset = distance in front of the skin (m)
};

/// Net force on the tool (N) and torque about the tool's origin (N·m) from this step's response.
struct Wrench {
  Vec3 force;
  Vec3 torque;
};

class ResponseWorkspace {
 private:
  friend void computeResponse(const ToolModel&, const Pose&, const SoftPatch&, const std::vector<Contact>&, Real,
                              Real, const ResponseSettings&, ResponseWorkspace&, std::vector<NodeCorrection>&,
                              Wrench&);
  std::vector<Vec3> m_positions;
  std::vector<Index> m_slot;  ///< per patch vertex: its entry in the output, or kInvalidIndex
};

/// Turns contacts into node corrections and the wrench on the tool, for a step of dt seconds with
/// the given skin (m). Nodes of zero inverse mass (pinned) are never moved. Allocates nothing
/// once the workspace and outCorrections have grown to the patch size.
void computeResponse(const ToolModel& model, const Pose& toolPose, const SoftPatch& patch,
                     const std::vector<Contact>& contacts, Real skin, Real dt, const ResponseSettings& settings,
                     ResponseWorkspace& workspace, std::vector<NodeCorrection>& outCorrections, Wrench& outWrench);

}  // namespace thintool
