// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The ball the Bullet benchmarks press (HandlerBench.cpp, WholeStepBench.cpp): scenes/SoftBallScene
// with a ball of the given faces joined by btConvexHullComputer (CreateEllipsoid's own hull stops
// near 2,360 faces), floating without gravity and pressure, so that it keeps the shape it was built
// with, held by its links, and needs no settling (which would take seconds at 65,536 faces), and
// the plate sampled as DetectionBench's: its faces are 0.802 m wide with its 1 mm margin, 16 cells a
// side at 0.051 m, 576 nodes (0.05 would make 17 and 646).

#include <SoftBallScene.h>

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>

#include <memory>

namespace thintool::scenes {

/// margin (m) is the ball's collision margin, which ThinTool's skin follows; toolOptions are
/// ThinTool's, whose sampling this sets.
inline std::unique_ptr<SoftBallScene> makeFloatingBall(Algorithm algorithm, int faces, double margin, double timeStep,
                                                       ToolOptions toolOptions = {},
                                                       WorldKind world = WorldKind::SoftRigid) {
  SceneSettings settings;
  settings.algorithm = algorithm;
  settings.world = world;
  settings.ballResolution = faces / 2 - 1;  // CreateEllipsoid's points make 2·(res + 1) faces
  settings.exactBallHull = true;
  settings.timeStep = timeStep;
  settings.toolOptions = toolOptions;
  settings.toolOptions.sampling.spacing = 0.051;
  auto scene = std::make_unique<SoftBallScene>(settings);
  scene->ball().getCollisionShape()->setMargin(btScalar(margin));
  scene->ball().m_cfg.kPR = 0;
  scene->setGravity(btVector3(0, 0, 0));
  return scene;
}

}  // namespace thintool::scenes
