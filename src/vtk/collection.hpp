// A ParaView collection file (.pvd): the frames of one kind with their simulated times. VTK 9.1
// has readers of it only in ParaView (vtkPVDReader) and no writer, so it is written here: a few
// lines of XML naming files this library wrote.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mpm_sdem::vtk_grids {

class Collection {
 public:
  // path: the .pvd file; the frames' files are named relative to its directory.
  explicit Collection(std::string path) : path_(std::move(path)) {}
  // Adds a frame and rewrites the file through a temporary one and a rename, so that a reader
  // (or a killed run) never sees it half written. Throws std::runtime_error when it cannot.
  void add(double time, const std::string& file);
  // A resumed run's: the frames an existing file lists up to time t (those written by the run
  // it resumes), to go on from. Returns their number and the last one's time (unchanged when
  // there is none).
  int continueFrom(double t, double& last_time);
  bool empty() const { return frames_.empty(); }

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace mpm_sdem::vtk_grids
