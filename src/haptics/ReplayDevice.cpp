// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/haptics/ReplayDevice.h>

#include <thintool/core/Error.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace thintool::haptics {

namespace {

const char* const kFields[] = {"time", "x", "y", "z", "buttons"};
const double kLimits[] = {1e9, 1e6, 1e6, 1e6, 4294967295.0};  // s, m, m, m, bit mask

[[noreturn]] void fail(const std::string& name, std::size_t line, const std::string& what) {
  throw Error(name + ":" + std::to_string(line) + ": " + what);
}

double parseNumber(const std::string& text, const std::string& name, std::size_t line, int field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  while (end != nullptr && (*end == ' ' || *end == '\t' || *end == '\r')) {
    ++end;
  }
  if (end == begin || end == nullptr || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
    fail(name, line, std::string("field '") + kFields[field] + "': expected a finite number, got '" + text + "'");
  }
  // Bounds far beyond any device, so that interpolating between two rows cannot overflow.
  if (std::abs(value) > kLimits[field]) {
    fail(name, line, std::string("field '") + kFields[field] + "': expected a magnitude of at most " +
                         std::to_string(kLimits[field]) + ", got '" + text + "'");
  }
  return value;
}

}  // namespace

ReplayDevice ReplayDevice::fromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw Error(path + ": cannot open the trajectory file");
  }
  return fromStream(in, path);
}

ReplayDevice ReplayDevice::fromStream(std::istream& in, const std::string& name) {
  std::vector<DeviceState> samples;
  std::string text;
  std::size_t line = 0;
  bool headerSeen = false;
  while (std::getline(in, text)) {
    ++line;
    if (text.empty() || text == "\r" || text[0] == '#') {
      continue;
    }
    if (!headerSeen) {
      headerSeen = true;
      if (text.rfind("time", 0) == 0) {
        continue;
      }
      fail(name, line, "expected the header 'time,x,y,z,buttons'");
    }
    std::vector<std::string> fields;
    std::stringstream row(text);
    std::string field;
    while (std::getline(row, field, ',')) {
      fields.push_back(field);
    }
    if (fields.size() != 5) {
      fail(name, line, "expected 5 fields (time,x,y,z,buttons), got " + std::to_string(fields.size()));
    }
    DeviceState sample;
    sample.time = parseNumber(fields[0], name, line, 0);
    sample.position = {parseNumber(fields[1], name, line, 1), parseNumber(fields[2], name, line, 2),
                       parseNumber(fields[3], name, line, 3)};
    const double buttons = parseNumber(fields[4], name, line, 4);
    if (buttons < 0 || buttons > 4294967295.0 || buttons != std::floor(buttons)) {
      fail(name, line, "field 'buttons': expected an integer bit mask >= 0, got '" + fields[4] + "'");
    }
    sample.buttons = static_cast<std::uint32_t>(buttons);
    if (!samples.empty() && !(sample.time > samples.back().time)) {
      fail(name, line, "field 'time': expected times to increase, got " + fields[0] + " after " +
                           std::to_string(samples.back().time));
    }
    samples.push_back(sample);
  }
  if (samples.empty()) {
    fail(name, line, "no samples: expected rows 'time,x,y,z,buttons' after the header");
  }
  return ReplayDevice(std::move(samples), name);
}

ReplayDevice::ReplayDevice(std::vector<DeviceState> samples, std::string name)
    : m_samples(std::move(samples)), m_name(std::move(name)) {
  const double start = m_samples.empty() ? 0 : m_samples.front().time;
  for (DeviceState& sample : m_samples) {
    sample.time -= start;
  }
}

double ReplayDevice::duration() const { return m_samples.empty() ? 0 : m_samples.back().time; }

bool ReplayDevice::read(double now, DeviceState& out) {
  if (m_samples.empty() || !(now <= duration())) {
    return false;
  }
  if (m_cursor >= m_samples.size() || m_samples[m_cursor].time > now) {
    m_cursor = 0;  // time went back: search from the start
  }
  while (m_cursor + 1 < m_samples.size() && m_samples[m_cursor + 1].time <= now) {
    ++m_cursor;
  }
  const DeviceState& a = m_samples[m_cursor];
  out.time = now;
  out.buttons = a.buttons;
  if (m_cursor + 1 == m_samples.size()) {
    out.position = a.position;
    return true;
  }
  const DeviceState& b = m_samples[m_cursor + 1];
  const double s = (now - a.time) / (b.time - a.time);
  out.position = a.position + (b.position - a.position) * s;
  return true;
}

}  // namespace thintool::haptics
