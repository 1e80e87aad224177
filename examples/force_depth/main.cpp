// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Force against depth for a slow press of the plate into the 128-face ball (5 cm/s, 1/240 s),
// with both deformation measures and with the linear spring, written as CSV and plotted.
//
//   force_depth [--out DIR]

#include "Plot.h"
#include "SoftBallScene.h"

#include <BulletSoftBody/btSoftBody.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using namespace thintool;

namespace {

struct Variant {
  const char* name;
  DeformationMeasure measure;
  double stiffness;
  double damping;
  double exponent;
};

const Variant kVariants[] = {
    {"indentation, k 100, lambda 20, n 1.5", DeformationMeasure::Indentation, 100, 20, 1.5},
    {"centroid (paper), k 100, lambda 20, n 1.5", DeformationMeasure::CentroidDisplacement, 100, 20, 1.5},
    {"indentation, linear k 30", DeformationMeasure::Indentation, 30, 0, 1},
};

btVector3 centreOf(const btSoftBody& ball) {
  btVector3 sum(0, 0, 0);
  for (int i = 0; i < ball.m_nodes.size(); ++i) {
    sum += ball.m_nodes[i].m_x;
  }
  return sum / btScalar(ball.m_nodes.size());
}

}  // namespace

int main(int argc, char** argv) {
  std::string outDir = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) {
      outDir = argv[++i];
    } else {
      std::cerr << "usage: force_depth [--out DIR]\n";
      return 2;
    }
  }
  const double speed = 0.05;
  const double dt = 1.0 / 240;
  const double deepest = 0.3;
  const std::string csv = outDir + "/force_depth.csv";
  std::ofstream out(csv);
  out << "variant,depth,force_y,faces\n";
  std::printf("%-44s %10s %10s %10s %10s\n", "variant", "F @ 5 cm", "F @ 10 cm", "F @ 20 cm", "F @ 30 cm");
  int index = 0;
  for (const Variant& variant : kVariants) {
    scenes::SceneSettings settings;
    settings.timeStep = dt;
    settings.toolOptions.force.enabled = true;
    settings.toolOptions.force.measure = variant.measure;
    settings.toolOptions.force.huntCrossley = {variant.stiffness, variant.damping, variant.exponent};
    scenes::SoftBallScene scene(settings);
    scene.settle();
    // The rest shape is the settled ball: the paper's measure would count the settling otherwise.
    scene.tool()->captureRestShape(scene.ball());
    const double top = scene.ballTop();
    const btVector3 centreAtStart = centreOf(scene.ball());
    const double halfThickness = 0.01;
    std::vector<double> at(4, 0);
    const double marks[] = {0.05, 0.10, 0.20, 0.30};
    for (int step = 0;; ++step) {
      // The plate's underside starts at the skin's edge and goes down to 30 cm below the top.
      const double depth = -scene.softMargin() + speed * dt * step;
      if (depth > deepest + 1e-9) {
        break;
      }
      const double centre = top - depth + halfThickness;
      scene.step(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(centre), 0)));
      const ToolForce& force = scene.tool()->report().contactForce;
      out << index << ',' << depth << ',' << force.force.y << ',' << force.faces.size() << '\n';
      for (int m = 0; m < 4; ++m) {
        if (depth <= marks[m]) {
          at[m] = force.force.y;
        }
      }
    }
    const btVector3 moved = centreOf(scene.ball()) - centreAtStart;
    std::printf("%-44s %9.2f N %9.2f N %9.2f N %9.2f N   (ball's centre moved %.2f m sideways)\n", variant.name,
                at[0], at[1], at[2], at[3], std::hypot(double(moved.x()), double(moved.z())));
    ++index;
  }
  out.close();
  std::string script = "set terminal pngcairo size 900,540 font 'Sans,11'\n"
                       "set output '" + outDir + "/force_depth.png'\n"
                       "set datafile separator ','\n"
                       "set key top left\nset grid\n"
                       "set xlabel 'plate depth below the ball top (m)'\n"
                       "set ylabel 'tissue force on the plate, up (N)'\n"
                       "set y2label 'paper measure (N)'\nset ytics nomirror\nset y2tics\n"
                       "set title 'Slow press (5 cm/s, 1/240 s) into the 128-face ball'\n"
                       "plot ";
  index = 0;
  for (const Variant& variant : kVariants) {
    script += std::string(index ? ", \\\n     " : "") + "'" + csv + "' using ($1==" + std::to_string(index) +
              " ? $2 : 1/0):3 every ::1" + (variant.measure == DeformationMeasure::CentroidDisplacement ? " axes x1y2" : "") +
              " with lines lw 2 title '" + variant.name +
              (variant.measure == DeformationMeasure::CentroidDisplacement ? " (right axis)" : "") + "'";
    ++index;
  }
  script += "\n";
  std::string whyNot;
  if (examples::runGnuplot(outDir + "/force_depth.gp", script, whyNot)) {
    std::printf("wrote %s and %s/force_depth.png\n", csv.c_str(), outDir.c_str());
  } else {
    std::printf("wrote %s; no plot: %s\n", csv.c_str(), whyNot.c_str());
  }
  return 0;
}
