// The ParaView series of a build without VTK (scripts/run installs only what the default scene
// needs; scripts/test brings libvtk9-dev). Asking for ParaView files is then refused before a run
// starts, through the same check a bad directory fails (the node's ~vtk/dir, the runner's
// --vtk-every), with what to install.
#include <limits>
#include <stdexcept>

#include "mpm_sdem/vtk/vtk_series.hpp"

namespace mpm_sdem {

namespace {
const char* const kNoVtk =
    "this build has no VTK, so it writes no ParaView files: install libvtk9-dev (scripts/test "
    "does) and build again";
}  // namespace

Problem vtkDirProblem(const std::string&) {
  return kNoVtk;
}

struct VtkSeries::Impl {
  std::string dir;
};

VtkSeries::VtkSeries(const std::string&, double) {
  throw std::runtime_error(kNoVtk);
}
VtkSeries::~VtkSeries() = default;
VtkSeries::VtkSeries(VtkSeries&&) noexcept = default;
VtkSeries& VtkSeries::operator=(VtkSeries&&) noexcept = default;
bool VtkSeries::write(const World&) {
  return false;
}
const std::string& VtkSeries::dir() const {
  return impl_->dir;
}
int VtkSeries::frames() const {
  return 0;
}
double VtkSeries::lastTime() const {
  return -std::numeric_limits<double>::infinity();
}

}  // namespace mpm_sdem
