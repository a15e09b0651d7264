// The seeds' verification cases as world definitions, shared by the tests, the benchmarks and the
// validation report (one definition per case, so that they measure the same thing). Core types
// only.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::cases {

// A rounded box block of outer size w x h (rounding a included), centred at center (m).
BlockDef boxBlock(const std::string& name, const Vec2& center, Real w, Real h, Real a,
                  BodyType type, Real density = 1000);
// A rigid cluster of discs (seed 003) standing for a flat face: a row of discs of radius r at
// pitch p (< 2 r: overlapping) with centres on the segment from..to (m), the block frame at its
// middle and along it. The face is bumpy by r - sqrt(r^2 - p^2 / 4) (0.16 mm for r = 5 mm,
// p = 2.5 mm).
BlockDef discRow(const std::string& name, const Vec2& from, const Vec2& to, Real r, Real p,
                 BodyType type);
// A disk of material filled at ppc x ppc points per cell (material 0).
BodyDef diskBody(const Vec2& center, Real radius, int ppc);
// Least-squares acceleration of x(t) = x0 + v0 t + a t^2 / 2 over the samples with t >= t0.
Real fittedAcceleration(const std::vector<Real>& t, const std::vector<Real>& x, Real t0 = 0);

// Seed 000 sec. 5.1.1 (Table 1): an elastic disk of radius 2 cm at 2 m/s towards an equal free
// rigid disk 4 mm away; no gravity; GIMP, APIC. Stiffnesses in N/m per metre (Table 1 read in
// cgs: 6e3 and 3e2), r_p = 1 mm, V_d = 2 mm, block restitution 1 and friction 0.1.
struct DiskCollision {
  Real bulk_modulus = 5e6;  // Pa (hard disk; the soft one is 5e5)
  Real shear_modulus = 3.7e6;
  Real normal_stiffness = 6e3;
  Real tangential_stiffness = 3e2;
  Real cell_size = 0.004;   // m; the seed's is 3 mm
  int points_per_cell = 2;  // per direction; 6 at the seed's resolution (5,024 points)
  CouplingScheme scheme = CouplingScheme::kImp;
};
WorldDef diskCollision(const DiskCollision& c);

// Seed 000 sec. 5.4 (Fig. 17): a one-dimensional elastic rod of 400 points (4 cm long, one
// 0.1 mm point thick, Table 1's hard material) at 2 cm/s towards a free rigid rod of equal mass
// (a 1 cm capsule of radius 1 mm) 2 mm away; no gravity; cell size h from 1 to 10 mm.
// Quadratic B-spline (with GIMP at these 10 to 100 points per cell the rod went non-finite before
// any contact at three of the sizes). Returns the time at which the free approach would close
// the gap in end_of_approach (s).
WorldDef rodCollision(CouplingScheme scheme, Real cell_size, Real& end_of_approach);

// Seed 000 sec. 5.2 (Table 2 in SI units, g = 1 m/s^2): a 10 cm elastic square (K = 6 MPa,
// G = 3.5 MPa, rho = 2500 kg/m^3, 2 x 2 points per cell) resting on a static block (a = 5 mm,
// restitution 0.5, friction mu) whose top is at y = 5 cm, the square's lowest points just
// touching; GIMP with PIC (which, with the contact damping, settles it); IMP springs as in
// Table 2 read in cgs (6e3, 3e2 N/m), r_p = 1 mm, V_d = 2 mm.
// disc_pitch > 0: the block's top face is a static cluster, one row of 5 mm discs at that
// pitch (discRow) whose tops are at y = 5 cm.
WorldDef restingSquare(Real cell_size, Real friction, CouplingScheme scheme = CouplingScheme::kImp,
                       Real disc_pitch = 0);

// The forces on the resting square's block: runs until every point is slower than 0.1 mm/s for
// 0.25 s on end (the soft contact rings with a period of about 0.2 s, seed 000 Fig. 12), or 3 s;
// then, when slide_speed > 0, sets the square sliding; then averages the contact force on the
// block over 0.05 s, starting 0.1 s after the slide began (at once without a slide).
struct RestingForces {
  Vec2 mean_force{0, 0};  // on the block (N/m)
  Real weight = 0;        // of the square (N/m)
  Real settled_at = 0;    // s
  bool settled = false;   // false: still moving after 3 s
};
RestingForces restingSquareForces(World& w, Real slide_speed);

// 2D analogue of seed 002 sec. 4.1: an elastic disk (R = 5 cm, rho = 1000 kg/m^3, E = 10 MPa,
// nu = 0.3, GIMP) released just above a static 45 deg incline with friction mu; IMP springs
// 1e7 and 5e6 N/m. Returns the acceleration of the disk's centre along the incline fitted to
// x = x0 + v0 t + a t^2 / 2 over t in [0.05, 0.3] s (after the landing). Analytic (eq. 55 for a
// cylinder): g (sin - mu cos) when tan > 3 mu (slides), 2/3 g sin otherwise (rolls).
// segment > 0 builds the incline's surface from collinear static segment blocks of that length
// (m) instead of one box: seed 002 Table 1 varies R = element size / cell size from 1 to 8, and
// our analogue of a surface element is a block.
// disc_pitch > 0 builds it as a static cluster instead: one row of discs of radius a at that
// pitch along the same line (discRow).
Real inclineAcceleration(Real mu, Real cell_size, CouplingScheme scheme = CouplingScheme::kImp,
                         Real segment = 0, Real disc_pitch = 0);
// The analytic acceleration of inclineAcceleration's disk (m/s^2).
Real inclineAnalytic(Real mu);

// Seed 002 sec. 4.1 itself in 2D: the same disk on a deformable FEM plate (1.2 x 0.05 m, linear
// triangles of edge element_size, E = 100 MPa, rho = 10000 kg/m^3, nu = 0.3: ten times the
// disk's, as the seed's plate; its bottom face held) instead of a rigid incline. The plate lies
// level and gravity is tilted by 45 deg, which is the same problem. R = element_size / cell_size.
// Returns the fitted acceleration along the plate as inclineAcceleration does. sph_disk: the
// disk's points are SPH particles (seed 001), meeting the plate through the same scheme.
Real femInclineAcceleration(Real mu, Real cell_size, Real element_size,
                            CouplingScheme scheme = CouplingScheme::kParticleSurface,
                            bool sph_disk = false);

// A plane-strain cantilever of FEM triangles under its own weight (1 x 0.05 m, E = 1 GPa,
// rho = 1000 kg/m^3, nu = 0.3, clamped at x = 0), meshed at element_size.
struct Cantilever {
  Real static_tip = 0;       // tip deflection after dynamic relaxation (m, downwards positive)
  Real euler_bernoulli = 0;  // q L^4 / (8 E' I), E' = E / (1 - nu^2) (m)
  Real frequency = 0;        // first natural frequency from the undamped release (Hz)
  Real frequency_eb = 0;     // 1.8751^2 / (2 pi) sqrt(E' I / (rho A L^4)) (Hz)
  int elements = 0;
  long element_steps = 0;
  Real seconds = 0;  // wall time of both runs
};
Cantilever cantilever(Real element_size, FemModel model = FemModel::kCorotational);

// Seed 002 sec. 4.3 (Walhorn et al. 2005): the water column collapsing through an elastic gate,
// config/scenes/water_gate.yaml. Runs `world` to t_end and follows the gate's upper-left corner
// (the node nearest (0.292, 0.08) m), sampling its horizontal displacement every `interval`.
struct GateRun {
  std::vector<Real> time, tip;   // s, m
  Real peak = 0, peak_time = 0;  // largest displacement and when (m, s)
  Real max_mach = 0;             // largest |v| / c of the water over the run
  long steps = 0;
  std::size_t points = 0;
  int elements = 0;
  Real seconds = 0;  // wall
  // Displacement at time t, linear between samples (m).
  Real at(Real t) const;
};
// `snapshot` is called when the run passes each of `snapshot_times` (may be empty).
GateRun runWaterGate(World& world, Real t_end, Real interval,
                     const std::vector<Real>& snapshot_times = {},
                     const std::function<void(const World&, Real)>& snapshot = nullptr);
// The published tip histories the report compares with, read off the papers' figures (Walhorn
// 2005, Idelsohn 2008, Rafiee 2009, Ryzhakov 2010, Li et al.; digitised): their mean and range
// of the peak and its time, and their values at kGateTimes.
struct GateReference {
  Real peak_mean, peak_min, peak_max;  // m
  Real time_mean, time_min, time_max;  // s
};
GateReference gateReference();
inline constexpr Real kGateTimes[] = {0.15, 0.20, 0.25, 0.30, 0.40};
// Mean, least and largest of the five published displacements at kGateTimes[i] (m).
void gateReferenceAt(int i, Real& mean, Real& lo, Real& hi);

// Rotation under friction: the incline's elastic disk (R = 5 cm, 10 MPa, nu = 0.3, GIMP) thrown
// along a static floor block at v0 without spin. While it slides, friction mu g decelerates its
// centre and spins it up at 2 mu g / R (I = M R^2 / 2); it rolls from t = v0 / (3 mu g) at
// 2/3 v0. offset moves the disk and the floor against the point lattice (fraction of a cell,
// both axes). With spin = true the disk starts rolling (omega = -v0 / R) and mu is large: it
// must then roll on at v0 with its energy kept.
struct ThrownDisk {
  Real cell_size = 0.005;  // m (10 cells per radius)
  Real offset = 0;         // cells
  Real mu = 0.1;
  Real v0 = 2;     // m/s
  Real t_end = 1;  // s
  bool spin = false;
  TransferScheme transfer = TransferScheme::kApic;
  CouplingScheme scheme = CouplingScheme::kImp;
};
WorldDef thrownDisk(const ThrownDisk& c);
// Runs thrownDisk's world to t_end, sampling every millisecond the centre's velocity, the
// disk's rigid-body spin (the least-squares fit of the points' velocities about the centre)
// and the total energy (material, J/m).
struct Rolling {
  Real spin_up = 0;        // rad/s^2, fitted to the spin over [0.05, 0.6] s (sliding)
  Real deceleration = 0;   // m/s^2, fitted to the centre's speed over the same window
  Real roll_speed = 0;     // m/s, mean over the last 0.15 s
  Real roll_start = 0;     // s, where the fitted sliding speed meets roll_speed
  Real roll_ratio = 0;     // -omega R / v over the last 0.15 s (1: rolling without slip)
  Real energy_change = 0;  // (E(t_end) - E(0)) / E(0)
};
Rolling rollDisk(World& w, const ThrownDisk& c);

// Seed 000 sec. 5.1.2: the Table 1 hard elastic disk (R = 2 cm) dropped from 3 cm onto a static
// block (restitution 1), 4 mm cells, 2 x 2 points per cell.
WorldDef dropDisk(CouplingScheme scheme = CouplingScheme::kImp);
// Runs dropDisk's world for 0.25 s: the disk's centre height at release and the highest it rises
// after its velocity turns upwards (m); bounced is false when it never turned.
struct Rebound {
  Real release = 0, peak = 0;
  bool bounced = false;
};
Rebound dropRebound(World& w);

// The shipped scene config/scenes/rock_into_bed.yaml under a scheme: a 3 cm rounded box (a =
// 5 mm, 2500 kg/m^3, restitution 0.2) thrown at (3, -20) m/s into a 30 x 8 cm granular bed
// (Drucker-Prager, rho = 1500 kg/m^3, E = 1 MPa, nu = 0.3, phi = 30 deg, sticky floor), 5 mm
// cells; contact springs 1e7 and 5e6 N/m.
// disc_radius > 0: the rock is a cluster of discs of that radius filling the same outline at a
// pitch of one radius (seed 003's rock as DEM discs).
WorldDef rockIntoBed(CouplingScheme scheme = CouplingScheme::kImp, Real disc_radius = 0);

// Seed 001 sec. 5.1 (Table 1, copper: rho = 8790 kg/m^3, E = 128 GPa; nu = 0 keeps the strip
// one-dimensional): v = 0.01 c sin(10 pi x) on a 1 m bar between sticky walls, 1 cm cells, 2 x 2
// points per cell, Courant factor 0.1; after 500 steps the velocities are reversed and 500 more
// are taken. Returns the largest |v(x, end) + v(x, 0)| over the amplitude and the energy ratio.
struct Reversal {
  Real velocity_error = 0;
  Real energy_ratio = 0;
};
// With sph, the particles inside its regions are SPH particles (seed 001's coupled bar).
Reversal reversal(TransferScheme transfer, StressUpdate update, const SphDef& sph = {});

// An SPH region: the box lo-hi, the kernel, and the artificial viscosity's alpha (beta 0).
SphDef sphBox(const Vec2& lo, const Vec2& hi, SphKernel kernel = SphKernel::kCubicSpline,
              Real alpha = 0);

// Seed 001 sec. 5.2: the copper bar (1 m, nu = 0, so that the plane-strain strip is a 1D bar)
// free in space, its two ends loaded by a compressive traction sigma ramped linearly over
// ramp_transits wave transits L/c and then held; Courant factor 0.1. The static strain is
// -sigma / E (-7.8125e-6 for the seed's 1 MPa). The traction is carried by the end columns'
// points and acts half a spacing out, on the bar's faces (World::setPointLoad). Measured over
// hold_transits transits after the ramp: the strain of the gauge length between the end
// columns, averaged in time over the ringing, and how far it swings.
struct BarStrain {
  Real mean_strain = 0, swing = 0;  // -
  long steps = 0;
  std::size_t points = 0;
};
BarStrain stressBar(Real cell_size, int points_per_cell, Real sigma, Real ramp_transits,
                    Real hold_transits, const SphDef& sph = {});

// Seed 001 sec. 6.1: a 1 m copper plate (Table 1, nu = 0.3) under a biaxial compressive
// traction of 1 MPa on its faces (on the outer material points), ramped over half of
// `transits` P-wave transits and held with local damping; with sph, its regions are SPH.
// Returns -sigma_xx / 1 MPa along the horizontal centre line and -sigma_yy / 1 MPa along the
// vertical one: their mean and largest deviation from 1, and how many of those points are SPH.
struct Biaxial {
  Real mean = 0, worst = 0;
  long line_points = 0, sph_points = 0, steps = 0;
};
Biaxial biaxial(Real cell_size, const SphDef& sph, Real transits = 40);

// Seed 001 sec. 6.2: a square copper plate W wide with a central hole of radius a =
// hole_cells cells (W = 2 a width_over_d, whole cells), loaded on its outer faces by the
// tractions of Kirsch's solution for a remote tension of 1 MPa along y, so that Kirsch's field
// is the finite plate's exact solution (no finite-width correction), and settled as biaxial's.
// Along the mid line out to 3a, sigma_yy against Kirsch at each point: the largest relative
// error, at the points nearest the hole, and the concentration factor of a fit.
struct PlateHole {
  Real edge = 0, edge_expected = 0;  // sigma_yy / 1 MPa at the points nearest the hole
  Real edge_error = 0, worst = 0;
  // Kirsch's form 1 + c1 (a/r)^2 + c2 (a/r)^4 fitted by least squares to the mid line's points
  // whose stencil is complete (below), at r = a: the concentration factor they give (Kirsch: 3).
  Real fitted_concentration = 0;
  // Over the points whose stencil lies inside the material (more than 1.5 cells from the hole):
  // within a stencil of the free surface the nodes lack the material beyond it, and the points
  // there do not converge pointwise (with material points alone, 30 transits, the nearest are
  // 5.2%, 4.3% and 8.2% low at 4, 6 and 8 cells per radius; a fit through them gave 2.866,
  // 2.970 and 2.903).
  Real worst_inside = 0;
  struct Sample {
    Real r = 0, got = 0, expected = 0;  // r / a; sigma_yy / 1 MPa
    bool sph = false;
  };
  std::vector<Sample> line;  // the mid line's points right of the hole, above the line
  long points = 0, sph_points = 0, steps = 0, particles = 0;
};
PlateHole plateWithHole(Real cell_size, int hole_cells, Real width_over_d, const SphDef& sph,
                        Real transits = 40);
// The SPH region of the plate with a hole: a square frame from inner to outer hole radii around
// the hole (material points at its surface and at the plate's faces).
SphDef holeFrame(Real cell_size, int hole_cells, Real width_over_d, Real inner = 1.5,
                 Real outer = 3);

// Particle-steps per second of `steps` steps of a 1 m copper plate of 2 x 2 points per cell,
// shearing at 0.1 m/s, all material points or (sph) all SPH particles; the share of the step in
// the SPH stage, and the stable step.
struct Throughput {
  long particles = 0;
  double particle_steps_per_second = 0, sph_share = 0;
  Real dt = 0;
};
Throughput throughput(Real cell_size, bool sph, int steps);

// Kirsch's stress (Pa) at d from the centre of a hole of radius a in an infinite plate under a
// remote tension S along y.
struct Kirsch {
  Real xx = 0, yy = 0, xy = 0;
};
Kirsch kirsch(Real a, Real S, const Vec2& d);

// Seed 000 sec. 5.3 (Table 3 in SI, g = 10 m/s^2): dry sand (Drucker-Prager: rho = 1500 kg/m^3,
// K = 500 kPa, G = 320 kPa, phi = 35 deg, psi = 25 deg, no cohesion or tension; grains apart
// beyond J = 1.27, MaterialDef::separation_volume_ratio) filled 20 cm
// high into a flat-bottomed silo 20 cm wide made of four static rounded blocks (a = 5 mm,
// friction 0.2); the two bottom plates leave a neck of width `neck` between their rounded
// ends, 25 cm above the floor that catches the flow. GIMP, APIC; r_p = 1 mm, V_d = 2 mm as in
// Table 3; springs 1e6 and 5e5 N/m (stiff enough that the static load of the fill, 4 N/m per
// point at the base, closes less than 4 um of r_p).
// The silo's sand: Table 3's Drucker-Prager above (the default, behind every figure before
// issue 41), or the mu(I) granular material of issue 41 (siloGranularSand) with the same
// density and stiffness.
enum class SiloSand { kDruckerPrager, kGranular };
WorldDef silo(Real neck, Real cell_size, int points_per_cell,
              SiloSand sand = SiloSand::kDruckerPrager);
// Issue 41's silo sand (MaterialModel::kGranular): Table 3's rho = 1500 kg/m^3, K = 500 kPa,
// G = 320 kPa; mu_s = sin 35 deg = 0.574, the plane-strain Mohr-Coulomb angle of Table 3 (the
// return caps sqrt(J2) at mu p, and steady isochoric plane-strain flow has no out-of-plane
// deviator, so sqrt(J2) is the Mohr circle's radius and p its centre: mu = sin phi);
// mu_2 - mu_s = 0.261 and I_0 = 0.279 (glass beads, Jop, Forterre & Pouliquen 2006); grains
// of 2 mm (Table 3's V_d, twice the contact radius r_p = 1 mm); critical solid fraction 0.6.
MaterialDef siloGranularSand(const char* name);
// Runs a silo until 30% of its fill has passed below the plates or t_max: the discharged mass
// in time and the rate fitted by least squares over the part from 10% to 30% (kg/s per metre;
// the head is then still above the silo's width, where Beverloo's rate does not depend on it).
struct SiloFlow {
  std::vector<Real> time, discharged;  // s, kg/m
  // kg/(s m). When less than 10% had passed by t_max (a neck of a few cells can arch and hold
  // the fill), the mean rate over the last second instead, and window_reached is false.
  Real rate = 0;
  Real window_start = 0, window_end = 0;
  bool window_reached = true;
};
SiloFlow siloFlow(World& w, Real t_max);
// The 2D Beverloo law in the seed's form: M = C rho g^0.5 (D0 - k_c r_p)^1.5, C = 0.58,
// k_c = 2.2, with the silo's rho, g and r_p (kg/(s m)).
Real beverloo(Real neck);
// The law's effective width D0 - k_c r_p (m).
Real beverlooWidth(Real neck);
// The silo's rho g^0.5 (kg m^-2.5 s^-1), so that Beverloo's rate is C rho g^0.5 W^1.5.
Real siloDensityRootGravity();

// Seed 000 sec. 7, scaled to a 30 x 30 cm container (the seed's is 61 cm): 25 random convex
// pentagons (outer radius 2.0-2.8 cm, a = 3 mm, 2200 kg/m^3, friction 0.2) on a jittered 5 x 5
// lattice, and Drucker-Prager fines of Table 3 (separation at J = 1.27 as in the silo) put
// point by point into randomly picked lattice squares clear of every pentagon until the fines
// are `fines_content` of the solids' mass. Static walls, a kinematic plate on top; 1 cm cells
// (5 mm when fine), GIMP, APIC; r_p = 1 mm (Table 3), springs 1e7 and 5e6 N/m. seed: the
// random draw (std::mt19937).
// plate is set to the plate's block index.
WorldDef granularMatrix(Real fines_content, bool fine, unsigned seed, int& plate);
// Lets the sample settle for 0.6 s, puts the plate 5 mm above it and drives it down at speed
// (m/s) until the settlement reaches max_settlement: the plate force (material and blocks, N/m)
// against the settlement counted from the plate's first contact (force above 1% of the
// sample's weight).
struct Compression {
  std::vector<Real> settlement, force;   // m, N/m
  Real solids_mass = 0, fines_mass = 0;  // kg/m
};
Compression compressMatrix(World& w, int plate, Real speed, Real max_settlement);

// Issue 41: the granular (mu(I)) sand that flows where a Drucker-Prager sand without dilation
// does, at low inertial numbers. Both yield at sqrt(J2) = slope x pressure: the DP cone's slope
// q_phi (seed 000 eq. 35, inscribed to Mohr-Coulomb in plane strain) becomes mu_s, so both flow
// at the in-plane friction angle flowingFrictionAngle(phi) = asin(q_phi). The rate dependence is
// the glass beads' (Jop, Forterre & Pouliquen 2006: mu_2 - mu_s = 0.261, I_0 = 0.279, critical
// solid fraction 0.6); the density and the dense state's moduli are the DP sand's; cohesion,
// dilation and separation do not carry over (the granular state separates at J = 1). Only for
// a sand without dilation: a dilating cone flows at no single angle to match.
MaterialDef matchedGranular(const MaterialDef& drucker_prager, Real grain_diameter);
// A single-wheel test rig (terramechanics' soil bin) in plane strain, as config/scenes/wheel.yaml
// sets it up: a rigid wheel (a disk block named "wheel" with a drive holding its angular
// velocity and horizontal speed, free to sink) on a bed of sand (the body named "bed").
// setWheelRig gives the wheel a load (its weight, N/m, through its density) and tows it at
// (1 - slip) omega R, omega being its drive's.
void setWheelRig(WorldDef& def, Real slip, Real load);
// Runs the rig to t_end and averages over the last half: drawbar pull (the material's
// horizontal force on the wheel, + forward, N/m), driving torque (the material's torque about
// the axle, which resists the spin: the motor's, N m/m), sinkage (the bed's top as filled minus
// the rim's lowest point, m), and the sinkage at the end.
struct WheelRun {
  Real pull = 0, torque = 0, sinkage = 0, final_sinkage = 0;
  Real pull_spread = 0;  // standard deviation of the pull over the window (N/m)
  Real radius = 0;       // the wheel's (m)
};
WheelRun runWheel(World& w, Real t_end);
// Issue 20's excavator blade: a kinematic blade pushed horizontally through a layer of sand on a
// rigid floor (plane strain, per metre of width). The layer, `bed` deep on a sticky floor, is
// Drucker-Prager sand (rho = 1500 kg/m^3, E = 1 MPa, nu = 0.3, phi, no dilation or cohesion); the
// blade a plate `thickness` thick with `rounding`, at rake angle alpha from the horizontal (90
// deg: vertical; below 90 its top leans back, away from the direction of travel), its lower end
// cut horizontal `depth` below the free surface and its front face at x = 5 cm where it meets
// the surface. Ahead of the blade the layer is full; behind it, it has been cut down to the
// blade's lower end. Domain 0.4 m long; IMP coupling with springs per metre of contact.
// config/scenes/excavator_blade.yaml is this world at depth 6 cm, 5 mm cells, friction 0.3.
struct Blade {
  Real depth = 0.06;         // d: from the free surface to the blade's lowest point (m)
  Real cell_size = 0.005;    // h (m)
  int points_per_cell = 2;   // per direction
  Real rake = 90;            // alpha (deg)
  Real friction = 0.3;       // blade-sand Coulomb coefficient, tan(delta)
  Real speed = 0.05;         // m/s, +x
  Real friction_angle = 35;  // deg: the material's phi (eq. 35's cone)
  Real bed = 0.16;           // m: the layer's depth above the floor
  Real thickness = 0.01;     // m: the blade's, across its faces, rounding included
  Real rounding = 0.002;     // m
  Real damping = 0;          // SolverDef::damping
  // Issue 41: the sand's model. Drucker-Prager (phi = friction_angle, as above) or the mu(I)
  // granular material of bladeSand, whose mu_s gives the same in-plane flowing angle.
  enum class Sand { kDruckerPrager, kGranular };
  Sand sand = Sand::kDruckerPrager;
  Real young_modulus = 1e6;  // Pa: E (the granular material's: its dense state's stiffness)
  Real poisson_ratio = 0.3;  // nu
  // pushBlade only:
  bool geostatic = true;  // start from the layer's weight as its stress
  Real ramp = 0.05;       // s over which the blade's speed is eased in
};
// The blade scene's sand (rho = 1500 kg/m^3) with E and nu from the Blade. Drucker-Prager: phi =
// friction_angle, no dilation or cohesion. Granular: matchedGranular of that sand (mu_s = sin
// of its flowing in-plane angle, bladeFrictionAngle: 33.0 deg for phi = 35 deg, mu_s = 0.545),
// grains 1 mm.
MaterialDef bladeSand(const Blade& c);
// The in-plane friction angle at which bladeSand flows in plane strain (rad): the one source of
// Reece's phi for either model. Drucker-Prager without dilation: asin(q_phi)
// (flowingFrictionAngle). Granular: granularReturn keeps sqrt(J2) <= mu p with p = -sigma_m and
// returns radially in the deviatoric plane, so its plastic strain rate is along the deviator s
// (out-of-plane component s_zz included). In steady plane-strain flow the stress no longer
// changes, the elastic rate vanishes and D_zz = 0 leaves no plastic D_zz: s_zz = 0, sigma_zz =
// (sigma_xx + sigma_yy) / 2. Then p = -(sigma_xx + sigma_yy) / 2 is the centre of Mohr's circle
// of the in-plane stresses and sqrt(J2) = sqrt(((sigma_xx - sigma_yy) / 2)^2 + sigma_xy^2) its
// radius R, so the yield condition R <= mu p is Mohr-Coulomb's R <= p sin(phi) with phi =
// asin(mu): asin(mu_s) for slow flow (I -> 0; the rate term adds (mu_2 - mu_s) / (I_0 / I + 1),
// 0.01 at the blade's I ~ 0.01). The same argument gives the Drucker-Prager asin(q_phi).
Real bladeFrictionAngle(const Blade& c);
// The shipped scene config/scenes/excavator_blade.yaml with what the case sweeps: its cell,
// sand, depth, rake, thickness, rounding, blade friction and speed, every point awake and no
// initial stress (pushBlade sets the layer's weight as its stress).
WorldDef excavatorBlade(const Blade& c);
// Pushes excavatorBlade's blade (block 0) until it has travelled `travel` (m): the horizontal
// and vertical forces of the material on it (N/m, the resistance positive against the motion,
// the vertical positive upwards), each averaged over the steps of a sample every `travel` / 200.
struct BladePush {
  std::vector<Real> displacement, horizontal, vertical;  // m, N/m, N/m
  long steps = 0;
  long contact_steps = 0;  // of which the coupling springs bounded (eq. 51's second term)
  std::size_t points = 0;
  Real seconds = 0;  // wall
};
BladePush pushBlade(World& w, const Blade& c, Real travel);
// McKyes (1985) for a wide blade (Reece's fundamental earth-moving equation with c = q = 0):
// the soil wedge ahead of a blade of rake alpha, failing along a plane from the blade's tip at
// beta to the horizontal, in soil of friction angle phi against a blade of friction angle delta.
// The force on the blade is F = gamma d^2 N_gamma (per metre of width), inclined at delta to the
// blade's normal, with N_gamma = (cot alpha + cot beta) / (2 [cos(alpha + delta) + sin(alpha +
// delta) cot(beta + phi)]) at the beta that minimises it. The blade pushes the wedge along
// (sin(alpha + delta), cos(alpha + delta)) (the friction on the wedge against its rise along the
// blade), so the wedge pushes back on the blade with a horizontal resistance F sin(alpha + delta)
// and lifts it by -F cos(alpha + delta) (for a vertical blade: F sin(delta), upwards).
struct Reece {
  Real n_gamma = 0;     // -
  Real beta = 0;        // rad
  Real horizontal = 0;  // N_gamma sin(alpha + delta): H = gamma d^2 horizontal
  Real vertical = 0;    // -N_gamma cos(alpha + delta): V = gamma d^2 vertical, upwards on the blade
};
Reece reece(Real alpha, Real phi, Real delta);
// Reece's horizontal force for excavatorBlade's world (N/m): gamma d^2 N_gamma sin(alpha + delta)
// with the material's in-plane friction angle (bladeFrictionAngle: the Drucker-Prager cone of
// eq. 35 without dilation flows in plane strain at asin(q_phi), 33.0 deg for phi = 35 deg; the
// granular sand at asin(mu_s), the same angle) and delta = atan(friction).
Real reeceHorizontal(const Blade& c);
// How fast the free surface over McKyes' wedge rises per metre the blade advances: the wedge
// slides along the failure plane while the blade slides along its face, so it rises at
// v sin(alpha) sin(beta) / sin(alpha + beta) (tan beta for a vertical blade). Its weight is
// Reece's surcharge q = gamma r x at the blade's advance x, adding q d N_q with N_q = 2 N_gamma.
Real wedgeRise(const Blade& c);
// The horizontal force of a push over the blade's advance x from `from` to `to` depths (after
// the blade's start, while the heap ahead of it is still small against d): the least-squares line
// H = onset + slope x, its value at x = 0 (the force on a level surface, which Reece's equation
// with q = 0 describes) and its standard error; the mean and the largest sample; the mean
// vertical force (upwards on the blade positive).
struct BladeForce {
  Real onset = 0, onset_error = 0;  // N/m
  Real slope = 0;                   // N/m per m of advance
  Real mean = 0, mean_error = 0;    // N/m
  Real peak = 0;                    // N/m
  Real vertical = 0;                // N/m
};
BladeForce bladeForce(const BladePush& p, Real depth, Real from = 0.05, Real to = 0.3);
// Least-squares line y = a + b x through the points added.
struct LineFit {
  Real n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  void add(Real x, Real y) {
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  Real slope() const { return (n * sxy - sx * sy) / (n * sxx - sx * sx); }
  Real intercept() const { return (sy - slope() * sx) / n; }
};
// A power law y = A x^k fitted by weighted least squares to log y against log x (weights from
// the relative errors y_error / y): the exponent k and its standard error.
struct PowerLaw {
  Real exponent = 0, error = 0;
};
PowerLaw powerLaw(const std::vector<Real>& x, const std::vector<Real>& y,
                  const std::vector<Real>& y_error);
// Richardson's extrapolation of one quantity measured at three cells, each `ratio` times the
// next finer (a1 coarsest): the changes d1 = a2 - a1 and d2 = a3 - a2, their ratio d2 / d1
// (in (0, 1): converging), the observed order p = ln(d1 / d2) / ln(ratio) and the limit
// a3 + d2 / (ratio^p - 1). order and limit are NaN where the changes do not shrink without
// changing sign (not in the asymptotic range); a caller may ask more (a least order).
struct Richardson {
  Real change_ratio = 0, order = 0, limit = 0;
};
Richardson richardson(Real a1, Real a2, Real a3, Real ratio);

// Issue 41: steady uniform chute flow of the mu(I) material (glass beads of Jop, Forterre &
// Pouliquen 2006: mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg, I_0 = 0.279, phi = 0.6, 1500 kg/m^3;
// K = 1 MPa, G = 0.6 MPa) of grains d, depth h on a rough (sticky) base, periodic in x (10
// cells wide), gravity tilted by theta, ASFLIP (APIC's loss per transfer acts as a viscosity
// here: docs/method.md, Granular flows), 2 x 2 points per cell.
struct Chute {
  Real theta = 24 * M_PI / 180;  // rad
  Real depth = 0.05;             // h (m)
  Real grain = 4e-3;             // d (m)
  Real cell_size = 0.005;        // m
};
WorldDef chute(const Chute& c);
// Bagnold's profile u(z) = (2/3) (I_theta / d) sqrt(phi g cos theta) [h^1.5 - (h - z)^1.5],
// I_theta = I_0 (tan theta - mu_s) / (mu_2 - tan theta), for the layer depth h (m/s).
Real bagnold(const Chute& c, Real h, Real z);
// Bagnold's profile of a layer of depth h at theta for granular material m (g = 9.81 m/s^2):
// u(z) = (2/3) (I_theta / d) sqrt(phi g cos theta) [h^1.5 - (h - z)^1.5], with
// I_theta = I_0 (tan theta - mu_s) / (mu_2 - tan theta) (m/s).
Real bagnoldProfile(const MaterialDef& m, Real theta, Real h, Real z);
// The points' mean speed per layer of one cell against Bagnold's at the layer's mean height, for
// the layer's depth read from the points (the top point plus a quarter cell).
// With them, the relative L2 error of the grid's velocity (issue 79; as Baumgarten's chute
// driver, normalised): sqrt(sum_i m_i (v_i - u_B(z_i))^2 / sum_i m_i u_B(z_i)^2) over the nodes
// with mass, u_B for the case's depth (z clamped to it), each periodic node once.
struct ChuteProfile {
  Real worst = 0;    // max over the layers of |u - u_B| / u_B(h)
  Real surface = 0;  // the top layer's speed over Bagnold's there
  Real depth = 0;    // h read from the points (m)
  Real l2 = 0;       // the grid's relative L2 error
};
ChuteProfile chuteProfile(const World& w, const Chute& c);
// Whether the points' volumes still fit their spacing (issue 41's chute runaway,
// docs/method.md, Granular flows): each point's volume fraction phi_p = sum_I S_Ip sum_q V_q
// S_Iq / h^2 (quadratic B-spline, periodic in x, the base as a mirror so that a packed layer
// reads 1 there; 0.998-1.002 for the lattice at rest) over the points below the top two cells,
// with their J. phi > 1: the points crowd more than their J says.
struct ChuteVolume {
  Real phi_min = 0, phi_max = 0, phi_mean = 0;  // over the points below the top two cells
  Real j_mean = 0;                              // the same points' mean J
  long separated = 0;                           // points at J >= 1 (all of the layer's)
  Real vy_max = 0;                              // largest |v_y| (m/s): 0 in the uniform flow
};
ChuteVolume chuteVolume(const World& w, const Chute& c);

// Issue 41: granular column collapse on a rough floor against the quasi-2D experiments (Lube et
// al. 2005, Phys. Rev. E 72; Lajeunesse et al. 2005, Phys. Fluids 17, whose fits are alike). A
// column of the chute's glass beads (1 mm), length L0 = 10 cm along the channel and height a L0,
// against a smooth back wall at x = 0, released at rest onto a sticky floor; plane strain (no
// side walls), ASFLIP with a relaxation time of 0.03 s, 2 x 2 points per cell.
struct GranularColumn {
  Real aspect = 2;         // a = H0 / L0
  Real length = 0.1;       // L0 (m)
  Real cell_size = 0.005;  // m
  Real grain = 1e-3;       // d (m)
  // The static friction angle (rad; 0: the glass beads' 20.9 deg), the beads' mu(I) shifted in
  // angle: mu_2's angle stays 11.86 deg above it.
  Real friction_angle = 0;
  // The channel's side walls (domain.sidewalls): width W (m; 0: none, plane strain) and the
  // beads' friction on them.
  Real sidewall_width = 0;
  Real sidewall_friction = 0;
};
WorldDef granularColumn(const GranularColumn& c);
// The deposit at t_max, or once every point is slower than 1 cm/s: its run-out L_inf (the first
// cell column from the back wall that holds no point: the deposit's front, stragglers beyond a
// gap left out), its farthest point (plus a quarter cell: points sit that far inside the
// outline), its height (the top point plus a quarter cell) and its fastest point.
struct ColumnDeposit {
  Real runout = 0;     // L_inf (m) from the back wall
  Real farthest = 0;   // m
  Real height = 0;     // H_inf (m)
  Real time = 0;       // s
  Real max_speed = 0;  // m/s
  bool at_rest = false;
};
ColumnDeposit collapseColumn(World& w, const GranularColumn& c, Real t_max);
// The experiments' fits for quasi-2D columns (Lube et al. 2005): (L_inf - L0) / L0 = 1.2 a for
// a <= 1.8 and 1.9 a^(2/3) for a >= 2.8 (NaN between, where neither was fitted); H_inf / L0 = a
// for a < 1.15, a^(2/5) above.
Real lubeRunout(Real aspect);
Real lubeHeight(Real aspect);
// The glass beads' fit in a quasi-2D channel (Lajeunesse, Monnier & Homsy 2005, Phys. Fluids 17,
// 103302), as Lagree, Staron & Popinet 2011 (J. Fluid Mech. 686, eq. 3.1) quote it: (L_inf -
// L0) / L0 = 1.8 a for a < 3, 2.3 a^(2/3) from a = 3.
Real lajeunesseRunout(Real aspect);

// Issue 91: Lagree's mu(I) cases in Basilisk (sandbox/M1EMN/Exemples: bagnold_periodic.c,
// granular_column.c and silo2DCo.c), set up for our solver. Basilisk's are dimensionless (g = 1,
// the continuum's density 1, a length unit L); ours take L in metres, g = 9.81 m/s^2 and the
// continuum's density 1500 kg/m^3, so that its speeds scale by sqrt(g L), its times by
// sqrt(L / g) and its stresses by rho g L. Its inertial number I = d gamma_dot / sqrt(p / rho)
// takes the continuum's density, ours the grains' (rho / phi): our d is Basilisk's times
// sqrt(phi). Basilisk's fluid is incompressible; ours is stiff (K = 1 MPa: under 0.2% of volume
// at these depths).
struct CrossSolverRheology {
  Real mu_s = 0.32, delta_mu = 0.28, i0 = 0.4;  // mu(I) = mu_s + delta_mu I / (I0 + I)
  Real grain = 0;                               // Basilisk's d (m)
};
MaterialDef crossSolverGranular(const CrossSolverRheology& r);
// bagnold_periodic.c: a periodic layer h = 5 cm deep on a sticky base at 0.43 rad (24.64 deg),
// mu_s 0.38, delta mu 0.26, I0 0.3, d = h / 25, starting (as Basilisk's) from Bagnold's profile.
struct CrossChute {
  Real depth = 0.05;  // h (m)
  Real theta = 0.43;  // rad
  Real cell_size = 0.005;
  TransferScheme transfer = TransferScheme::kAsflip;
};
CrossSolverRheology crossChuteRheology(const CrossChute& c);
WorldDef crossSolverChute(const CrossChute& c);
// Sets every point's velocity to Bagnold's at its height (the start of bagnold_periodic.c).
void startOnBagnold(World& w, const CrossChute& c);
// The points' mean speed along the slope in layers one cell thick, at the layers' mean height.
struct LayerProfile {
  std::vector<Real> z, u;  // m, m/s
};
LayerProfile layerProfile(const World& w, Real layer);
// granular_column.c's columns of aspect a = H0 / L0 with H0 = 10 cm, mu_s 0.32, delta mu 0.28,
// I0 0.4, on a sticky floor against a smooth back wall: its first, a = 0.5 with d = H0 / 30, and
// its second, a = 1.42 with d = H0 / 65.
struct CrossColumn {
  Real height = 0.1;      // H0 (m)
  Real aspect = 0.5;      // a
  Real grain_ratio = 30;  // H0 / d
  Real cell_size = 0.005;
  TransferScheme transfer = TransferScheme::kAsflip;
};
GranularColumn crossColumnShape(const CrossColumn& c);
WorldDef crossSolverColumn(const CrossColumn& c);
// The deposit's thickness (m) per column of cells, at the columns' centres x (m): the points'
// volume, each at most its packed volume (J capped at 1), over the column's width.
struct Deposit {
  std::vector<Real> x, thickness;
};
Deposit depositThickness(const World& w, Real cell);
// Where the deposit, followed from its first abscissa, first thins below `thin` (m), linearly
// between the two samples around it; its last abscissa if it never does.
Real depositFront(const Deposit& d, Real thin);
// silo2DCo.c without cohesion: a flat-bottomed silo 10 W wide filled 4.5 W deep, discharging
// through an opening W = 4 cm in the middle of its floor (between the surfaces the sand
// touches: the plates stand a contact radius further apart on each side); sticky side walls,
// the floor Coulomb with friction 1 (above every mu(I), so that it does not slip: Basilisk's is
// no-slip); mu_s as asked, delta mu 0.28, I0 0.4, d = W / 30. The floor lies 5 W above the
// domain's bottom, so that the heap below stays clear of the opening.
struct CrossSilo {
  Real opening = 0.04;  // W (m)
  Real mu_s = 0.3;
  Real cell_size = 0.004;
  TransferScheme transfer = TransferScheme::kAsflip;
};
WorldDef crossSolverSilo(const CrossSilo& c);
// The floor's top (m): the gauge counts what has fallen below the floor's underside.
Real crossSiloFloor(const CrossSilo& c);
// The discharge's volume rate per metre (m^2/s at the initial density): the least-squares slope
// of the mass below the floor over [t_from, t_to] (sampled every 1% of t_to) over rho.
Real dischargeRate(World& w, const CrossSilo& c, Real t_from, Real t_to);

// Issue 44: a plate intruding into the blade's sand (Drucker-Prager, 1500 kg/m^3, E = 1 MPa,
// phi = 35 deg; bladeSand), against resistive force theory (RFT: Li, Zhang & Goldman 2013,
// Science 339): each element of a plate at depth |z| moving in a granular bed feels a stress
// alpha(beta, gamma) |z|, a function only of the plate's angle beta and the direction of its
// motion gamma; for a flat plate of length L (per metre of width, plane strain) whose centre is
// at depth z_c, F = alpha z_c L. beta: the plate's long axis from +x, counter-clockwise (deg);
// gamma: the motion's angle below +x (90 straight down; 0 along +x). The layer starts under its
// own weight (layerWeightAsStress), the plate above it.
struct Plate {
  Real angle = 0;          // beta (deg)
  Real direction = 90;     // gamma (deg), 0 to 90
  Real speed = 0.1;        // m/s along the motion
  Real depth = 0.06;       // gamma = 0: the centre's depth while dragged (m; reached straight down)
  Real reach = 0.09;       // gamma > 0: the centre's depth where the motion stops (m)
  Real length = 0.05;      // L (m)
  Real thickness = 0.005;  // across its faces, rounding included (m)
  Real rounding = 0.002;   // m
  Real friction = 0.3;     // plate-sand Coulomb coefficient (steel, as the blade's)
  Real restitution = BlockDef{}.restitution;  // the plate's: its contacts' dashpots
  Real cell_size = 0.005;                     // m
  Real bed = 0.2;                             // the layer's depth (m)
  Real width = 0.5;                           // the domain's (m)
  // The medium and the solver: the blade's sand at phi (deg; 0: no shear strength, a fluid
  // that carries pressure only), under gravity g (m/s^2, downwards; 0: no weight, so that
  // nothing but inertia loads the plate), with the points' velocities by `transfer`.
  Real friction_angle = 35;
  Real cohesion = 0;    // Pa (with phi = 0 and no weight: Prandtl's punch, the locking benchmark)
  Real separation = 0;  // the sand's separation_volume_ratio (0: off; ASFLIP's free surface)
  Real gravity = 9.81;
  TransferScheme transfer = TransferScheme::kApic;
  // Sand at rest sleeps below this speed (m/s, solver.sleep_speed; 0: every point awake).
  Real sleep_speed = 0;
  StressUpdate stress_update = StressUpdate::kUsf;  // solver.stress_update
  // The numerical choices that issue 90's diagnosis switches one at a time (the defaults are the
  // report's): the kernel, the points per cell side, the coupling scheme (IMP's contact disks
  // are half the point spacing), and for a drag (gamma = 0) whether sand lies behind the
  // plate: without the wake, the layer behind the plate's start is cut away down to the plate's
  // lower edge, so that no sand shares the grid's nodes with the plate's trailing face.
  KernelType kernel = KernelType::kQuadraticBSpline;
  int points_per_cell = 2;
  CouplingScheme scheme = CouplingScheme::kImp;
  bool wake = true;
  bool volumetric_average = false;  // solver.volumetric_average (anti-locking)
  Real step_scale = 1;  // time.cfl and time.contact_factor times this (0.5: the step halved)
};
WorldDef plateIntrusion(const Plate& c);
// The plate's motion: for gamma > 0 from its start along gamma until its centre is `reach` deep;
// for gamma = 0 straight down to `depth` (not sampled), then 3 L along +x. Samples every mm of
// motion: the centre's depth below the layer's initial surface and the material's force on the
// plate (N/m, x along +x, z upwards), averaged over the steps since the last sample.
struct PlateRun {
  std::vector<Real> travel, depth, fx, fz;  // m, m, N/m, N/m
  long steps = 0;
  std::size_t points = 0;
  Real seconds = 0;       // wall, over every part of a run continued from a checkpoint
  bool finished = true;   // false: stopped at PlateCheckpoints::stop_at_step
  long resumed_from = 0;  // the step a checkpoint let it continue from (0: from the start)
};
// Checkpoints of a plate run, so that a run of hours can stop (killed, or the machine's session
// ended) and go on later: the world (core/checkpoint.hpp, continued bit for bit) and the run's
// own progress in one file, replaced every `every` seconds of wall time and removed when the run
// ends. A run that finds the file continues from it when it was written by this build for this
// plate; otherwise it starts over and says why on stderr.
struct PlateCheckpoints {
  std::string path;    // the file; empty: no checkpoints
  double every = 600;  // s of wall time between checkpoints
  // > 0: write one at this step and return unfinished (a run in parts; a run continued from
  // that step goes on)
  long stop_at_step = 0;
};
PlateRun movePlate(World& w, const Plate& c, const PlateCheckpoints& k = {});
// The depth below the surface at which the plate is just covered: L |sin beta| / 2 + t / 2 (m).
Real plateCovered(const Plate& c);
// Where a push's window starts (m): a centimetre below plateCovered, past the entry's transient.
// It ends at the reach. pushLines and pushMean measure over it.
Real pushWindowStart(const Plate& c);
// A push's forces as lines F = a + k z in the centre's depth (least squares over its window,
// pushWindowStart to the reach; RFT has a = 0), and the exponent of |F| in z there.
struct PlateLines {
  Real ax = 0, kx = 0, az = 0, kz = 0;  // N/m, N/m^2
  Real exponent = 0;
};
PlateLines pushLines(const Plate& c, const PlateRun& p);
// A drag's mean forces over the last half of its 3 L (N/m: x along +x, z upwards).
Vec2 dragMean(const Plate& c, const PlateRun& p);
// A push's mean forces over its window (N/m). Where the force is not a line in z (a
// fast push rings with the layer's waves: 4,500 N/m of rho c v L against 300 of rho L v^2 at
// 2 m/s), the mean over the window's several round trips of the wave is the robust measure.
Vec2 pushMean(const Plate& c, const PlateRun& p);
// Bearing capacity factors of a strip footing in plane strain for friction angle phi (rad):
// Prandtl-Reissner's N_q = exp(pi tan phi) tan^2(pi/4 + phi/2) (exact for a weightless
// rigid-plastic soil) and Meyerhof's N_gamma = (N_q - 1) tan(1.4 phi). A footing of width B at
// depth z bears q B = gamma z N_q B + gamma B^2 N_gamma / 2 per metre.
struct BearingFactors {
  Real n_q = 0, n_gamma = 0;
};
BearingFactors bearingFactors(Real phi);
// RFT's generic stresses per unit depth (Li et al. 2013, eq. S2-S3: the first terms of a Fourier
// series in 2 beta and gamma, fitted to nine media; N/cm^3 = 1e6 N/m^3, to be scaled by one
// factor zeta per medium): alpha_z upwards, alpha_x against the motion's +x (a plate moving in
// +x feels F_x = -alpha_x |z| L). beta and gamma in rad, gamma > 0 downwards.
struct RftStress {
  Real x = 0, z = 0;  // N/m^3 at zeta = 1
};
RftStress rftGeneric(Real beta, Real gamma);
// The layer's weight as its initial stress (sigma_yy = -gamma z below the top of each point's
// column of the lattice of spacing `spacing`, sigma_xx = sigma_zz = K0 sigma_yy with the elastic
// K0 = nu / (1 - nu) of a laterally confined layer), so that gravity does not start it ringing
// as a sudden load would (to twice the static stress, undamped). Material 0's.
void layerWeightAsStress(World& w, Real spacing);

}  // namespace mpm_sdem::cases
