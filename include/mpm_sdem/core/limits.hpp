/// \file
/// The ranges every input must lie in: one source for the scene parser, World, the runner and the
/// node's parameters and services (docs/scene_reference.md, "Ranges"). Each range is physical with
/// a wide margin and keeps the arithmetic sound: doubles in the material; single precision in
/// Box2D (masses and inertias far below float's 3e38); and a stable step of at least
/// kMinTimeStep, so that no accepted value can freeze simulated time.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <limits>
#include <string>

#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

namespace limits {

/// The interval an input must lie in, with its unit for messages.
struct Range {
  ///@{
  /// The bounds, in unit.
  Real min, max;
  ///@}
  const char* unit;       ///< "" when dimensionless
  bool open_min = false;  ///< min itself excluded
};

inline constexpr Range kDensity{0.1, 1e5, "kg/m^3"};      ///< aerogel to four times osmium
inline constexpr Range kModulus{1, 1e13, "Pa"};           ///< E, K, G: a soft gel to 10 x diamond
inline constexpr Range kStrength{0, 1e12, "Pa"};          ///< cohesion, tensile strength, adhesion
inline constexpr Range kSoundSpeed{0.1, 1e4, "m/s"};      ///< a fluid's c0, artificial or real
inline constexpr Range kTaitExponent{1, 15, "", true};    ///< gamma: 7 for water
inline constexpr Range kViscosity{0, 1e6, "Pa s"};        ///< water 1e-3 to bitumen
inline constexpr Range kStiffness{1, 1e13, "N/m per m"};  ///< contact springs
inline constexpr Range kFriction{0, 10, ""};              ///< Coulomb coefficients
inline constexpr Range kArtificialViscosity{0, 10, ""};   ///< SPH alpha, beta (1 is strong)
inline constexpr Range kRestitution{0, 1, "", true};      ///< 0 would need an infinite damper
inline constexpr Range kInertiaScale{1, 1e4,
                                     ""};  ///< solver.inertia_scale: 1 (off) to 100x the step
/// solver.sleep_speed: 0 (off) to 1 m/s, far above any rest a granular bed comes to.
inline constexpr Range kSleepSpeed{0, 1, "m/s"};
inline constexpr Range kSleepTime{0, 100, "s"};    ///< solver.sleep_time
inline constexpr Range kSleepMargin{0, 100, "m"};  ///< solver.sleep_margin (0: two tiles)
inline constexpr Range kSpeed{0, 1e3, "m/s"};      ///< fastest point of a body, block or command
inline constexpr Range kGravity{0, 1e4, "m/s^2"};  ///< magnitude: 1000 g, beyond any centrifuge
/// Loads held on a block from outside (the node's ~apply_obstacle_wrench): the acceleration they
/// give its fastest point, all together, at most the strongest gravity accepted; and the speed
/// they add over their durations at most kSpeed.max (rigid/block_checks.hpp, heldLoadsProblem).
inline constexpr Range kLoadAcceleration{0, kGravity.max, "m/s^2"};
inline constexpr Range kCellSize{1e-5, 1e3, "m"};    ///< grid.cell_size
inline constexpr Range kLength{1e-5, 1e3, "m"};      ///< block roundings and core extents
inline constexpr Range kCoordinate{-1e5, 1e5, "m"};  ///< domain corners and positions
inline constexpr Range kAngle{-1e4, 1e4, "rad"};     ///< block angles (Box2D keeps a float)
inline constexpr Range kEndTime{0, 1e6, "s", true};  ///< time.end
inline constexpr Range kTimeStep{1e-9, 1e3, "s"};    ///< fixed time.dt, time.dt_max
/// Top of a picture's colour scale (the scene's view.max_value, the node's ~image/max_value):
/// above 0, or every point would be drawn at the top colour.
inline constexpr Range kScaleSpeed{0, 1e3, "m/s", true};     ///< the fastest speed accepted
inline constexpr Range kScalePressure{0, 1e13, "Pa", true};  ///< the stiffest modulus accepted
/// No chosen step may fall below this: a simulated second would take more than a billion steps.
inline constexpr Real kMinTimeStep = kTimeStep.min;
inline constexpr std::size_t kMaxNameLength = 64;       ///< characters of a name
inline constexpr std::size_t kMaxSceneBytes = 1 << 20;  ///< scene files are a few kB

/// Any finite number in a unit: for a value whose bounds another check states with its reason.
inline constexpr Range anyIn(const char* unit) {
  return {-std::numeric_limits<Real>::max(), std::numeric_limits<Real>::max(), unit};
}
/// A number as messages show it (6 significant digits).
std::string shown(Real v);

/// Empty when v lies in r, else "must be in [min, max] unit, got v" (NaN and infinity never lie).
Problem rangeProblem(Real v, const Range& r);
/// A ROS graph base name, also usable as a tf frame and a file-name part: a letter, then letters,
/// digits or '_', at most kMaxNameLength characters.
Problem nameProblem(const std::string& name);
///@{
/// OpenMP threads: 0 (automatic) to the machine's logical cores; more only spin against each
/// other (a request for 100000 used to crash the node).
Problem threadsProblem(long threads);
int logicalCores();
///@}

///@{
/// Bytes a world of this many grid nodes and material points holds, with the coupling's and the
/// tiles' share (an estimate, rounded up), and the problem when that exceeds half the machine's
/// physical memory. Checked before anything is allocated.
double worldBytes(double nodes, double points);
Problem memoryProblem(double nodes, double points);
///@}

/// An output file a run can write (a bag, a video): not a directory, in an existing writable
/// directory, ending in one of the extensions. "" or why not; checked before the run starts.
Problem outputFileProblem(const std::string& path, std::initializer_list<const char*> extensions);

}  // namespace limits
}  // namespace mpm_sdem
