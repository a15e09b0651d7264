// ParaView files of a run: each frame of a world as VTK XML unstructured grids (.vtu, written by
// VTK's own writer, binary appended and zlib-compressed), and per kind of file a collection
// (.pvd) that lists the frames with their simulated times, so that ParaView opens each kind as
// one time series (File > Open points.pvd). No VTK type appears here: the runner and the node
// include this header without VTK's.
//
// SI units: metres in the world frame (z = 0: the simulation is the x-y plane), seconds, m/s,
// Pa with tension positive; masses, forces and torques per metre of out-of-plane thickness
// (kg/m, N/m, N m/m). Frame n (from 0, six digits) writes into the directory:
//
// points_n.vtu  one vertex per material point and SPH particle, in single precision (like the
//   node's clouds). Point data: velocity (m/s, 3 components, z = 0), speed (m/s), stress (Pa,
//   the symmetric tensor's 6 components XX, YY, ZZ, XY, YZ, XZ: plane strain carries ZZ, YZ and
//   XZ are 0), pressure (Pa, compression positive) and von_mises (Pa, sqrt(3 J2)) as on the
//   node's ~particles (pressure() and vonMises() of core/mpm/constitutive.hpp), material (index
//   in the scene's materials), kind (0 material point, 1 SPH particle), mass (kg/m), J (volume
//   ratio V / V0).
// blocks_n.vtu  while the world has blocks: each block's rounded outline as polygons in the world
//   frame, one per convex part (a spheropolygon is one, a disc cluster one per disc). A rounded
//   corner is sampled by kCornerChords chords and a whole disc by 4 kCornerChords; the points
//   lie on the outline. Cell data, the same on every part of a block: block (its place in the
//   list, indexing the field data block_names), part, type (0 static, 1 kinematic, 2 dynamic),
//   position (centre of mass, m), angle (rad), velocity (of the centre of mass, m/s),
//   angular_velocity (rad/s); the material's load on it in the last step, coupling_force (N/m),
//   coupling_torque (N m/m about the centre of mass), coupling_contacts; the other blocks',
//   block_force, block_torque, block_contacts (Blocks::coupling() and blockContact()).
// fem_n.vtu  while the world has FEM bodies: their triangles in the current configuration. Point
//   data: displacement from the mesh as meshed (m), velocity (m/s), body (index in the scene's
//   fem_bodies, naming the field data fem_names), held (1: a held node). Cell data: von_mises
//   (Pa), stress (Pa, 6 components as above), body.
//
// Every dataset's field data also holds TimeValue (s), which ParaView reads when a file is
// opened on its own. points.pvd, blocks.pvd and fem.pvd are rewritten after each frame through a
// temporary file and a rename, so a run that is killed leaves collections listing every frame
// written whole. A new series starts at frame 0 and overwrites the files of an earlier one in the
// same directory (frames beyond its own stay, unlisted).
#pragma once

#include <memory>
#include <string>

#include "mpm_sdem/core/problem.hpp"

namespace mpm_sdem {

class World;

// Chords per rounded corner of a block outline (a disc: 4 kCornerChords). A corner turning by
// theta (at most pi, a capsule's end) is cut by chords of theta / kCornerChords, each inside the
// outline by at most rounding (1 - cos(theta / (2 kCornerChords))): 1.9% of the rounding at pi.
constexpr int kCornerChords = 8;

// "" or why a series cannot be written into dir: none given, a path that exists and is not a
// directory, or a directory (or the nearest existing parent, where it will be made) that cannot
// be written. Checked before a run starts.
Problem vtkDirProblem(const std::string& dir);

class VtkSeries {
 public:
  // Makes the directory (and its parents). Throws std::runtime_error with vtkDirProblem's reason.
  // A resumed run (resume_after: the checkpoint's time, s) keeps the frames the collections
  // there list up to that time and goes on after them.
  explicit VtkSeries(const std::string& dir, double resume_after = -1);
  ~VtkSeries();
  VtkSeries(VtkSeries&&) noexcept;
  VtkSeries& operator=(VtkSeries&&) noexcept;

  // Writes one frame of the world and rewrites the collections. A world at or before the last
  // frame's time writes nothing (false): a collection's times must increase. Throws
  // std::runtime_error when a file cannot be written.
  bool write(const World& world);

  const std::string& dir() const;
  int frames() const;       // written so far
  double lastTime() const;  // s, of the last frame; -infinity before the first

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpm_sdem
