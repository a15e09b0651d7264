/// \file
/// Deformable bodies by the finite element method (seed 002 sec. 2.3, in 2D plane strain):
/// linear triangles with lumped mass, stepped by central differences in the same step as the
/// material (eq. 17-21: p_K^{n+1/2} = p_K^{n-1/2} + dt f_K^n). The material meets a body at its
/// boundary segments, the edges of one triangle: each is a contact shape (ContactBodies), its
/// velocity and response interpolated from its two nodes (seed 002 eq. 44-49), so that the
/// particle-to-surface scheme (sec. 3) and the spring schemes work against it unchanged. Bodies
/// also meet the domain walls and the blocks that forces do not move (static and kinematic),
/// node by node; FEM bodies do not meet each other or dynamic blocks.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mpm_sdem/core/coupling/contact_bodies.hpp"
#include "mpm_sdem/core/fem/fem_mesh.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/boundary.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// How an element turns strain into stress.
enum class FemModel {
  kLinear,        ///< small strain: sigma = C eps(u); rotations show up as strain
  kCorotational,  ///< each triangle's rotation (polar decomposition of F) taken out before the
                  ///< linear law and put back after: large rotation, small strain
};
/// The model's name as a scene writes it.
const char* femModelName(FemModel m);

/// One deformable body (scene section `fem_bodies`): its mesh, material, damping and held nodes.
struct FemBodyDef {
  std::string name;                          ///< unique among the FEM bodies
  FemMesh mesh;                              ///< reference configuration, world frame (m)
  FemModel model = FemModel::kCorotational;  ///< linear or corotational
  Real density = 1000;                       ///< kg/m^3
  Real youngs_modulus = 1e6;                 ///< Pa
  Real poisson_ratio = 0.3;                  ///< plane strain: below 0.5
  ///@{
  /// Rayleigh damping C = alpha M + beta K: alpha (1/s) damps the low modes (2 zeta w = alpha),
  /// beta (s) the high ones (2 zeta = beta w).
  Real mass_damping = 0;
  Real stiffness_damping = 0;
  ///@}
  Real friction = 0.5;        ///< Coulomb coefficient with the material, blocks and walls
  Real restitution = 1;       ///< of spring contacts with the material (IMP schemes), in (0, 1]
  Vec2 velocity{0, 0};        ///< initial, of the centre of mass (m/s)
  Real angular_velocity = 0;  ///< initial, about the centre of mass (rad/s)
  ///@{
  /// Held nodes: those inside any of these boxes (m), moving at held_velocity (m/s) - a clamped
  /// edge, or a driven one.
  std::vector<Box> held;
  Vec2 held_velocity{0, 0};
  ///@}
};

/// Why the body cannot be simulated (its name, meshProblem, values out of range), naming the
/// key; empty when it can.
Problem femBodyProblem(const FemBodyDef& def);

/// The bodies are fixed for a world's life: a body is its place in the list.
class FemBodies final : public ContactBodies {
 public:
  /// Throws std::invalid_argument with femBodyProblem's message.
  FemBodies(const std::vector<FemBodyDef>& defs, const Vec2& gravity);

  /// How many bodies.
  int count() const { return static_cast<int>(defs_.size()); }
  /// The acceleration of gravity (m/s^2) on every node from the next step on.
  void setGravity(const Vec2& gravity) { gravity_ = gravity; }
  /// Body i's definition.
  const FemBodyDef& def(int i) const { return defs_[i]; }
  ///@{
  /// Body i's nodes first_node(i) .. first_node(i) + nodeCount(i) - 1, elements likewise.
  int firstNode(int i) const { return bodies_[i].first_node; }
  int nodeCount(int i) const { return bodies_[i].node_count; }
  int firstElement(int i) const { return bodies_[i].first_element; }
  int elementCount(int i) const { return bodies_[i].element_count; }
  int totalNodes() const { return static_cast<int>(x_.size()); }
  int totalElements() const { return static_cast<int>(elements_.size()); }
  ///@}
  ///@{
  /// Node k now (m), its reference position, velocity (m/s) and lumped mass (kg/m).
  Vec2 position(int k) const { return {x_[k], y_[k]}; }
  Vec2 reference(int k) const { return {X_[k], Y_[k]}; }
  Vec2 velocity(int k) const { return {vx_[k], vy_[k]}; }
  Real nodeMass(int k) const { return mass_[k]; }
  ///@}
  /// Whether node k is held (moves at its body's held_velocity).
  bool held(int k) const { return inv_mass_[k] == 0; }
  /// Element e's three nodes, counter-clockwise.
  const std::array<int, 3>& elementNodes(int e) const { return elements_[e].node; }
  /// Cauchy stress of element e at the start of the last step (Pa): xx, yy, xy, and zz (plane
  /// strain), and its von Mises equivalent.
  struct Stress {
    ///@{
    /// Pa
    Real xx = 0, yy = 0, xy = 0, zz = 0;
    ///@}
    template <class Archive>
    void serialize(Archive& ar) {
      ar(xx, yy, xy, zz);
    }
  };
  /// Element e's stress.
  const Stress& stress(int e) const { return stress_[e]; }
  /// The von Mises equivalent of a stress (Pa).
  static Real vonMises(const Stress& s);
  /// Each node's von Mises stress: the mean over the triangles that share it (Pa), for outputs.
  void nodalVonMises(std::vector<Real>& out) const;
  ///@{
  /// Kinetic and strain energy (J/m) and the gravitational potential energy -m g.x (J/m).
  Real kineticEnergy() const;
  Real strainEnergy() const;
  Real potentialEnergy() const;
  ///@}
  /// What the material did to each body in the last step (N/m) and its contact count.
  struct Load {
    Vec2 force{0, 0};  ///< N/m
    int contacts = 0;  ///< contacts that carried it
    template <class Archive>
    void serialize(Archive& ar) {
      ar(force, contacts);
    }
  };
  /// Each body's load from the material in the last step.
  const std::vector<Load>& coupling() const { return coupling_; }

  /// The explicit step the elements allow (s): the smallest, over triangles, of h / c_p (h the
  /// triangle's least altitude, c_p = sqrt((lambda + 2 mu) / rho) the plane-strain P-wave speed)
  /// reduced by stiffness damping to (h / c_p)(sqrt(1 + xi^2) - xi) with xi = beta c_p / h.
  /// World multiplies it by kappa_1 (seed 000 eq. 51's CFL factor).
  Real elementStep() const { return element_step_; }
  /// Multi-rate stepping: the nodes take substeps of at most max_substep (s) within each
  /// material step, their internal forces evaluated anew in each, the material's forces held
  /// at the step's mean (momentum exact); infinity (the default): one step per material step,
  /// which the element step must then bound.
  void setMaxSubstep(Real max_substep) { max_substep_ = max_substep; }
  /// How many substeps a step of dt takes (1 without multi-rate stepping).
  int substepsFor(Real dt) const {
    return dt > max_substep_ ? static_cast<int>(std::ceil(dt / max_substep_)) : 1;
  }

  /// What the nodes meet besides the material: the domain walls and the shapes of `obstacles`
  /// that forces do not move (static and kinematic blocks); nullptr for none.
  void setSurroundings(const Vec2& domain_min, const Vec2& domain_max, const WallDef walls[4],
                       const ContactBodies* obstacles);

  /// ContactBodies: one shape per boundary segment, its two nodes' positions as the core (a
  /// segment, no rounding). A point behind a segment, within half its triangle's depth and
  /// between the bisectors at its ends, is inside at that depth (negative distance); further
  /// in, the segment does not claim it. So every point near the outline belongs to one segment,
  /// and the nearest one (forEachContact's least distance) is the surface's.
  int shapeCount() const override { return static_cast<int>(segments_.size()); }
  int bodyOf(int s) const override { return segments_[s].body; }
  /// 1 << 62 | body: apart from the blocks' keys (44 bits).
  std::uint64_t bodyKey(int s) const override {
    return (std::uint64_t{1} << 62) | static_cast<std::uint64_t>(segments_[s].body);
  }
  const Vec2* coreVertices(int s) const override { return segment_vertices_.data() + 2 * s; }
  int coreVertexCount(int) const override { return 2; }
  Real rounding(int) const override { return 0; }
  CoreDistance closest(int s, const Vec2& x) const override;
  Box bounds(int s) const override;
  Real friction(int s) const override { return defs_[segments_[s].body].friction; }
  Real dampingRatio(int s) const override { return bodies_[segments_[s].body].zeta; }
  bool movable(int s) const override;
  /// The segment's mass at its middle (eq. 49 with phi = 1/2 at both nodes).
  Real mass(int s) const override;
  Vec2 velocityAt(int s, const Vec2& x) const override;
  /// Eq. 49: sum_J phi_J^2 / m_J, the same along every direction.
  Mat2 inverseMass(int s, const Vec2& x) const override;
  Real lightestMass() const override { return lightest_; }
  Real maxDampingRatio() const override { return max_zeta_; }
  /// A segment's two ends (position, other) when asked.
  BodyPose pose(int s) const override;
  Real movedSince(int s, const BodyPose& then) const override;
  /// Internal forces at the current positions (eq. 20) and the trial velocities: each free node's
  /// velocity after dt under them, gravity and damping (eq. 17), over the substeps of
  /// setMaxSubstep (the internal forces anew in each, the state then put back); held nodes take
  /// their velocity.
  void beginCoupling(Real dt) override;
  Vec2 trialVelocityAt(int s, const Vec2& x) const override;
  /// Eq. 46 and 53: a force at a point of a segment goes to its nodes by phi_J.
  void applyForce(int s, const Vec2& force, const Vec2& x) override;
  /// Eq. 44: the trial velocities of the two nodes change by phi_J impulse / m_J.
  void applyImpulse(int s, const Vec2& impulse, const Vec2& x, Real dt) override;
  void pushForce(int s, const Vec2& force, const Vec2& x) override;
  void recordForce(int s, const Vec2& force, const Vec2& x) override;
  /// A step of h under the internal forces of beginCoupling and the forces pushed since the
  /// last substep (then cleared).
  int substep(Real h, Real max_substep, Real share) override;
  /// No substeps: the element step joins the world's step bound instead.
  Real stableStep(Real) const override { return std::numeric_limits<Real>::infinity(); }
  /// v^{n+1/2} = trial + dt f_contact / m; the walls and obstacles; x^{n+1} = x^n + dt v^{n+1/2}.
  /// Multi-rate (substepsFor(dt) > 1): beginCoupling's free motion over the substeps, then the
  /// contact forces' impulse dt f_contact / m as a kick at the end (moving the nodes from the
  /// next step on). max_substep (the blocks') is not the elements' bound.
  int step(Real dt, Real max_substep) override;

 private:
  friend struct detail::CheckpointAccess;
  /// The nodes' motion and what the step carries over (the mesh follows from the definitions).
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(x_, y_, vx_, vy_, tvx_, tvy_, fx_, fy_, cfx_, cfy_, stress_, segment_vertices_, coupling_);
  }
  struct Element {
    std::array<int, 3> node;
    int body = 0;
    Real area = 0;            ///< reference (m^2)
    Real dndx[3][2];          ///< reference shape-function gradients (1/m)
    Real lambda = 0, mu = 0;  ///< Lame constants (Pa)
  };
  struct Segment {
    int a = 0, b = 0;  ///< nodes, body on the left of a -> b
    int body = 0;
    Real claim = 0;          ///< how deep behind it a point still belongs to it (m)
    int prev = 0, next = 0;  ///< the boundary segments ending at a and starting at b
  };
  struct Body {
    int first_node = 0, node_count = 0, first_element = 0, element_count = 0;
    Real zeta = 0;
  };
  /// Phi_a of the point of segment s nearest x (clamped to the segment).
  Real phiA(int s, const Vec2& x) const;
  void internalForces();
  void refreshSegments();
  void meetSurroundings(int k, Real dt);
  /// One substep of h of every node under the internal forces, gravity and damping, free of
  /// the material; with surroundings, the walls and obstacles met.
  void advance(Real h, bool surroundings);

  std::vector<FemBodyDef> defs_;
  std::vector<Body> bodies_;
  /// Nodes (structure of arrays).
  std::vector<Real> x_, y_, X_, Y_, vx_, vy_, tvx_, tvy_, fx_, fy_, cfx_, cfy_;
  std::vector<Real> mass_, inv_mass_, alpha_;
  std::vector<int> node_body_;
  std::vector<Vec2> held_velocity_;
  std::vector<char> on_boundary_;
  std::vector<Element> elements_;
  std::vector<Stress> stress_;
  std::vector<Segment> segments_;
  std::vector<Vec2> segment_vertices_;
  std::vector<Load> coupling_;
  Vec2 gravity_{0, 0};
  Real element_step_ = std::numeric_limits<Real>::infinity();
  Real max_substep_ = std::numeric_limits<Real>::infinity();  ///< setMaxSubstep's
  /// beginCoupling's copy of the nodes' state while it runs the free substeps.
  std::vector<Real> saved_x_, saved_y_, saved_vx_, saved_vy_;
  /// Multi-rate: the nodes' state at the end of the step's free motion (beginCoupling's).
  std::vector<Real> free_x_, free_y_, free_vx_, free_vy_;
  Real lightest_ = std::numeric_limits<Real>::infinity();
  Real max_zeta_ = 0;
  /// Surroundings.
  Vec2 domain_min_{0, 0}, domain_max_{0, 0};
  WallDef walls_[4];
  bool has_domain_ = false;
  const ContactBodies* obstacles_ = nullptr;
};

}  // namespace mpm_sdem
