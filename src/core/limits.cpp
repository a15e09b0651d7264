#include "mpm_sdem/core/limits.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"

namespace mpm_sdem::limits {

std::string shown(Real v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

namespace {

std::string num(Real v) {
  return shown(v);
}

std::string gib(double bytes) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return s;
}

}  // namespace

Problem rangeProblem(Real v, const Range& r) {
  const bool above_min = r.open_min ? v > r.min : v >= r.min;
  if (above_min && v <= r.max) return "";
  const std::string unit = *r.unit ? std::string(" ") + r.unit : std::string();
  return "must be in " + std::string(r.open_min ? "(" : "[") + num(r.min) + ", " + num(r.max) +
         "]" + unit + ", got " + num(v);
}

Problem nameProblem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > kMaxNameLength)
    return "must be at most " + std::to_string(kMaxNameLength) + " characters, got " +
           std::to_string(name.size());
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  bool ok = letter(name[0]);
  for (char c : name) ok = ok && (letter(c) || digit(c) || c == '_');
  if (ok) return "";
  // Printable in the message even when it holds control characters.
  std::string shown;
  for (char c : name.substr(0, 32)) shown += (c >= 32 && c < 127) ? c : '?';
  return "must start with a letter and hold only letters, digits and '_' (a ROS name and tf "
         "frame), got '" +
         shown + (name.size() > 32 ? "...'" : "'");
}

int logicalCores() {
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

Problem threadsProblem(long threads) {
  if (threads >= 0 && threads <= logicalCores()) return "";
  return "must be 0 (automatic) to " + std::to_string(logicalCores()) +
         " (this machine's cores; more threads only wait for each other), got " +
         std::to_string(threads);
}

double worldBytes(double nodes, double points) {
  double per_node = 0, per_point = 0;
  Grid().forEachField([&per_node](const auto& a) { per_node += sizeof(a[0]); });
  Particles().forEachColumn([&per_point](const auto& c) { per_point += sizeof(c[0]); });
  // Twice the columns: the tile bins and the coupling's own arrays (multi-velocity nodes, IMP
  // and boundary-particle lists) hold at most as much again.
  return 2 * (nodes * per_node + points * per_point);
}

Problem memoryProblem(double nodes, double points) {
  const double need = worldBytes(nodes, points);
  const double have = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGESIZE);
  if (std::isfinite(need) && (have <= 0 || need <= 0.5 * have)) return "";
  return "needs about " + gib(need) + " (" + num(nodes) + " grid nodes, " + num(points) +
         " material points), more than half this machine's " + gib(have) +
         "; use larger cells or a smaller domain";
}

Problem outputFileProblem(const std::string& path, std::initializer_list<const char*> extensions) {
  namespace fs = std::filesystem;
  if (path.empty()) return "no file given";
  std::error_code error;
  if (fs::is_directory(path, error) || path.back() == '/')
    return "'" + path + "' is a directory; give a file name in it";
  const fs::path file(path);
  std::string list;
  bool known = false;
  for (const char* e : extensions) {
    known = known || file.extension() == e;
    list += (list.empty() ? "" : ", ") + std::string(e);
  }
  if (!known) return "'" + path + "' must end in " + list;
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, error))
    return "the directory of '" + path + "' does not exist; create it first";
  if (access(dir.c_str(), W_OK) != 0) return "cannot write in the directory of '" + path + "'";
  if (fs::exists(path, error) && !fs::is_regular_file(path, error))
    return "'" + path + "' exists and is not a regular file";
  return "";
}

}  // namespace mpm_sdem::limits
