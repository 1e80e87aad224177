// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Everything a tool can be told, grouped by pipeline stage. The defaults suit the paper's scene
/// (a 0.8 × 0.02 × 0.8 m plate into a 128-face ball of radius 1 m) and scale with the tool's size.

#include <thintool/core/Api.h>
#include <thintool/detection/DetectionTypes.h>
#include <thintool/force/ForceTypes.h>
#include <thintool/response/ResponseTypes.h>
#include <thintool/tool/ToolModelSettings.h>

#include <limits>
#include <optional>
#include <string>

namespace thintool {

/// The energy guard of thintool::SoftBodySolver. A tool's contacts move soft nodes in Bullet's
/// collision pass, and Bullet's solve turns every move into velocity, its holds and links carrying
/// the kick to the neighbours; a pressure body squeezed against a tool, or a sheet that Bullet's
/// own solve already shakes, can then gain energy step after step until it flies apart. A passive
/// contact cannot do that: a node hit by a tool point moving at u leaves at about u at most, and
/// gains at most ½·m·u². So, for each soft body that the tool's response moved in the collision
/// pass or, for a kinematic or static tool, its holds hold in the solve (a dynamic tool gives way
/// and takes their push back), after Bullet's solve and the last word:
/// - no node moves faster than the faster of: speedFactor times the faster of 1 m/s and the tool's
///   points at the nodes the response moved or the holds hold (a point no faster than the tool's
///   fastest corner), and the body's fastest node as Bullet predicted it before the solve (its
///   forces and gravity applied). The factor is not applied to the predicted speed, which carries
///   the last step's: a body the guard holds to twice the tool's speed would otherwise be allowed
///   twice that in the next step, and so on. A pressure body's prediction is no measure of its
///   motion: Bullet applies the pressure there and the links take most of it back in the solve (a
///   light vessel is predicted at 60 to 200 m/s where it ends its steps at 7). For such a body,
///   measured in the step before, the predicted speed counts no higher than the fastest node the
///   guard left then, or speedFactor times the fastest of the latest step the guard did not act in,
///   which the guard measures while a guarding tool's pair with the body is live. The bound holds
///   for a node's velocity after the last word and, where the tool's last word runs
///   (separation.enabled), for its move in Bullet's solve, shortened to it before the last word,
///   which puts back on its side a node the shorter move leaves in the tool;
/// - the body's kinetic energy about its centre of mass, as the solve left it, is at most (1 +
///   energySlack) times the same energy before the solve (each node's motion as Bullet set it up,
///   (x - q)/dt, pose matching included, less the response's moves) plus ½·m·u² for each node the
///   response moved or a hold holds, or ½·M·restingSpeed² for its mass M, whichever is more. The
///   solve also turns the body's elastic energy (stretched links, pressure) into motion, which the
///   energy before it does not see: internal motion up to that root-mean-square speed is taken as
///   the body's own.
/// Over either bound, velocities are scaled down to it (about the centre of mass for the energy, so
/// that a falling or pushed body keeps its motion as a whole); positions are touched only where a
/// move in the solve was too long. It costs two passes over the body's nodes in the steps the
/// response moves or the holds hold a node of it, one before the solve and one after, and a third
/// when it has to slow nodes; the moves are checked in the solve's own last pass over the nodes. A
/// pressure body costs one pass in each other step in which a guarding tool's pair with it is live.
///
/// With boundForcesNextStep, the step after a guarded one bounds what the body's forces add: a
/// pressure body that a fast tool has squeezed flat gets Bullet's pressure kPR·area/|volume| at a
/// volume near zero, a kick of thousands of m/s in one step, and a step in which the tool may not
/// touch it at all. For that body, Bullet's own bound on a node's change of velocity from its forces
/// in a step (btSoftBodyWorldInfo::m_maxDisplacement over the step, per axis; 1000 m by default) is
/// lowered, for its predictMotion only, to the larger of: speedFactor times the fastest of its
/// nodes as the guard left them, the tool's fastest corner over that step, and restingSpeed; and,
/// when two or more tool pieces moved or held its nodes (a grasp), the body's extent over the step: a
/// squeezed pressure body held between jaws gets a large kick every step, which the holds on both
/// sides take back in the solve. Against a single piece the body bulges away from it instead, and
/// the kick stays. The bound stays for the next step while a node is predicted as fast as it
/// allows, and costs one pass over the body's nodes in each step it applies. Gravity and pose
/// matching are not bounded.
struct EnergyGuardSettings {
  bool enabled = true;
  Real speedFactor = 2;    ///< >= 1
  Real energySlack = 0.05;  ///< relative, >= 0
  Real restingSpeed = 1;    ///< m/s, >= 0
  bool boundForcesNextStep = true;
};

/// What ThinTool does inside Bullet's soft solver and with Bullet's bodies: switches that only the
/// Bullet glue reads; the core's stages never see them.
struct BulletSettings {
  /// Constraint response: give Bullet's soft solver one-sided plane contacts (btSoftBody::RContact)
  /// that hold the moved nodes where the projection put them and, with swept detection, every
  /// other node near the tool behind the tool face it is in front of (computeHolds). Without them
  /// the links and the pressure of a squashed body pull nodes back into the tool within the step.
  /// With friction, a node that sticks is held to the tool's surface motion (its hold is not
  /// frictionless), and its holds are solved once more after the links in each position iteration
  /// of thintool::SoftBodySolver's solve, so that the links of a grasped body do not drag the held
  /// nodes along the jaws. The soft bodies that a dynamic tool the force model carries
  /// (force.applyToDynamicTool) touches, and with another soft-body solver those a tool with
  /// friction touches, get a whole contact pass after the links instead, their other contacts
  /// included (btSoftBody::m_cfg.m_psequence).
  bool holdInSolver = true;
  /// How far along its plane a hold without friction reaches, in multiples of the pair's skin
  /// beyond the skin (>= 0): it acts on its node only while the node, put on the hold's plane,
  /// lies within the piece grown by skin·(1 + holdPlaneReach). Past the tool a hold's plane is
  /// no longer the tool's: a pressure body squeezed under a plate, its nodes held below the plate's
  /// plane across its whole width, cannot bulge past the rim and loses volume until Bullet's
  /// pressure (kPR·area/volume) throws it apart. Empty: the whole plane. Runs only in a world whose
  /// soft-body solver is a thintool::SoftBodySolver.
  std::optional<Real> holdPlaneReach;
  /// With friction (response.friction.enabled, the default): μs = μk = the soft body's m_cfg.kDF
  /// × the tool body's getFriction(), per pair, as stock Bullet's node contact
  /// (btSoftBodyInternals.h, CollideSDF_RS), which lets a node stick while its tangential motion is
  /// within that times its normal motion. Off: response.friction's two coefficients.
  bool frictionFromBodies = true;
  /// Swept detection: find the soft faces near the tool by reading every face's three nodes each
  /// step (their start, predicted end and last sweep's end), instead of walking the soft body's
  /// face tree (btSoftBody::m_fdbvt), which ThinTool otherwise builds and Bullet then refits in
  /// every predictMotion. It misses no face however fast it moved, and a whole step costs less at
  /// every size measured, 128 to 65,536 faces (./scripts/step-table.py). A tree that exists
  /// anyway (another tool's, or Bullet's soft–soft collision's) is walked all the same. Off by
  /// default: it gathers the faces in another order, which moves the generated scenes' chaotic
  /// outcomes (docs/results/generated-scenes.md).
  bool scanFaces = false;
  /// In btDeformableMultiBodyDynamicsWorld, with thintool::DeformableBodySolver: the tool's node
  /// contacts in Bullet's implicit solve (btSoftBody::DeformableNodeRigidContact) come from
  /// ThinTool's swept detection (ToolOptions::swept), in place of Bullet's own (fCollision::SDF_RDN,
  /// which Bullet's deformable demos leave off, keeping only face contacts), which asks the
  /// tool's distance field, at one instant, how far each node's predicted place lies inside it, and
  /// answers with the nearest side: a node carried past a thin tool's mid-plane is pushed out of
  /// the far side. Each node the detection finds heading into the tool grown by the skin, still
  /// outside the tool's surface at the start of the step (behind the grown face it comes through by
  /// less than the skin), gets a contact on that face's plane, with Bullet's hardness (kKHR or
  /// kCHR) and ThinTool's friction (ToolOptions::response.friction, on by default; with
  /// frictionFromBodies Bullet's coefficient, the soft body's kDF times the tool's friction); a node the tool's sweep passed over is left to the last
  /// word, whose move carries no velocity, where the contact would push it out as one. Bullet's
  /// face contacts stay Bullet's. On a multibody link the contact acts through the multibody's
  /// Jacobian at the node, as Bullet's own does. Off, the tool keeps Bullet's own node contacts.
  bool deformableNodeContacts = true;
};

struct ToolOptions {
  /// Names the tool in error messages and reports; empty picks "tool <n>".
  std::string name;

  SamplingSettings sampling;
  AssociationSettings association;
  /// Deepest a soft face is looked for below a tool node (m, > 0); empty picks each piece's
  /// thickness.
  std::optional<Real> probeDepth;
  /// Contact margin kept between the tool's faces and the soft surface (m, >= 0). Empty uses each
  /// soft body's own collision margin (btSoftBody::getCollisionShape()->getMargin()), as Bullet's
  /// stock soft–rigid contact does.
  std::optional<Real> skin;
  /// How fast (m/s) a soft node that begins a step inside the skin but outside the tool is pushed
  /// out to the full skin: a body created within the tool's margin, a tool registered or set down
  /// onto tissue, and a node that Bullet's soft solve (links, pressure) left inside the skin in the
  /// step before. Pushed out to the full skin in one step, those nodes would leave at up to
  /// skin/dt: 15 m/s from Bullet's default 0.25 m margin at 60 Hz, and a pressure body pressed
  /// against the tool would bounce between the solve and the push every step. A pair's first step
  /// also keeps only the closest node's distance and grows from there. Infinite: at once.
  Real skinGrowthSpeed = 1;

  /// Swept detection (detection/SweptDetection.h): contacts over the whole motion of a step, so a
  /// tool moving farther than its thickness per step never passes through. Off, the paper's
  /// discrete rays and checks run at the end of the step only, as in the paper.
  bool swept = true;
  /// Swept detection reads a turning tool's motion in the step as the chord of its arc. On, a soft
  /// node whose chord passes through the tool but which ends outside it is taken only if its path
  /// along the arc (sampled every separation.maxTurnPerSample) enters the tool too: for a tool that
  /// spins in place, a burr or a round tool, whose chord reading pushes away nodes it never touched.
  /// Off by default (docs/results/generated-scenes.md: what it changes on the generated scenes).
  bool sweptFollowsArc = false;
  /// The paper's filters; used by the discrete detection only (swept detection knows each
  /// contact's side from the motion).
  FilterSettings filters;
  ResponseSettings response;
  /// The last word (response/Separation.h): after Bullet's soft solver, no soft node is left
  /// inside the tool and no soft face pierced by it. Runs only in a world whose soft-body solver is
  /// a thintool::SoftBodySolver.
  SeparationSettings separation;
  /// After the last word, the soft bodies near the tool leave the step no faster, and with no
  /// more energy, than their own forces and the tool's motion can give them. Runs only in a world
  /// whose soft-body solver is a thintool::SoftBodySolver.
  EnergyGuardSettings energyGuard;
  /// The tissue's force on the tool (force/ContactForce.h): off by default.
  ForceSettings force;
  BulletSettings bullet;

  /// The paper's algorithm as published: discrete rays, association, both checks, and no last
  /// word after the soft solver (set separation.enabled for the paper's detection with it).
  static ToolOptions paper() {
    ToolOptions options;
    options.swept = false;
    options.separation.enabled = false;
    options.energyGuard.enabled = false;
    options.response.friction.enabled = false;  // the paper's response is frictionless
    // The paper moves every colliding node to the tool's surface at once.
    options.skinGrowthSpeed = std::numeric_limits<Real>::infinity();
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
THINTOOL_API std::string validateToolOptions(const ToolOptions& options);

}  // namespace thintool
