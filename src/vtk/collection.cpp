#include "collection.hpp"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace mpm_sdem::vtk_grids {

namespace {

// The shortest text that reads back as the same double: ParaView matches the series' times
// with the TimeValue inside each file.
std::string exact(double t) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, t);
  return std::string(buf, r.ptr);
}

}  // namespace

int Collection::continueFrom(double t, double& last_time) {
  std::ifstream in(path_);
  std::string line;
  while (std::getline(in, line)) {
    // Lines of add(): <DataSet timestep="T" group="" part="0" file="F"/>
    const std::size_t a = line.find("timestep=\""), f = line.find("file=\"");
    if (a == std::string::npos || f == std::string::npos) continue;
    const double time = std::strtod(line.c_str() + a + 10, nullptr);
    const std::size_t end = line.find('"', f + 6);
    if (time > t || end == std::string::npos) continue;
    frames_.emplace_back(time, line.substr(f + 6, end - f - 6));
    last_time = time;
  }
  return static_cast<int>(frames_.size());
}

void Collection::add(double time, const std::string& file) {
  frames_.emplace_back(time, file);
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
           "  <Collection>\n";
    for (const auto& [t, f] : frames_)
      out << "    <DataSet timestep=\"" << exact(t) << "\" group=\"\" part=\"0\" file=\"" << f
          << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    out.flush();
    if (!out) {
      frames_.pop_back();
      throw std::runtime_error("cannot write " + tmp);
    }
  }
  if (std::rename(tmp.c_str(), path_.c_str()) != 0) {
    frames_.pop_back();
    throw std::runtime_error("cannot rename " + tmp + " to " + path_);
  }
}

}  // namespace mpm_sdem::vtk_grids
