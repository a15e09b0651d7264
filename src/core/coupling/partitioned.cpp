#include "coupling/partitioned.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "mpm/transfer.hpp"
#include "state_archive.hpp"

namespace mpm_sdem {

namespace {

// The closed outline of a body's shape, counter-clockwise (m).
std::vector<Vec2> outline(const ShapeDef& shape, Real spacing) {
  std::vector<Vec2> poly;
  switch (shape.type) {
    case ShapeType::kRectangle:
      poly = {shape.min, Vec2(shape.max.x(), shape.min.y()), shape.max,
              Vec2(shape.min.x(), shape.max.y())};
      break;
    case ShapeType::kPolygon:
      poly = shape.vertices;
      break;
    case ShapeType::kDisk: {
      const int n = std::max(8, static_cast<int>(std::ceil(2 * M_PI * shape.radius / spacing)));
      for (int k = 0; k < n; ++k) {
        const Real a = 2 * M_PI * k / n;
        poly.push_back(shape.center + shape.radius * Vec2(std::cos(a), std::sin(a)));
      }
      break;
    }
  }
  if (signedArea(poly) < 0) std::reverse(poly.begin(), poly.end());
  return poly;
}

// poly moved inwards by d: each vertex along the bisector of its edges' inward normals, by d
// over the cosine of half the turn (capped for sharp corners).
std::vector<Vec2> inset(const std::vector<Vec2>& poly, Real d) {
  const std::size_t n = poly.size();
  std::vector<Vec2> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e0 = (poly[i] - poly[(i + n - 1) % n]).normalized();
    const Vec2 e1 = (poly[(i + 1) % n] - poly[i]).normalized();
    const Vec2 n0(-e0.y(), e0.x()), n1(-e1.y(), e1.x());  // inward for counter-clockwise
    const Vec2 m = (n0 + n1).normalized();
    out[i] = poly[i] + d / std::max<Real>(m.dot(n0), 0.2) * m;
  }
  return out;
}

}  // namespace

PartitionedCoupling::PartitionedCoupling(const CouplingDef& def, Real cell_size,
                                         const std::vector<BodyDef>& bodies)
    : Coupling(def), h_(cell_size) {
  // Boundary particles half a cell apart on each body's outline, inset (seed 003).
  const Real spacing = 0.5 * cell_size;
  for (const BodyDef& body : bodies) {
    const std::vector<Vec2> poly = inset(outline(body.shape, spacing), def.boundary_inset);
    const int first = static_cast<int>(x_.size());
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
      const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
      for (int k = 0; k < pieces; ++k) {
        x_.push_back(a + (b - a) * (static_cast<Real>(k) / pieces));
        v_.push_back(body.velocity);
        body_.push_back(static_cast<int>(&body - bodies.data()));
      }
    }
    const int last = static_cast<int>(x_.size()) - 1;
    for (int k = first; k < last; ++k) segments_.push_back({k, k + 1});
    if (last > first) segments_.push_back({last, first});
  }
  load_.assign(x_.size(), Vec2(0, 0));
  couple_.assign(x_.size(), 0);
  stamp_.assign(x_.size(), -1);
}

void PartitionedCoupling::attach(const Particles& P) {
  // Each boundary particle's host: the nearest point filled from the same body (points keep
  // their index for the life of the world). A boundary particle of a body without points has
  // none and moves with the grid.
  host_.assign(x_.size(), -1);
  std::vector<Real> best(x_.size(), std::numeric_limits<Real>::infinity());
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Vec2 xp(P.x[p], P.y[p]);
    for (std::size_t e = 0; e < x_.size(); ++e) {
      if (body_[e] != P.body[p]) continue;
      const Real d2 = (x_[e] - xp).squaredNorm();
      if (d2 < best[e]) {
        best[e] = d2;
        host_[e] = static_cast<int>(p);
      }
    }
  }
  offset_.resize(x_.size());
  for (std::size_t e = 0; e < x_.size(); ++e) offset_[e] = offsetFrom(P, x_[e], host_[e]);
}

Vec2 PartitionedCoupling::offsetFrom(const Particles& P, const Vec2& x, int host) {
  return host >= 0 ? Vec2(x - Vec2(P.x[host], P.y[host])) : Vec2(0, 0);
}

int PartitionedCoupling::nearestPoint(const CouplingStep& s, const Vec2& x, int body) const {
  // The points binned this step in the 3 x 3 tiles around x (a tile is 3 cells wide, so this
  // covers every point within three cells).
  const Tiles& T = s.tiles;
  const Grid& G = s.grid;
  const int a = static_cast<int>((x.x() - G.origin.x()) * G.inv_h) / Tiles::kSize;
  const int b = static_cast<int>((x.y() - G.origin.y()) * G.inv_h) / Tiles::kSize;
  int best = -1;
  Real best_d2 = std::numeric_limits<Real>::infinity();
  for (int tb = std::max(0, b - 1); tb <= std::min(T.ny - 1, b + 1); ++tb) {
    for (int ta = std::max(0, a - 1); ta <= std::min(T.nx - 1, a + 1); ++ta) {
      const int t = ta + tb * T.nx;
      for (int q = T.start[t]; q < T.start[t + 1]; ++q) {
        const int p = T.order[q];
        if (s.particles.body[p] != body) continue;
        const Real d2 = (Vec2(s.particles.x[p], s.particles.y[p]) - x).squaredNorm();
        if (d2 < best_d2) {
          best_d2 = d2;
          best = p;
        }
      }
    }
  }
  return best;
}

void PartitionedCoupling::bucketSegments(const Grid& G) {
  // Counting sort of the segments by the cell of their middle; they move every step.
  cells_x_ = G.nx - 1;
  cells_y_ = G.ny - 1;
  cell_start_.assign(static_cast<std::size_t>(cells_x_) * cells_y_ + 1, 0);
  segment_cell_.resize(segments_.size());
  longest_ = 0;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Vec2 a = x_[segments_[k][0]], b = x_[segments_[k][1]];
    longest_ = std::max(longest_, (b - a).norm());
    const Vec2 mid = (0.5 * (a + b) - G.origin) * G.inv_h;
    const int i = std::clamp(static_cast<int>(mid.x()), 0, cells_x_ - 1);
    const int j = std::clamp(static_cast<int>(mid.y()), 0, cells_y_ - 1);
    segment_cell_[k] = i + j * cells_x_;
    ++cell_start_[segment_cell_[k] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_segments_.resize(segments_.size());
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t k = 0; k < segments_.size(); ++k)
    cell_segments_[fill_[segment_cell_[k]]++] = static_cast<int>(k);
}

void PartitionedCoupling::contact(ContactBodies& B, int b, const Vec2& n, Real overlap,
                                  const Vec2& point, const Vec2& wall_velocity, int e0, int e1,
                                  Real t) {
  // A DEM contact of seed 003's wall condition, with this project's linear springs: normal
  // spring and damping from the block's restitution, friction as Coulomb-limited viscous
  // (the wall's nodes change when it is rebuilt, so no tangential spring history).
  const Real m = reducedMass(wall_mass_, B.mass(b));
  const Vec2 u = wall_velocity - B.velocityAt(b, point);  // wall relative to block
  const Real un = u.dot(n);
  const Real gamma = 2 * B.dampingRatio(b) * std::sqrt(def_.normal_stiffness * m);
  const Real fn = std::fmax(def_.normal_stiffness * overlap - gamma * un, Real(0));
  const Vec2 ut = u - un * n;
  const Real slide = ut.norm();
  const Real gamma_t = 2 * std::sqrt(def_.tangential_stiffness * m);
  const Vec2 ft =
      slide > 0 ? Vec2(-std::fmin(B.friction(b) * fn, gamma_t * slide) / slide * ut) : Vec2(0, 0);
  const Vec2 on_wall = fn * n + ft;
  if (on_wall.isZero()) return;
  // The wall's nodal forces F_P, copied to F_S (eq. 23), each with its moment about its node: the
  // nodes lie the inset inside the body's outline, and a tangential force moved there would
  // turn the body with a lever shorter by the inset (a thrown disk spun up 1.7% slower).
  const auto share = [&](int e, Real w) {
    load_[e] += w * on_wall;
    couple_[e] += cross(point - x_[e], w * on_wall);
  };
  share(e0, 1 - t);
  if (t > 0) share(e1, t);
  B.applyForce(b, -on_wall, point);
  ++active_;
}

void PartitionedCoupling::beforeStep(CouplingStep& s) {
  ContactBodies& B = s.bodies;
  const Grid& G = s.grid;
  const Particles& P = s.particles;
  if (wall_mass_ == 0 && P.size() > 0) {
    Real total = 0;
    for (Real m : P.mass) total += m;
    wall_mass_ = total / P.size();
    half_size_ = P.half_size[0];
    attach(P);
  }
  bucketSegments(G);
  std::fill(load_.begin(), load_.end(), Vec2(0, 0));
  std::fill(couple_.begin(), couple_.end(), Real(0));
  active_ = 0;
  // (1) DEM: each block against the wall segments near it. Vertex-edge pairs both ways as in
  // seed 000 eq. 39: the wall's nodes against the block's outline, and the block's core
  // vertices against the interior of the nearest segment.
  for (int b = 0; b < B.shapeCount(); ++b) {
    const Vec2* core = B.coreVertices(b);
    const int nv = B.coreVertexCount(b);
    const Real a = B.rounding(b);
    // The wall's surface lies the inset outside its segments (where the body's outline was):
    // a body rests on a block with its outline, not sunk into it by the inset.
    const Real reach = a + def_.boundary_inset;
    const Box box = B.bounds(b);
    const Real grow = def_.boundary_inset + 0.5 * longest_ + G.h;  // segments filed by middle
    const int i0 = std::max(0, static_cast<int>((box.min.x() - grow - G.origin.x()) * G.inv_h));
    const int j0 = std::max(0, static_cast<int>((box.min.y() - grow - G.origin.y()) * G.inv_h));
    const int i1 =
        std::min(cells_x_ - 1, static_cast<int>((box.max.x() + grow - G.origin.x()) * G.inv_h));
    const int j1 =
        std::min(cells_y_ - 1, static_cast<int>((box.max.y() + grow - G.origin.y()) * G.inv_h));
    struct Nearest {
      Real distance;
      int segment;
      Real t;
    };
    Nearest nearest[kMaxBlockVertices];
    for (int k = 0; k < nv; ++k) nearest[k] = {reach, -1, 0};
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const int cell = i + j * cells_x_;
        for (int q = cell_start_[cell]; q < cell_start_[cell + 1]; ++q) {
          const int sg = cell_segments_[q];
          for (int e : segments_[sg]) {  // the wall's nodes, each once per block
            if (stamp_[e] == b) continue;
            stamp_[e] = b;
            const CoreDistance d = B.closest(b, x_[e]);
            // Only within reach: a wall node inside the core got there by passing the
            // block's outline, and a spring stretched across the block would throw it out.
            if (d.distance > 0 && d.distance < reach)
              contact(B, b, d.normal, reach - d.distance,
                      d.point + (a + d.distance - def_.boundary_inset) / 2 * d.normal, v_[e], e, e,
                      0);
          }
          const Vec2 p0 = x_[segments_[sg][0]], p1 = x_[segments_[sg][1]];
          const Vec2 edge = p1 - p0;
          const Real len2 = edge.squaredNorm();
          if (!(len2 > 0)) continue;
          // Distance of a core vertex from the segment on the side away from the material; a
          // vertex behind the wall is not pulled through it.
          const Vec2 out = Vec2(edge.y(), -edge.x()) / std::sqrt(len2);
          for (int k = 0; k < nv; ++k) {
            const Real t = (core[k] - p0).dot(edge) / len2;
            if (!(t > 0 && t < 1)) continue;  // the ends are the nodes' pairs above
            const Real dist = (core[k] - p0).dot(out);
            if (dist > 0 && dist < nearest[k].distance) nearest[k] = {dist, sg, t};
          }
        }
      }
    }
    for (int k = 0; k < nv; ++k) {
      if (nearest[k].segment < 0) continue;
      const auto& sg = segments_[nearest[k].segment];
      const Real t = nearest[k].t;
      const Vec2 edge = x_[sg[1]] - x_[sg[0]];
      const Vec2 n = Vec2(-edge.y(), edge.x()) / edge.norm();  // out of the block, into the wall
      contact(B, b, n, reach - nearest[k].distance,
              core[k] + (a + nearest[k].distance - def_.boundary_inset) / 2 * n,
              v_[sg[0]] + t * (v_[sg[1]] - v_[sg[0]]), sg[0], sg[1], t);
    }
  }
  std::fill(stamp_.begin(), stamp_.end(), -1);
  load_sum_.setZero();
  for (const Vec2& f : load_) load_sum_ += f;
}

void PartitionedCoupling::addGridForces(CouplingStep& s) {
  // (2)-(3): the loads as non-conforming Neumann conditions on the grid (eq. 13-14).
  on_material_.setZero();
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    for (std::size_t e = 0; e < x_.size(); ++e) {
      if (load_[e].isZero()) continue;
      if (detail::spreadPointLoad<K>(s.grid, x_[e], half_size_, load_[e], couple_[e]))
        on_material_ += load_[e];
    }
  });
}

void PartitionedCoupling::rehost(const CouplingStep& s, std::size_t e) {
  // The affine field of a point describes the material within about a cell of it. Where the
  // flow tears, a boundary particle's offset from its host stretches with L_p without bound,
  // and the host's field extrapolated that far no longer moves it with the material next to
  // it: in the wooden-block scene a wall node 3.2 cm from its host was driven into the floor
  // at 0.3 m/s, its spring pushing the thin layer above it ever harder until the step
  // collapsed (t = 0.649 s at 0.5 cm cells). Past a cell, the nearest point within three
  // cells takes it over (none: it moves with the grid, as a body's without points).
  if (host_[e] < 0 || offset_[e].squaredNorm() <= h_ * h_) return;
  const int host = nearestPoint(s, x_[e], body_[e]);
  if (host == host_[e]) return;
  host_[e] = host;
  offset_[e] = offsetFrom(s.particles, x_[e], host);
}

void PartitionedCoupling::afterMaterialStep(CouplingStep& s) {
  // (3)-(4): the boundary particles move with the material, like massless material points:
  // with the affine velocity field of their host point, v_p + L_p (x - x_p), which is the
  // grid's field near the host to first order. Moved with the grid's velocity interpolated at
  // their own place instead, they drifted off the surface of a body that turns (on a disk of
  // 10 cells per radius, +-0.8 mm after one turn): the wall became a lumpy wheel that hopped
  // as it rolled.
  const Particles& P = s.particles;
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    for (std::size_t e = 0; e < x_.size(); ++e) {
      if (!x_[e].allFinite()) continue;  // World reports the non-finite state
      if (!host_.empty()) rehost(s, e);
      const int p = host_.empty() ? -1 : host_[e];
      if (p >= 0) {  // the offset from the host turns and stretches with L_p
        Vec2& d = offset_[e];
        d += s.dt * Vec2(P.lxx[p] * d.x() + P.lxy[p] * d.y(), P.lyx[p] * d.x() + P.lyy[p] * d.y());
        const Vec2 x = Vec2(P.x[p], P.y[p]) + d;
        v_[e] = (x - x_[e]) / s.dt;
        x_[e] = x;
      } else {
        v_[e] = detail::materialVelocityAt<K>(s.grid, x_[e], half_size_);
        x_[e] += s.dt * v_[e];
      }
      // Inside the domain, as the material points are kept.
      const Vec2 lo = s.grid.origin + Vec2::Constant(Grid::kPad * s.grid.h);
      const Vec2 hi = lo + Vec2(s.grid.cells_x, s.grid.cells_y) * s.grid.h;
      x_[e] = x_[e].cwiseMax(lo).cwiseMin(hi);
    }
  });
  // Keep the wall closed as the surface stretches: split segments longer than a cell.
  const std::size_t count = segments_.size();
  for (std::size_t k = 0; k < count; ++k) {
    const int a = segments_[k][0], b = segments_[k][1];
    if (!((x_[b] - x_[a]).norm() > h_)) continue;
    const int m = static_cast<int>(x_.size());
    x_.push_back(0.5 * (x_[a] + x_[b]));
    v_.push_back(0.5 * (v_[a] + v_[b]));
    body_.push_back(body_[a]);
    if (!host_.empty()) {
      // Its own host, the nearest point around it: with its neighbour's, a segment whose ends'
      // hosts part (a torn flow) was split again every step, each new particle following the
      // same host away from the gap (the wooden-block scene passed 0.67 GB and did not finish).
      const int host = nearestPoint(s, x_[m], body_[a]);
      host_.push_back(host);
      offset_.push_back(offsetFrom(s.particles, x_[m], host));
    }
    load_.emplace_back(0, 0);
    couple_.push_back(0);
    stamp_.push_back(-1);
    segments_[k][1] = m;
    segments_.push_back({m, b});
  }
}

std::string PartitionedCoupling::settings() const {
  char text[96];
  std::snprintf(text, sizeof text, "boundary inset %g m, k_n %g N/m", def_.boundary_inset,
                def_.normal_stiffness);
  return text;
}

void PartitionedCoupling::saveState(cereal::BinaryOutputArchive& ar) {
  stateIo(ar);
}
void PartitionedCoupling::loadState(cereal::BinaryInputArchive& ar) {
  stateIo(ar);
}

}  // namespace mpm_sdem
