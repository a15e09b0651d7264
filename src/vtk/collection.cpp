#include "collection.hpp"

#include <charconv>
#include <cstdio>
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
