#include "mpm_sdem/vtk/vtk_series.hpp"

#include <unistd.h>
#include <vtkNew.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "collection.hpp"
#include "grids.hpp"

namespace mpm_sdem {

namespace fs = std::filesystem;

namespace {

void writeGrid(vtkUnstructuredGrid* grid, const fs::path& path) {
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(grid);
  // Raw binary after the XML header: the smallest and fastest form ParaView reads.
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();  // arrays past 4 GiB
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

Problem vtkDirProblem(const std::string& dir) {
  if (dir.empty()) return "no directory given";
  std::error_code error;
  fs::path existing = fs::absolute(dir, error);
  if (error) return "'" + dir + "': " + error.message();
  if (fs::exists(existing, error) && !fs::is_directory(existing, error))
    return "'" + dir + "' exists and is not a directory";
  while (!fs::exists(existing, error) && existing.has_parent_path() &&
         existing.parent_path() != existing)
    existing = existing.parent_path();
  if (!fs::is_directory(existing, error))
    return "'" + existing.string() + "' (in the path of '" + dir + "') is not a directory";
  if (access(existing.c_str(), W_OK | X_OK) != 0)
    return "cannot write in '" + existing.string() + "' (to make '" + dir + "')";
  return "";
}

struct VtkSeries::Impl {
  std::string dir;
  int frames = 0;
  double last_time = -std::numeric_limits<double>::infinity();
  vtk_grids::Collection points, blocks, fem;
  explicit Impl(const std::string& d)
      : dir(d),
        points((fs::path(d) / "points.pvd").string()),
        blocks((fs::path(d) / "blocks.pvd").string()),
        fem((fs::path(d) / "fem.pvd").string()) {}
};

VtkSeries::VtkSeries(const std::string& dir, double resume_after) {
  if (const Problem p = vtkDirProblem(dir); !p.empty())
    throw std::runtime_error("cannot write the VTK series: " + p.message);
  std::error_code error;
  fs::create_directories(dir, error);
  if (error)
    throw std::runtime_error("cannot make the VTK directory '" + dir + "': " + error.message());
  impl_ = std::make_unique<Impl>(dir);
  if (resume_after >= 0) {
    Impl& s = *impl_;
    s.frames = s.points.continueFrom(resume_after, s.last_time);
    double ignored = 0;
    s.blocks.continueFrom(resume_after, ignored);
    s.fem.continueFrom(resume_after, ignored);
  }
}

VtkSeries::~VtkSeries() = default;
VtkSeries::VtkSeries(VtkSeries&&) noexcept = default;
VtkSeries& VtkSeries::operator=(VtkSeries&&) noexcept = default;

const std::string& VtkSeries::dir() const {
  return impl_->dir;
}

int VtkSeries::frames() const {
  return impl_->frames;
}

double VtkSeries::lastTime() const {
  return impl_->last_time;
}

bool VtkSeries::write(const World& world) {
  Impl& s = *impl_;
  const double t = world.time();
  if (!(t > s.last_time)) return false;
  char number[16];
  std::snprintf(number, sizeof number, "_%06d.vtu", s.frames);
  // Each file before its collection names it: a collection never lists a missing frame.
  auto frame = [&](vtkUnstructuredGrid* grid, const char* kind, vtk_grids::Collection& c) {
    const std::string file = kind + std::string(number);
    writeGrid(grid, fs::path(s.dir) / file);
    c.add(t, file);
  };
  frame(vtk_grids::points(world), "points", s.points);
  if (world.blocks()) frame(vtk_grids::blocks(world), "blocks", s.blocks);
  if (world.femBodies()) frame(vtk_grids::fem(world), "fem", s.fem);
  ++s.frames;
  s.last_time = t;
  return true;
}

}  // namespace mpm_sdem
