// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// thintool_run: runs scene files, or sweeps of them, and writes one row per run (accuracy by the
// ground truth beside the time per step, from the same run) as CSV, JSON and a markdown table.
// Run it without arguments for its usage.

#include "Json.h"
#include "Runner.h"
#include "SceneFile.h"

#include <thintool/core/Error.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace thintool::eval;

const char* kUsage = R"(usage: thintool_run [options] scene.json [scene.json ...]

Runs each scene file (eval/scenes/README.md describes the format) and prints a markdown table:
crossed nodes, tool inside, largest and RMS penetration, force error, and time per step.

  --set PATH=VALUE        override a field before the file is read, e.g. step.dt=1/240,
                          algorithm=paper, tools[0].trajectory.speed=5 (repeatable)
  --sweep PATH=V1,V2,...  run every combination of the swept values (repeatable); commas inside
                          brackets belong to the value: --sweep 'tools[0].shape.half_extents=[0.4,0.01,0.4],[0.5,0.01,0.02]'
  --reference PATH=VALUE  an override of the reference run, the finest configuration, against
                          which every run's force error is computed (repeatable); needs the force
                          model on (--set thintool.force=true)
  --csv FILE              one row per run
  --json FILE             the same rows as a JSON array
  --steps FOLDER          one CSV per run with every step's measures
  --quiet                 no progress line
)";

struct Sweep {
  std::string path;
  std::vector<std::string> values;
};

// Splits at the commas outside brackets and quotes.
std::vector<std::string> splitValues(const std::string& text) {
  std::vector<std::string> values;
  std::string current;
  int depth = 0;
  bool quoted = false;
  for (char c : text) {
    if (c == '"') quoted = !quoted;
    if (!quoted && (c == '[' || c == '{')) ++depth;
    if (!quoted && (c == ']' || c == '}')) --depth;
    if (c == ',' && depth == 0 && !quoted) {
      values.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  values.push_back(current);
  return values;
}

struct Row {
  std::string file;
  std::vector<std::string> sweptValues;
  RunResult result;
  double forceError = std::nan("");
};

std::string number(double value, int digits = 6) {
  if (std::isnan(value)) return "";
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

std::string stepName(double dt) {
  const double perSecond = 1 / dt;
  if (std::abs(perSecond - std::round(perSecond)) < 1e-6 * perSecond) return "1/" + number(std::round(perSecond));
  return number(dt);
}

std::string csvQuoted(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

void writeCsv(const std::string& path, const std::vector<Sweep>& sweeps, const std::vector<Row>& rows) {
  std::ofstream out(path);
  if (!out) throw thintool::Error(path + ": cannot write the file");
  out << "scene,file";
  for (const Sweep& s : sweeps) out << ',' << csvQuoted(s.path);
  out << ",algorithm,dt,soft_faces,soft_nodes,tool_nodes,steps,crossed_nodes,still_crossed,tool_inside_steps,"
         "ends_inside,max_penetration_m,rms_penetration_m,peak_force_n,force_error,us_per_step,tool_us_per_step,finite\n";
  for (const Row& row : rows) {
    const RunResult& r = row.result;
    out << csvQuoted(r.scene) << ',' << csvQuoted(row.file);
    for (const std::string& v : row.sweptValues) out << ',' << csvQuoted(v);
    out << ',' << algorithmKey(r.algorithm) << ',' << number(r.timeStep, 9) << ',' << r.softFaces << ','
        << r.softNodes << ',' << r.toolNodes << ',' << r.truth.steps << ',' << r.truth.crossedNodes << ','
        << r.truth.stillCrossed << ',' << r.truth.toolInsideSteps << ',' << (r.truth.endsInside ? 1 : 0) << ','
        << number(r.truth.maxPenetration) << ',' << number(r.truth.rmsPenetration) << ',' << number(r.peakForce)
        << ',' << number(row.forceError) << ',' << number(r.microsecondsPerStep) << ','
        << number(r.toolMicrosecondsPerStep) << ',' << (r.finite ? 1 : 0) << '\n';
  }
}

std::string jsonNumber(double value) { return std::isfinite(value) ? number(value) : "null"; }

void writeJson(const std::string& path, const std::vector<Sweep>& sweeps, const std::vector<Row>& rows) {
  std::ofstream out(path);
  if (!out) throw thintool::Error(path + ": cannot write the file");
  out << "[\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const RunResult& r = rows[i].result;
    out << "  {\"scene\": " << jsonQuoted(r.scene) << ", \"file\": " << jsonQuoted(rows[i].file);
    for (std::size_t s = 0; s < sweeps.size(); ++s) {
      out << ", " << jsonQuoted(sweeps[s].path) << ": " << jsonQuoted(rows[i].sweptValues[s]);
    }
    out << ", \"algorithm\": " << jsonQuoted(algorithmKey(r.algorithm)) << ", \"dt\": " << jsonNumber(r.timeStep)
        << ", \"soft_faces\": " << r.softFaces << ", \"soft_nodes\": " << r.softNodes
        << ", \"tool_nodes\": " << r.toolNodes << ", \"steps\": " << r.truth.steps
        << ", \"crossed_nodes\": " << r.truth.crossedNodes << ", \"still_crossed\": " << r.truth.stillCrossed
        << ", \"tool_inside_steps\": " << r.truth.toolInsideSteps
        << ", \"ends_inside\": " << (r.truth.endsInside ? "true" : "false")
        << ", \"max_penetration_m\": " << jsonNumber(r.truth.maxPenetration)
        << ", \"rms_penetration_m\": " << jsonNumber(r.truth.rmsPenetration)
        << ", \"peak_force_n\": " << jsonNumber(r.peakForce)
        << ", \"force_error\": " << jsonNumber(rows[i].forceError)
        << ", \"us_per_step\": " << jsonNumber(r.microsecondsPerStep)
        << ", \"tool_us_per_step\": " << jsonNumber(r.toolMicrosecondsPerStep)
        << ", \"finite\": " << (r.finite ? "true" : "false") << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
  }
  out << "]\n";
}

void writeSteps(const std::string& folder, int index, const RunResult& r) {
  const std::string path = folder + "/run" + std::to_string(index) + ".csv";
  std::ofstream out(path);
  if (!out) throw thintool::Error(path + ": cannot write the file (does the folder exist?)");
  out << "t,crossings,tool_inside,max_penetration_m,fx,fy,fz,us_step,us_tool\n";
  for (const StepSample& s : r.samples) {
    out << number(s.time, 9) << ',' << s.crossings << ',' << (s.toolInside ? 1 : 0) << ','
        << number(s.maxPenetration) << ',' << number(s.force.x) << ',' << number(s.force.y) << ','
        << number(s.force.z) << ',' << number(s.stepMicroseconds) << ',' << number(s.toolMicroseconds) << '\n';
  }
}

class Progress {
 public:
  Progress(bool enabled, int runs) : m_enabled(enabled), m_runs(runs), m_tty(isatty(fileno(stderr)) != 0) {}
  void begin(int run, const std::string& label) {
    m_run = run;
    m_label = label;
    m_shown = -1;
    if (m_enabled && !m_tty) std::fprintf(stderr, "[%d/%d] %s\n", run, m_runs, label.c_str());
  }
  void update(int done, int steps) {
    if (!m_enabled || !m_tty) return;
    const int width = 30;
    const int filled = steps > 0 ? done * width / steps : width;
    if (filled == m_shown) return;
    m_shown = filled;
    std::fprintf(stderr, "\r[%d/%d] [%s%s] %3d%% %s", m_run, m_runs, std::string(filled, '#').c_str(),
                 std::string(width - filled, '-').c_str(), steps > 0 ? done * 100 / steps : 100, m_label.c_str());
    if (done == steps) std::fprintf(stderr, "\n");
  }

 private:
  bool m_enabled;
  int m_runs;
  bool m_tty;
  int m_run = 0;
  int m_shown = -1;
  std::string m_label;
};

int run(int argc, char** argv) {
  std::vector<Override> sets;
  std::vector<Override> referenceSets;
  std::vector<Sweep> sweeps;
  std::vector<std::string> files;
  std::string csvPath;
  std::string jsonPath;
  std::string stepsFolder;
  bool quiet = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw thintool::Error(arg + ": expected a value after it");
      return argv[++i];
    };
    if (arg == "--set") {
      sets.push_back(parseOverride(value()));
    } else if (arg == "--sweep") {
      const Override o = parseOverride(value());
      sweeps.push_back({o.path, splitValues(o.value)});
    } else if (arg == "--reference") {
      referenceSets.push_back(parseOverride(value()));
    } else if (arg == "--csv") {
      csvPath = value();
    } else if (arg == "--json") {
      jsonPath = value();
    } else if (arg == "--steps") {
      stepsFolder = value();
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      throw thintool::Error(arg + ": unknown option (see --help)");
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::cerr << kUsage;
    return 2;
  }

  const bool reference = !referenceSets.empty();

  // Every combination of the swept values, for every file; each is read (and checked) up front,
  // so that a bad value fails before hours of runs, not after. A job's reference run shares its
  // swept values but those the reference overrides, so one reference serves every job that
  // differs from it only there (every algorithm and step of one speed, say).
  struct Job {
    std::string file;
    std::vector<std::string> values;
    SceneSpec scene;
    std::string referenceKey;
    std::vector<Override> referenceOverrides;
  };
  auto overridden = [&](const std::string& path) {
    for (const Override& o : referenceSets) {
      if (o.path == path) return true;
    }
    return false;
  };
  std::vector<Job> jobs;
  std::vector<std::string> referenceKeys;
  std::size_t combinations = 1;
  for (const Sweep& s : sweeps) combinations *= s.values.size();
  for (const std::string& file : files) {
    for (std::size_t c = 0; c < combinations; ++c) {
      std::vector<Override> overrides = sets;
      std::vector<std::string> values;
      std::size_t rest = c;
      for (auto s = sweeps.rbegin(); s != sweeps.rend(); ++s) {
        values.insert(values.begin(), s->values[rest % s->values.size()]);
        rest /= s->values.size();
      }
      for (std::size_t s = 0; s < sweeps.size(); ++s) overrides.push_back({sweeps[s].path, values[s]});
      Job job{file, values, loadScene(file, overrides), "", {}};
      if (reference) {
        job.referenceKey = file;
        job.referenceOverrides = sets;
        for (std::size_t s = 0; s < sweeps.size(); ++s) {
          if (overridden(sweeps[s].path)) continue;
          job.referenceOverrides.push_back({sweeps[s].path, values[s]});
          job.referenceKey += "|" + sweeps[s].path + "=" + values[s];
        }
        job.referenceOverrides.insert(job.referenceOverrides.end(), referenceSets.begin(), referenceSets.end());
        loadScene(file, job.referenceOverrides);
        if (std::find(referenceKeys.begin(), referenceKeys.end(), job.referenceKey) == referenceKeys.end()) {
          referenceKeys.push_back(job.referenceKey);
        }
      }
      jobs.push_back(std::move(job));
    }
  }

  Progress progress(!quiet, int(jobs.size() + referenceKeys.size()));
  int runIndex = 0;
  RunOptions runOptions;
  runOptions.progress = [&](int done, int steps) { progress.update(done, steps); };
  if (!quiet) {
    // Where the settled body lies, for whoever writes a trajectory's start.
    runOptions.settled = [](double low, double high) {
      std::fprintf(stderr, "  settled: the soft body spans y = %.3f to %.3f m\n", low, high);
    };
  }
  std::vector<std::pair<std::string, RunResult>> references;
  auto referenceFor = [&](const Job& job) -> const RunResult& {
    for (const auto& r : references) {
      if (r.first == job.referenceKey) return r.second;
    }
    const SceneSpec scene = loadScene(job.file, job.referenceOverrides);
    progress.begin(++runIndex, "reference for " + job.referenceKey);
    references.emplace_back(job.referenceKey, runScene(scene, runOptions));
    return references.back().second;
  };

  std::vector<Row> rows;
  for (const Job& job : jobs) {
    const RunResult* referenceRun = reference ? &referenceFor(job) : nullptr;
    std::string label = job.scene.name;
    for (std::size_t s = 0; s < sweeps.size(); ++s) label += " " + sweeps[s].path + "=" + job.values[s];
    progress.begin(++runIndex, label);
    Row row{job.file, job.values, runScene(job.scene, runOptions), std::nan("")};
    if (referenceRun != nullptr) row.forceError = forceError(row.result, *referenceRun);
    if (!stepsFolder.empty()) writeSteps(stepsFolder, int(rows.size()), row.result);
    rows.push_back(std::move(row));
  }

  // A swept algorithm has its own column already.
  auto shown = [&](std::size_t s) { return sweeps[s].path != "algorithm"; };
  std::cout << "| scene |";
  for (std::size_t s = 0; s < sweeps.size(); ++s) {
    if (shown(s)) std::cout << ' ' << sweeps[s].path << " |";
  }
  std::cout << " algorithm | dt | soft faces | crossed | tool inside (steps) | max pen. (mm) | RMS pen. (mm) | "
               "force error | us/step | tool us/step |\n|---|";
  for (std::size_t s = 0; s < sweeps.size(); ++s) {
    if (shown(s)) std::cout << "---|";
  }
  std::cout << "---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& row : rows) {
    const RunResult& r = row.result;
    std::cout << "| " << r.scene << " |";
    for (std::size_t s = 0; s < sweeps.size(); ++s) {
      if (shown(s)) std::cout << ' ' << row.sweptValues[s] << " |";
    }
    std::cout << ' ' << algorithmKey(r.algorithm) << " | " << stepName(r.timeStep) << " | " << r.softFaces << " | "
              << r.truth.crossedNodes << " | " << r.truth.toolInsideSteps << " | "
              << number(r.truth.maxPenetration * 1000, 3) << " | " << number(r.truth.rmsPenetration * 1000, 3)
              << " | " << (std::isnan(row.forceError) ? "-" : number(row.forceError, 3)) << " | "
              << number(r.microsecondsPerStep, 4) << " | "
              << (isStock(r.algorithm) ? "-" : number(r.toolMicrosecondsPerStep, 4))
              << (r.finite ? "" : " (non-finite: stopped)") << " |\n";
  }
  if (!csvPath.empty()) writeCsv(csvPath, sweeps, rows);
  if (!jsonPath.empty()) writeJson(jsonPath, sweeps, rows);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const thintool::Error& error) {
    std::cerr << "thintool_run: " << error.what() << '\n';
    return 1;
  }
}
