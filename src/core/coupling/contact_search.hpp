// Global and local search for material point - body pairs (seed 002 sec. 3.1, seed 000 sec.
// 4.1): the points are bucket-sorted by cell, each body scans the cells under its outline grown
// by a reach, and the pairs are kept until a point or body moves half the Verlet distance.
#pragma once

#include <cstdint>
#include <vector>

#include "mpm_sdem/core/coupling/contact_bodies.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

// A material point near a contact shape. The pairs of one point with the shapes of one body
// come together (a cluster's discs near the point); the first of them carries the contact
// (forEachContact).
struct ContactPair {
  int particle = 0;
  int shape = 0;               // numbered as ContactBodies numbers them now
  int body = 0;                // ContactBodies::bodyOf(shape)
  std::uint64_t body_key = 0;  // ContactBodies::bodyKey(shape)
  Vec2 history{0, 0};          // accumulated tangential sliding (m), spring schemes
  Vec2 force{0, 0};            // on the particle (N/m) in the last step; zero when not touching
  Vec2 point{0, 0};            // contact point (m) in the last step
  template <class Archive>
  void serialize(Archive& ar) {
    ar(particle, shape, body, body_key, history, force, point);
  }
};

class ContactSearch {
 public:
  // reach (m): how far outside a body's rounded outline a point becomes a pair, on top of the
  // Verlet distance.
  void init(const Vec2& domain_min, const Vec2& domain_max, Real cell_size, Real reach,
            Real verlet_distance);
  // Rebuilds the pairs when anything moved more than half the Verlet distance. Pairs come
  // sorted by (body, particle, shape); a point's contact with a body that survives a rebuild
  // keeps its history, also across a renumbering of the bodies (matched by body key).
  void update(const Particles& P, const ContactBodies& B);
  // f(ContactPair& c, int shape, const CoreDistance& d) once for each point and body near it:
  // c is the first of their pairs (it carries the contact: history, force, point; the others'
  // forces are cleared), shape the deepest of the body's shapes near the point (the body's
  // outline there is their union) and d its closest point to the point.
  template <class F>
  void forEachContact(const Particles& P, const ContactBodies& B, F&& f);
  // The same with the points at where(group, particle) instead, and f(group, c, shape, d):
  // group numbers the calls from 0 (the same numbering while the pairs are not rebuilt). A
  // group for which skip(group) is true is passed over before any distance is computed.
  template <class X, class F, class Skip>
  void forEachContactAt(const ContactBodies& B, X&& where, F&& f, Skip&& skip);
  // Rebuild at the next update (the bodies or the points changed).
  void invalidate() { built_ = false; }

  std::vector<ContactPair>& pairs() { return pairs_; }
  const std::vector<ContactPair>& pairs() const { return pairs_; }
  long rebuilds() const { return rebuilds_; }
  // The checkpoint state of its owner's: the pairs and where things stood at the last rebuild
  // (the buckets are rebuilt with them).
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(x_built_, y_built_, bodies_built_, pairs_, rebuilds_, built_);
  }

 private:
  bool needsRebuild(const Particles& P, const ContactBodies& B) const;
  void rebuild(const Particles& P, const ContactBodies& B);

  Vec2 lo_{0, 0};
  Real bucket_ = 1, reach_ = 0, verlet_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_, cell_items_, cell_of_;
  std::vector<Real> x_built_, y_built_;
  std::vector<BodyPose> bodies_built_;
  std::vector<ContactPair> pairs_, previous_;
  long rebuilds_ = 0;
  bool built_ = false;
};

template <class F>
void ContactSearch::forEachContact(const Particles& P, const ContactBodies& B, F&& f) {
  forEachContactAt(
      B, [&P](int, int p) { return Vec2(P.x[p], P.y[p]); },
      [&f](int, ContactPair& c, int shape, const CoreDistance& d) { f(c, shape, d); },
      [](int) { return false; });
}

template <class X, class F, class Skip>
void ContactSearch::forEachContactAt(const ContactBodies& B, X&& where, F&& f, Skip&& skip) {
  int group = 0;
  for (std::size_t g = 0; g < pairs_.size(); ++group) {
    ContactPair& c = pairs_[g];
    if (skip(group)) {
      for (++g; g < pairs_.size() && pairs_[g].body == c.body && pairs_[g].particle == c.particle;
           ++g) {
      }
      continue;
    }
    const Vec2 x = where(group, c.particle);
    int shape = c.shape;
    CoreDistance d = B.closest(shape, x);
    std::size_t end = g + 1;
    for (; end < pairs_.size() && pairs_[end].body == c.body && pairs_[end].particle == c.particle;
         ++end) {
      const int other = pairs_[end].shape;
      const CoreDistance e = B.closest(other, x);
      if (e.distance - B.rounding(other) < d.distance - B.rounding(shape)) {
        shape = other;
        d = e;
      }
      pairs_[end].force.setZero();
    }
    f(group, c, shape, d);
    g = end;
  }
}

}  // namespace mpm_sdem
