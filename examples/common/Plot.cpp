// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "Plot.h"

#include <cstdlib>
#include <fstream>

namespace thintool::examples {

bool runGnuplot(const std::string& scriptPath, const std::string& script, std::string& whyNot) {
  std::ofstream out(scriptPath);
  out << script;
  out.close();
  if (!out) {
    whyNot = "cannot write " + scriptPath;
    return false;
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    whyNot = "gnuplot is not installed (Debian: apt-get install gnuplot-nox); run 'gnuplot " + scriptPath + "' later";
    return false;
  }
  if (std::system(("gnuplot '" + scriptPath + "'").c_str()) != 0) {
    whyNot = "gnuplot failed on " + scriptPath;
    return false;
  }
  return true;
}

}  // namespace thintool::examples
