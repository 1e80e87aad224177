// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/DeformableBodySolver.h>

#include "SoftBodySolverImpl.h"

namespace thintool {

DeformableBodySolver::DeformableBodySolver(CollisionConfiguration& configuration)
    : m_impl(std::make_unique<detail::SoftBodySolverImpl>(configuration, m_softBodies, true)) {}

DeformableBodySolver::~DeformableBodySolver() = default;

void DeformableBodySolver::predictMotion(btScalar solverdt) {
  m_impl->rememberSpeeds();
  btDeformableBodySolver::predictMotion(solverdt);
}

void DeformableBodySolver::applyTransforms(btScalar timeStep) {
  m_impl->rememberStarts();
  btDeformableBodySolver::applyTransforms(timeStep);
  m_impl->lastWordAfterTransforms();
}

}  // namespace thintool
