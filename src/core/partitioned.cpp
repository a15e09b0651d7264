#include "mpm_sdem/core/partitioned.hpp"

#include <algorithm>
#include <cmath>

#include "transfer.hpp"

namespace mpm_sdem {

PartitionedCoupling::PartitionedCoupling(const CouplingDef& def, Real cell_size)
    : Coupling(def), h_(cell_size) {}

void PartitionedCoupling::rebuild(const CouplingStep& s) {
  const Particles& P = s.particles;
  const Grid& G = s.grid;
  const std::size_t nodes = static_cast<std::size_t>(G.nx) * G.ny;
  volume_.assign(nodes, 0);
  mass_.assign(nodes, 0);
  mom_x_.assign(nodes, 0);
  mom_y_.assign(nodes, 0);
  Real level = 0.5;
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    constexpr int S = K::kSupport;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (!std::isfinite(P.x[p]) || !std::isfinite(P.y[p])) continue;  // World reports it
      Real xg, yg;
      Stencil1D sx, sy;
      detail::stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
      const Real vol = P.volume0[p] * P.J[p];
      for (int j = 0; j < S; ++j) {
        for (int i = 0; i < S; ++i) {
          const int q = G.index(sx.base + i, sy.base + j);
          const Real w = sx.w[i] * sy.w[j];
          volume_[q] += w * vol;
          mass_[q] += w * P.mass[p];
          mom_x_[q] += w * P.mass[p] * P.vx[p];
          mom_y_[q] += w * P.mass[p] * P.vy[p];
        }
      }
    }
    half_size_ = P.size() > 0 ? P.half_size[0] : Real(0.25);
    Stencil1D at_node;
    K::stencil(Real(8), half_size_, at_node);  // the weight of the node under the point
    const Real s0 = at_node.w[8 - at_node.base];
    level = std::min<Real>(0.5 + s0 * def_.boundary_inset / h_, 0.9);
  });
  Real total = 0;
  for (Real m : P.mass) total += m;
  wall_mass_ = P.size() > 0 ? total / P.size() : 0;

  // Marching squares on the volume fraction: a crossing point on every grid edge whose ends are
  // on either side of the level, joined into segments cell by cell.
  const Real inv_area = G.inv_h * G.inv_h;
  auto inside = [&](int q) { return volume_[q] * inv_area >= level; };
  edge_point_.assign(2 * nodes, -1);
  x_.clear();
  v_.clear();
  segments_.clear();
  auto point = [&](int q0, int q1, int edge) {
    if (edge_point_[edge] >= 0) return edge_point_[edge];
    const Real f0 = volume_[q0] * inv_area, f1 = volume_[q1] * inv_area;
    const Real t = (level - f0) / (f1 - f0);
    const Vec2 x0 = G.origin + Vec2(q0 % G.nx, q0 / G.nx) * G.h;
    const Vec2 x1 = G.origin + Vec2(q1 % G.nx, q1 / G.nx) * G.h;
    auto vel = [&](int q) {
      return mass_[q] > 0 ? Vec2(mom_x_[q] / mass_[q], mom_y_[q] / mass_[q]) : Vec2(0, 0);
    };
    edge_point_[edge] = static_cast<int>(x_.size());
    x_.push_back(x0 + t * (x1 - x0));
    v_.push_back(vel(q0) + t * (vel(q1) - vel(q0)));
    return edge_point_[edge];
  };
  cells_x_ = G.nx - 1;
  cells_y_ = G.ny - 1;
  cell_start_.assign(static_cast<std::size_t>(cells_x_) * cells_y_ + 1, 0);
  for (int j = 0; j < cells_y_; ++j) {
    for (int i = 0; i < cells_x_; ++i) {
      const int a = G.index(i, j), b = G.index(i + 1, j), c = G.index(i + 1, j + 1),
                d = G.index(i, j + 1);
      const int bits = inside(a) | inside(b) << 1 | inside(c) << 2 | inside(d) << 3;
      const int cell = i + j * cells_x_;
      cell_start_[cell + 1] = cell_start_[cell];
      if (bits == 0 || bits == 15) continue;
      // Edges: 0 bottom (a-b), 1 right (b-c), 2 top (d-c), 3 left (a-d).
      auto e = [&](int which) {
        switch (which) {
          case 0:
            return point(a, b, 2 * a);
          case 1:
            return point(b, c, 2 * b + 1);
          case 2:
            return point(d, c, 2 * d);
          default:
            return point(a, d, 2 * a + 1);
        }
      };
      // Each segment with the material on its left, so that its right normal points out.
      const Vec2 corner = G.origin + Vec2(i, j) * G.h;
      Vec2 inner(0, 0);
      int n_in = 0;
      const int quad[4][3] = {{a, 0, 0}, {b, 1, 0}, {c, 1, 1}, {d, 0, 1}};
      for (const auto& q : quad) {
        if (!inside(q[0])) continue;
        inner += corner + Vec2(q[1], q[2]) * G.h;
        ++n_in;
      }
      inner /= n_in;
      auto join = [&](int e0, int e1) {
        int p0 = e(e0), p1 = e(e1);
        const Vec2 edge = x_[p1] - x_[p0];
        const Vec2 to_inner = inner - x_[p0];
        if (edge.x() * to_inner.y() - edge.y() * to_inner.x() < 0) std::swap(p0, p1);
        segments_.push_back({p0, p1});
        ++cell_start_[cell + 1];
      };
      const bool centre =
          (volume_[a] + volume_[b] + volume_[c] + volume_[d]) * inv_area / 4 >= level;
      switch (bits) {
        case 1:
        case 14:
          join(3, 0);
          break;
        case 2:
        case 13:
          join(0, 1);
          break;
        case 3:
        case 12:
          join(3, 1);
          break;
        case 4:
        case 11:
          join(1, 2);
          break;
        case 6:
        case 9:
          join(0, 2);
          break;
        case 7:
        case 8:
          join(3, 2);
          break;
        case 5:  // saddle: a and c inside
          if (centre) {
            join(0, 1);
            join(2, 3);
          } else {
            join(3, 0);
            join(1, 2);
          }
          break;
        case 10:  // saddle: b and d inside
          if (centre) {
            join(3, 0);
            join(1, 2);
          } else {
            join(0, 1);
            join(2, 3);
          }
          break;
        default:
          break;
      }
    }
  }
  load_.assign(x_.size(), Vec2(0, 0));
  stamp_.assign(x_.size(), -1);
  x_built_ = x_;
  drift_ = 0;
  since_rebuild_ = 0;
}

void PartitionedCoupling::contact(Blocks& B, int b, const Vec2& n, Real overlap, const Vec2& point,
                                  const Vec2& wall_velocity, int e0, int e1, Real t) {
  // A DEM contact of seed 003's wall condition, with this project's linear springs: normal
  // spring and damping from the block's restitution, friction as Coulomb-limited viscous
  // (the wall's nodes change when it is rebuilt, so no tangential spring history).
  const BlockDef& bd = B.def(b);
  const Real M = bd.type == BodyType::kDynamic ? B.massProperties(b).mass : 0;
  const Real m = M > 0 ? M * wall_mass_ / (M + wall_mass_) : wall_mass_;
  const Vec2 u = wall_velocity - B.velocityAt(b, point);  // wall relative to block
  const Real un = u.dot(n);
  const Real gamma = 2 * B.dampingRatio(b) * std::sqrt(def_.normal_stiffness * m);
  const Real fn = std::fmax(def_.normal_stiffness * overlap - gamma * un, Real(0));
  const Vec2 ut = u - un * n;
  const Real slide = ut.norm();
  const Real gamma_t = 2 * std::sqrt(def_.tangential_stiffness * m);
  const Vec2 ft =
      slide > 0 ? Vec2(-std::fmin(bd.friction * fn, gamma_t * slide) / slide * ut) : Vec2(0, 0);
  const Vec2 on_wall = fn * n + ft;
  if (on_wall.isZero()) return;
  load_[e0] += (1 - t) * on_wall;  // the wall's nodal forces F_P, copied to F_S (eq. 23)
  if (t > 0) load_[e1] += t * on_wall;
  B.addMaterialForce(b, -on_wall, point);
  ++active_;
}

void PartitionedCoupling::beforeStep(CouplingStep& s) {
  if (since_rebuild_ < 0 || since_rebuild_ >= def_.boundary_interval) rebuild(s);
  Blocks& B = s.blocks;
  const Grid& G = s.grid;
  B.clearCoupling();
  std::fill(load_.begin(), load_.end(), Vec2(0, 0));
  active_ = 0;
  // (1) DEM: each block against the wall segments near it. Vertex-edge pairs both ways as in
  // seed 000 eq. 39: the wall's nodes against the block's outline, and the block's core
  // vertices against the interior of the nearest segment.
  for (int b = 0; b < B.count(); ++b) {
    const Vec2* core = B.vertices(b);
    const int nv = B.vertexCount(b);
    const Real a = B.def(b).rounding;
    Vec2 lo = core[0], hi = core[0];
    for (int k = 1; k < nv; ++k) {
      lo = lo.cwiseMin(core[k]);
      hi = hi.cwiseMax(core[k]);
    }
    const Real grow = a + drift_ + G.h;
    const int i0 = std::max(0, static_cast<int>((lo.x() - grow - G.origin.x()) * G.inv_h));
    const int j0 = std::max(0, static_cast<int>((lo.y() - grow - G.origin.y()) * G.inv_h));
    const int i1 =
        std::min(cells_x_ - 1, static_cast<int>((hi.x() + grow - G.origin.x()) * G.inv_h));
    const int j1 =
        std::min(cells_y_ - 1, static_cast<int>((hi.y() + grow - G.origin.y()) * G.inv_h));
    struct Nearest {
      Real distance;
      int segment;
      Real t;
    };
    Nearest nearest[kMaxBlockVertices];
    for (int k = 0; k < nv; ++k) nearest[k] = {a, -1, 0};
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const int cell = i + j * cells_x_;
        for (int sg = cell_start_[cell]; sg < cell_start_[cell + 1]; ++sg) {
          for (int e : segments_[sg]) {  // the wall's nodes, each once per block
            if (stamp_[e] == b) continue;
            stamp_[e] = b;
            const CoreDistance d = closestOnCore(core, nv, x_[e]);
            // Only within the rounding: a wall node inside the core came from material that
            // passed the wall between two contour updates (a lone point has no contour), and
            // a spring stretched across the block would throw it out.
            if (d.distance > 0 && d.distance < a)
              contact(B, b, d.normal, a - d.distance, d.point + (a + d.distance) / 2 * d.normal,
                      v_[e], e, e, 0);
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
      contact(B, b, n, a - nearest[k].distance, core[k] + (a + nearest[k].distance) / 2 * n,
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
      if (detail::spreadPointLoad<K>(s.grid, x_[e], half_size_, load_[e])) on_material_ += load_[e];
    }
  });
}

void PartitionedCoupling::afterMaterialStep(CouplingStep& s) {
  // (3)-(4): the boundary particles move with the material, like massless material points.
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    for (std::size_t e = 0; e < x_.size(); ++e) {
      if (!x_[e].allFinite()) continue;
      v_[e] = detail::gridVelocityAt<K>(s.grid, x_[e], half_size_);
      x_[e] += s.dt * v_[e];
      drift_ = std::max(drift_, (x_[e] - x_built_[e]).norm());
    }
  });
  ++since_rebuild_;
}

}  // namespace mpm_sdem
