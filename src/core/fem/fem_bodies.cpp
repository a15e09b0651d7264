#include "mpm_sdem/core/fem/fem_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mpm_sdem/core/coupling/restitution.hpp"

namespace mpm_sdem {

namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

Problem rangeOf(const char* key, Real v, const limits::Range& r) {
  const Problem p = limits::rangeProblem(v, r);
  return p.empty() ? p : p.under(key);
}

// The rotation of a triangle's deformation gradient, R = [c -s; s c] of F = R S with S symmetric
// (2D polar decomposition): the angle of (F00 + F11, F10 - F01), without trigonometry. The
// identity for the linear model, and for an F whose angle is undefined (both zero).
struct Rotation {
  Real c = 1, s = 0;
};
Rotation corotation(Real f00, Real f01, Real f10, Real f11, FemModel model) {
  if (model != FemModel::kCorotational) return {};
  const Real a = f00 + f11, b = f10 - f01, r = std::sqrt(a * a + b * b);
  if (!(r > 0)) return {};
  return {a / r, b / r};
}

// A 2 x 2 tensor in components.
struct Tensor2 {
  Real xx = 0, xy = 0, yx = 0, yy = 0;
};

// sum_K a_K (x) grad N_K over a triangle's nodes: F for the positions, its rate for the
// velocities.
template <class Element>
Tensor2 nodalGradient(const Element& e, const std::vector<Real>& ax, const std::vector<Real>& ay) {
  Tensor2 g;
  for (int k = 0; k < 3; ++k) {
    const int n = e.node[k];
    g.xx += ax[n] * e.dndx[k][0];
    g.xy += ax[n] * e.dndx[k][1];
    g.yx += ay[n] * e.dndx[k][0];
    g.yy += ay[n] * e.dndx[k][1];
  }
  return g;
}

// sym(R^T A), the corotated frame's symmetric part (its yx equals its xy).
Tensor2 corotatedSymmetric(const Rotation& R, const Tensor2& A) {
  Tensor2 e;
  e.xx = R.c * A.xx + R.s * A.yx;
  e.yy = -R.s * A.xy + R.c * A.yy;
  e.xy = e.yx = Real(0.5) * (R.c * A.xy + R.s * A.yy - R.s * A.xx + R.c * A.yx);
  return e;
}

// Outward normal of a boundary segment a -> b (the body on its left), unit.
Vec2 outwardNormal(const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  return Vec2(e.y(), -e.x()) / e.norm();
}

}  // namespace

const char* femModelName(FemModel m) {
  return m == FemModel::kLinear ? "linear" : "corotational";
}

Problem femBodyProblem(const FemBodyDef& d) {
  if (Problem p = limits::nameProblem(d.name); !p.empty()) return p.under("name");
  if (Problem p = meshProblem(d.mesh); !p.empty()) return p.under("mesh");
  for (const Vec2& v : d.mesh.nodes) {
    for (int a = 0; a < 2; ++a)
      if (Problem p = rangeOf("outline", v[a], limits::kCoordinate); !p.empty()) return p;
  }
  if (Problem p = rangeOf("density", d.density, limits::kDensity); !p.empty()) return p;
  if (Problem p = rangeOf("youngs_modulus", d.youngs_modulus, limits::kModulus); !p.empty())
    return p;
  if (!(d.poisson_ratio >= 0 && d.poisson_ratio <= 0.49))
    return {"poisson_ratio", "must be in [0, 0.49] (plane strain locks towards 0.5), got " +
                                 std::to_string(d.poisson_ratio)};
  if (!(d.mass_damping >= 0 && d.mass_damping <= 1e6))
    return {"mass_damping", "must be in [0, 1e6] 1/s, got " + std::to_string(d.mass_damping)};
  if (!(d.stiffness_damping >= 0 && d.stiffness_damping <= 1))
    return {"stiffness_damping", "must be in [0, 1] s, got " + std::to_string(d.stiffness_damping)};
  if (Problem p = rangeOf("friction", d.friction, limits::kFriction); !p.empty()) return p;
  if (Problem p = rangeOf("restitution", d.restitution, limits::kRestitution); !p.empty()) return p;
  if (!(std::abs(d.angular_velocity) <= 1e4))
    return {"angular_velocity", "must be finite, at most 1e4 rad/s"};
  for (const Vec2* v : {&d.velocity, &d.held_velocity}) {
    if (!(v->allFinite() && v->norm() <= limits::kSpeed.max))
      return {v == &d.velocity ? "velocity" : "held_velocity",
              "must be finite and at most " + std::to_string(limits::kSpeed.max) + " m/s"};
  }
  for (const Box& b : d.held)
    if (!(b.min.allFinite() && b.max.allFinite() && (b.min.array() <= b.max.array()).all()))
      return {"held", "each box needs finite corners with min <= max"};
  return {};
}

Real FemBodies::vonMises(const Stress& s) {
  // Three-dimensional: plane strain carries sigma_zz.
  const Real a = s.xx - s.yy, b = s.yy - s.zz, c = s.zz - s.xx;
  return std::sqrt(Real(0.5) * (a * a + b * b + c * c) + 3 * s.xy * s.xy);
}

void FemBodies::nodalVonMises(std::vector<Real>& out) const {
  out.assign(x_.size(), 0);
  std::vector<int> count(x_.size(), 0);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Real s = vonMises(stress_[e]);
    for (const int k : elements_[e].node) {
      out[k] += s;
      ++count[k];
    }
  }
  for (std::size_t k = 0; k < out.size(); ++k) out[k] /= count[k];  // every node has a triangle
}

FemBodies::FemBodies(const std::vector<FemBodyDef>& defs, const Vec2& gravity)
    : defs_(defs), gravity_(gravity) {
  for (std::size_t i = 0; i < defs.size(); ++i) {
    const FemBodyDef& d = defs[i];
    if (Problem p = femBodyProblem(d); !p.empty())
      throw std::invalid_argument("fem_bodies[" + std::to_string(i) + "] '" + d.name +
                                  "': " + p.text());
    const int body = static_cast<int>(i);
    Body b;
    b.first_node = totalNodes();
    b.node_count = static_cast<int>(d.mesh.nodes.size());
    b.first_element = totalElements();
    b.element_count = static_cast<int>(d.mesh.triangles.size());
    b.zeta = restitutionDampingRatio(d.restitution);
    max_zeta_ = std::max(max_zeta_, b.zeta);
    bodies_.push_back(b);
    for (const Vec2& v : d.mesh.nodes) {
      X_.push_back(v.x());
      Y_.push_back(v.y());
      vx_.push_back(d.velocity.x());
      vy_.push_back(d.velocity.y());
      node_body_.push_back(body);
      mass_.push_back(0);
      bool held = false;
      for (const Box& box : d.held)
        held =
            held || ((v.array() >= box.min.array()).all() && (v.array() <= box.max.array()).all());
      inv_mass_.push_back(held ? 0 : 1);  // 1: set from the mass below
      held_velocity_.push_back(held ? d.held_velocity : Vec2(0, 0));
      alpha_.push_back(d.mass_damping);
    }
    // Plane strain Lame constants.
    const Real E = d.youngs_modulus, nu = d.poisson_ratio;
    const Real lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    const Real wave = std::sqrt((lambda + 2 * mu) / d.density);  // c_p
    for (const auto& t : d.mesh.triangles) {
      Element e;
      for (int k = 0; k < 3; ++k) e.node[k] = b.first_node + t[k];
      e.body = body;
      const Vec2 p0 = d.mesh.nodes[t[0]], p1 = d.mesh.nodes[t[1]], p2 = d.mesh.nodes[t[2]];
      const Real twice = cross(p1 - p0, p2 - p0);
      e.area = Real(0.5) * twice;
      // grad N_k = perp(x_{k+2} - x_{k+1}) / 2A, perp(v) = (v.y, -v.x) rotated inwards.
      const Vec2 p[3] = {p0, p1, p2};
      for (int k = 0; k < 3; ++k) {
        const Vec2 opp = p[(k + 2) % 3] - p[(k + 1) % 3];
        e.dndx[k][0] = -opp.y() / twice;
        e.dndx[k][1] = opp.x() / twice;
      }
      e.lambda = lambda;
      e.mu = mu;
      // Lumped mass: a third of the triangle's to each corner.
      for (int k = 0; k < 3; ++k) mass_[e.node[k]] += d.density * e.area / 3;
      // Explicit step: the least altitude over the P-wave speed, less for stiffness damping.
      const Real longest = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
      const Real h = twice / longest;
      const Real xi = d.stiffness_damping * wave / h;
      element_step_ = std::min(element_step_, h / wave * (std::sqrt(1 + xi * xi) - xi));
      elements_.push_back(e);
    }
    // Boundary segments, linked to their neighbours along the outline.
    const std::vector<BoundaryEdge> edges = boundaryEdges(d.mesh);
    const int first_segment = static_cast<int>(segments_.size());
    std::vector<int> starts(d.mesh.nodes.size(), -1), ends(d.mesh.nodes.size(), -1);
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const BoundaryEdge& be = edges[k];
      Segment s;
      s.a = b.first_node + be.a;
      s.b = b.first_node + be.b;
      s.body = body;
      const Vec2 A = d.mesh.nodes[be.a], B = d.mesh.nodes[be.b];
      s.claim = Real(0.5) * std::abs(cross(B - A, d.mesh.nodes[be.opposite] - A)) / (B - A).norm();
      starts[be.a] = first_segment + static_cast<int>(k);
      ends[be.b] = first_segment + static_cast<int>(k);
      segments_.push_back(s);
    }
    for (std::size_t k = 0; k < edges.size(); ++k) {
      Segment& s = segments_[first_segment + k];
      // A pinched outline (two segments meeting at a node twice) keeps the last; the bisector
      // there is approximate.
      s.prev = ends[edges[k].a] >= 0 ? ends[edges[k].a] : first_segment + static_cast<int>(k);
      s.next = starts[edges[k].b] >= 0 ? starts[edges[k].b] : first_segment + static_cast<int>(k);
    }
    // The initial twist about the centre of mass.
    Real m = 0;
    Vec2 centre(0, 0);
    for (int k = b.first_node; k < b.first_node + b.node_count; ++k) {
      m += mass_[k];
      centre += mass_[k] * Vec2(X_[k], Y_[k]);
    }
    centre /= m;
    for (int k = b.first_node; k < b.first_node + b.node_count; ++k) {
      vx_[k] -= d.angular_velocity * (Y_[k] - centre.y());
      vy_[k] += d.angular_velocity * (X_[k] - centre.x());
    }
    coupling_.emplace_back();
  }
  const std::size_t n = X_.size();
  x_ = X_;
  y_ = Y_;
  tvx_ = vx_;
  tvy_ = vy_;
  fx_.assign(n, 0);
  fy_.assign(n, 0);
  cfx_.assign(n, 0);
  cfy_.assign(n, 0);
  on_boundary_.assign(n, 0);
  for (std::size_t k = 0; k < n; ++k) inv_mass_[k] = inv_mass_[k] > 0 ? 1 / mass_[k] : 0;
  for (const Segment& s : segments_) on_boundary_[s.a] = on_boundary_[s.b] = 1;
  stress_.assign(elements_.size(), Stress());
  for (int s = 0; s < shapeCount(); ++s)
    if (movable(s)) lightest_ = std::min(lightest_, mass(s));
  refreshSegments();
}

void FemBodies::setSurroundings(const Vec2& lo, const Vec2& hi, const WallDef walls[4],
                                const ContactBodies* obstacles) {
  domain_min_ = lo;
  domain_max_ = hi;
  for (int k = 0; k < 4; ++k) walls_[k] = walls[k];
  has_domain_ = true;
  obstacles_ = obstacles;
}

void FemBodies::refreshSegments() {
  segment_vertices_.resize(2 * segments_.size());
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    segment_vertices_[2 * s] = position(segments_[s].a);
    segment_vertices_[2 * s + 1] = position(segments_[s].b);
  }
}

Real FemBodies::phiA(int s, const Vec2& x) const {
  const Vec2* v = coreVertices(s);
  const Vec2 e = v[1] - v[0];
  const Real t = std::clamp((x - v[0]).dot(e) / e.squaredNorm(), Real(0), Real(1));
  return 1 - t;
}

CoreDistance FemBodies::closest(int s, const Vec2& x) const {
  const Vec2* v = coreVertices(s);
  const Vec2 A = v[0], B = v[1], e = B - A;
  const Vec2 n = outwardNormal(A, B);
  const Real t = std::clamp((x - A).dot(e) / e.squaredNorm(), Real(0), Real(1));
  CoreDistance d;
  d.point = A + t * e;
  const Vec2 r = x - d.point;
  if (r.dot(n) >= 0) {  // in front: the distance to the segment
    d.distance = r.norm();
    d.normal = d.distance > 1e-12 * e.norm() ? Vec2(r / d.distance) : n;
    return d;
  }
  // Behind: the segment's own when between the bisectors at its ends and within its claim.
  d.normal = n;
  d.distance = kInfinity;
  const Segment& g = segments_[s];
  const Real depth = -(x - A).dot(n);
  if (depth > g.claim) return d;
  const Vec2* pv = coreVertices(g.prev);
  const Vec2* nv = coreVertices(g.next);
  const Vec2 mA = outwardNormal(pv[0], pv[1]) + n, mB = n + outwardNormal(nv[0], nv[1]);
  if (cross(mA, x - A) * cross(mA, e) < 0 || cross(mB, x - B) * cross(mB, -e) < 0) return d;
  d.distance = -depth;
  d.point = x + depth * n;  // the foot on the segment's line
  return d;
}

Box FemBodies::bounds(int s) const {
  // The segment and the strip behind it that it claims.
  const Vec2* v = coreVertices(s);
  const Vec2 in = -segments_[s].claim * outwardNormal(v[0], v[1]);
  Box b{v[0].cwiseMin(v[1]), v[0].cwiseMax(v[1])};
  b.min = b.min.cwiseMin(v[0] + in).cwiseMin(v[1] + in);
  b.max = b.max.cwiseMax(v[0] + in).cwiseMax(v[1] + in);
  return b;
}

bool FemBodies::movable(int s) const {
  return inv_mass_[segments_[s].a] > 0 || inv_mass_[segments_[s].b] > 0;
}

Real FemBodies::mass(int s) const {
  const Real inv = Real(0.25) * (inv_mass_[segments_[s].a] + inv_mass_[segments_[s].b]);
  return inv > 0 ? 1 / inv : kInfinity;
}

Vec2 FemBodies::velocityAt(int s, const Vec2& x) const {
  const Real pa = phiA(s, x);
  const int a = segments_[s].a, b = segments_[s].b;
  return pa * Vec2(vx_[a], vy_[a]) + (1 - pa) * Vec2(vx_[b], vy_[b]);
}

Vec2 FemBodies::trialVelocityAt(int s, const Vec2& x) const {
  const Real pa = phiA(s, x);
  const int a = segments_[s].a, b = segments_[s].b;
  return pa * Vec2(tvx_[a], tvy_[a]) + (1 - pa) * Vec2(tvx_[b], tvy_[b]);
}

Mat2 FemBodies::inverseMass(int s, const Vec2& x) const {
  const Real pa = phiA(s, x), pb = 1 - pa;
  return (pa * pa * inv_mass_[segments_[s].a] + pb * pb * inv_mass_[segments_[s].b]) *
         Mat2::Identity();
}

BodyPose FemBodies::pose(int s) const {
  BodyPose p;
  p.position = coreVertices(s)[0];
  p.other = coreVertices(s)[1];
  return p;
}

Real FemBodies::movedSince(int s, const BodyPose& then) const {
  return std::max((coreVertices(s)[0] - then.position).norm(),
                  (coreVertices(s)[1] - then.other).norm());
}

void FemBodies::internalForces() {
  // Eq. 20 per triangle: f_K = -A P grad N_K, with F = sum_K x_K (x) grad N_K. The corotational
  // form polar-decomposes F = R S, applies the linear law to eps = sym(S) - I and rotates the
  // stress back (P = R sigma); the linear form takes R = I. Written out in components: the
  // substeps of multi-rate bodies call this tens of times per material step.
  std::fill(fx_.begin(), fx_.end(), Real(0));
  std::fill(fy_.begin(), fy_.end(), Real(0));
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    const Element& e = elements_[i];
    const FemBodyDef& d = defs_[e.body];
    const Tensor2 F = nodalGradient(e, x_, y_);
    const Rotation R = corotation(F.xx, F.xy, F.yx, F.yy, d.model);
    Tensor2 eps = corotatedSymmetric(R, F);  // S = R^T F; eps = sym(S) - I
    eps.xx -= 1;
    eps.yy -= 1;
    const Real tr = eps.xx + eps.yy;
    Real s00 = e.lambda * tr + 2 * e.mu * eps.xx, s11 = e.lambda * tr + 2 * e.mu * eps.yy;
    Real s01 = 2 * e.mu * eps.xy;
    stress_[i].zz = e.lambda * tr;
    if (d.stiffness_damping > 0) {  // Rayleigh's beta K v: the linear law on the strain rate
      const Tensor2 rate = corotatedSymmetric(R, nodalGradient(e, vx_, vy_));
      const Real b = d.stiffness_damping, rtr = rate.xx + rate.yy;
      s00 += b * (e.lambda * rtr + 2 * e.mu * rate.xx);
      s11 += b * (e.lambda * rtr + 2 * e.mu * rate.yy);
      s01 += b * 2 * e.mu * rate.xy;
    }
    // P = R sigma; the nodal forces -A P grad N_K; the Cauchy stress R sigma R^T.
    const Real p00 = R.c * s00 - R.s * s01, p01 = R.c * s01 - R.s * s11;
    const Real p10 = R.s * s00 + R.c * s01, p11 = R.s * s01 + R.c * s11;
    for (int k = 0; k < 3; ++k) {
      const Real g0 = e.dndx[k][0], g1 = e.dndx[k][1];
      fx_[e.node[k]] -= e.area * (p00 * g0 + p01 * g1);
      fy_[e.node[k]] -= e.area * (p10 * g0 + p11 * g1);
    }
    stress_[i].xx = p00 * R.c - p01 * R.s;
    stress_[i].yy = p10 * R.s + p11 * R.c;
    stress_[i].xy = p00 * R.s + p01 * R.c;
  }
}

Real FemBodies::strainEnergy() const {
  Real sum = 0;
  for (const Element& e : elements_) {
    const Tensor2 F = nodalGradient(e, x_, y_);
    Tensor2 eps = corotatedSymmetric(corotation(F.xx, F.xy, F.yx, F.yy, defs_[e.body].model), F);
    eps.xx -= 1;
    eps.yy -= 1;
    const Real tr = eps.xx + eps.yy;
    const Real norm2 = eps.xx * eps.xx + 2 * eps.xy * eps.xy + eps.yy * eps.yy;
    sum += e.area * (e.mu * norm2 + Real(0.5) * e.lambda * tr * tr);
  }
  return sum;
}

Real FemBodies::kineticEnergy() const {
  Real sum = 0;
  for (std::size_t k = 0; k < x_.size(); ++k)
    sum += Real(0.5) * mass_[k] * (vx_[k] * vx_[k] + vy_[k] * vy_[k]);
  return sum;
}

Real FemBodies::potentialEnergy() const {
  Real sum = 0;
  for (std::size_t k = 0; k < x_.size(); ++k)
    sum -= mass_[k] * (gravity_.x() * x_[k] + gravity_.y() * y_[k]);
  return sum;
}

void FemBodies::beginCoupling(Real dt) {
  internalForces();
  for (Load& c : coupling_) c = Load();
  std::fill(cfx_.begin(), cfx_.end(), Real(0));
  std::fill(cfy_.begin(), cfy_.end(), Real(0));
  const int n = substepsFor(dt);
  if (n > 1) {
    // Multi-rate: the nodes' motion free of the material over the step, in the elements' own
    // substeps (one explicit step of dt past the element step would amplify the stiff modes,
    // not predict them). step() then takes this motion and adds the material's impulse as a
    // kick at its end (a split of the step: the elements, then the contact), so that the
    // nodes end the step at the velocity the material's contact saw: trial + impulse / m.
    saved_x_ = x_, saved_y_ = y_, saved_vx_ = vx_, saved_vy_ = vy_;
    for (int k = 0; k < n; ++k) {
      if (k > 0) internalForces();
      advance(dt / n, true);
    }
    tvx_ = vx_, tvy_ = vy_;
    free_x_ = x_, free_y_ = y_, free_vx_ = vx_, free_vy_ = vy_;
    x_ = saved_x_, y_ = saved_y_, vx_ = saved_vx_, vy_ = saved_vy_;
    internalForces();
    return;
  }
  for (std::size_t k = 0; k < x_.size(); ++k) {
    if (inv_mass_[k] == 0) {
      tvx_[k] = held_velocity_[k].x();
      tvy_[k] = held_velocity_[k].y();
      continue;
    }
    // Eq. 17 with the internal force, gravity and mass-proportional damping.
    tvx_[k] = vx_[k] + dt * (fx_[k] * inv_mass_[k] + gravity_.x() - alpha_[k] * vx_[k]);
    tvy_[k] = vy_[k] + dt * (fy_[k] * inv_mass_[k] + gravity_.y() - alpha_[k] * vy_[k]);
  }
}

void FemBodies::applyForce(int s, const Vec2& force, const Vec2& x) {
  pushForce(s, force, x);
  recordForce(s, force, x);
}

void FemBodies::pushForce(int s, const Vec2& force, const Vec2& x) {
  const Real pa = phiA(s, x);
  const Segment& g = segments_[s];
  cfx_[g.a] += pa * force.x();
  cfy_[g.a] += pa * force.y();
  cfx_[g.b] += (1 - pa) * force.x();
  cfy_[g.b] += (1 - pa) * force.y();
}

void FemBodies::recordForce(int s, const Vec2& force, const Vec2&) {
  const Segment& g = segments_[s];
  coupling_[g.body].force += force;
  ++coupling_[g.body].contacts;
}

int FemBodies::substep(Real h, Real max_substep, Real) {
  step(h, max_substep);
  std::fill(cfx_.begin(), cfx_.end(), Real(0));
  std::fill(cfy_.begin(), cfy_.end(), Real(0));
  return 1;
}

void FemBodies::applyImpulse(int s, const Vec2& impulse, const Vec2& x, Real dt) {
  const Real pa = phiA(s, x);
  const Segment& g = segments_[s];
  tvx_[g.a] += pa * impulse.x() * inv_mass_[g.a];
  tvy_[g.a] += pa * impulse.y() * inv_mass_[g.a];
  tvx_[g.b] += (1 - pa) * impulse.x() * inv_mass_[g.b];
  tvy_[g.b] += (1 - pa) * impulse.y() * inv_mass_[g.b];
  applyForce(s, impulse / dt, x);
}

void FemBodies::meetSurroundings(int k, Real dt) {
  // Momentum-based contact with the static side (seed 002 eq. 47-52 with an infinite mass
  // there): the node may close its gap within the step and no further; the normal velocity
  // beyond that is removed and friction takes off tangential speed in proportion. Written as a
  // wall rule (applyWall) in the frame that closes the gap exactly.
  Vec2 v(vx_[k], vy_[k]);
  const Vec2 x = position(k);
  auto meet = [&](const WallDef& wall, const Vec2& into, Real gap, const Vec2& surface_v) {
    const Vec2 closing = surface_v + std::max(gap, Real(0)) / dt * into;
    Vec2 u = v - closing;
    applyWall(wall, into.x(), into.y(), u.x(), u.y());
    v = u + closing;
  };
  if (has_domain_) {
    const Vec2 into[4] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};  // left, right, bottom, top
    const Real gap[4] = {x.x() - domain_min_.x(), domain_max_.x() - x.x(), x.y() - domain_min_.y(),
                         domain_max_.y() - x.y()};
    for (int w = 0; w < 4; ++w)
      if (gap[w] < dt * v.norm()) meet(walls_[w], into[w], gap[w], Vec2(0, 0));
  }
  if (obstacles_) {
    const ContactBodies& O = *obstacles_;
    const Real reach = dt * v.norm();
    for (int s = 0; s < O.shapeCount(); ++s) {
      if (O.movable(s)) continue;
      const Box b = O.bounds(s);
      if ((x.array() < b.min.array() - reach).any() || (x.array() > b.max.array() + reach).any())
        continue;
      const CoreDistance c = O.closest(s, x);
      const Real gap = c.distance - O.rounding(s);
      if (gap > reach) continue;
      const Real mu = std::min(O.friction(s), defs_[node_body_[k]].friction);
      meet(WallDef{WallType::kFriction, mu}, -c.normal, gap, O.velocityAt(s, x));
    }
  }
  vx_[k] = v.x();
  vy_[k] = v.y();
}

void FemBodies::advance(Real h, bool surroundings) {
  for (std::size_t k = 0; k < x_.size(); ++k) {
    if (inv_mass_[k] == 0) {
      vx_[k] = held_velocity_[k].x();
      vy_[k] = held_velocity_[k].y();
    } else {
      vx_[k] += h * (fx_[k] * inv_mass_[k] + gravity_.x() - alpha_[k] * vx_[k]);
      vy_[k] += h * (fy_[k] * inv_mass_[k] + gravity_.y() - alpha_[k] * vy_[k]);
      if (surroundings && on_boundary_[k]) meetSurroundings(static_cast<int>(k), h);
    }
    x_[k] += h * vx_[k];
    y_[k] += h * vy_[k];
  }
}

int FemBodies::step(Real dt, Real) {
  const int n = substepsFor(dt);
  if (n > 1) {
    // beginCoupling's free motion, then the contact forces' impulse as a kick at the step's
    // end: momentum exact, and the nodes' velocity the one the material's contact assumed. No
    // displacement of the kick over this step (it moved surface nodes past their elements):
    // the next step's substeps carry it, with the elements' response.
    for (std::size_t k = 0; k < x_.size(); ++k) {
      x_[k] = free_x_[k];
      y_[k] = free_y_[k];
      vx_[k] = free_vx_[k];  // the trial velocities have the impulses of some schemes too
      vy_[k] = free_vy_[k];
      if (inv_mass_[k] == 0) continue;
      vx_[k] += dt * cfx_[k] * inv_mass_[k];
      vy_[k] += dt * cfy_[k] * inv_mass_[k];
      if (on_boundary_[k]) meetSurroundings(static_cast<int>(k), dt);
    }
    refreshSegments();
    return n;
  }
  for (std::size_t k = 0; k < x_.size(); ++k) {
    if (inv_mass_[k] == 0) {
      vx_[k] = held_velocity_[k].x();
      vy_[k] = held_velocity_[k].y();
    } else {
      // The trial velocity without the impulses, plus every contact force over the step.
      vx_[k] += dt * ((fx_[k] + cfx_[k]) * inv_mass_[k] + gravity_.x() - alpha_[k] * vx_[k]);
      vy_[k] += dt * ((fy_[k] + cfy_[k]) * inv_mass_[k] + gravity_.y() - alpha_[k] * vy_[k]);
      if (on_boundary_[k]) meetSurroundings(static_cast<int>(k), dt);
    }
    x_[k] += dt * vx_[k];
    y_[k] += dt * vy_[k];
  }
  refreshSegments();
  return 1;
}

}  // namespace mpm_sdem
