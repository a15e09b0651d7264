#include "mpm_sdem/core/coupling/contact_set.hpp"

#include <algorithm>
#include <limits>

namespace mpm_sdem {

ContactSet::ContactSet(std::vector<ContactBodies*> members) : members_(std::move(members)) {
  refresh();
}

void ContactSet::refresh() {
  first_.assign(1, 0);
  first_body_.clear();
  int bodies = 0;
  for (const ContactBodies* m : members_) {
    first_body_.push_back(bodies);
    // Bodies are numbered by their shapes' bodyOf, consecutively from 0.
    int most = -1;
    for (int s = 0; s < m->shapeCount(); ++s) most = std::max(most, m->bodyOf(s));
    bodies += most + 1;
    first_.push_back(first_.back() + m->shapeCount());
  }
}

int ContactSet::bodyOf(int s) const {
  const int m = member(s);
  return first_body_[m] + members_[m]->bodyOf(s - first_[m]);
}

Real ContactSet::lightestMass() const {
  Real m = std::numeric_limits<Real>::infinity();
  for (const ContactBodies* b : members_) m = std::min(m, b->lightestMass());
  return m;
}

Real ContactSet::maxDampingRatio() const {
  Real z = 0;
  for (const ContactBodies* b : members_) z = std::max(z, b->maxDampingRatio());
  return z;
}

void ContactSet::beginCoupling(Real dt) {
  for (ContactBodies* b : members_) b->beginCoupling(dt);
}

Real ContactSet::stableStep(Real kappa2) const {
  Real dt = std::numeric_limits<Real>::infinity();
  for (const ContactBodies* b : members_) dt = std::min(dt, b->stableStep(kappa2));
  return dt;
}

int ContactSet::step(Real dt, Real max_substep) {
  int substeps = 0;
  for (ContactBodies* b : members_) substeps = std::max(substeps, b->step(dt, max_substep));
  return substeps;
}

int ContactSet::substep(Real h, Real max_substep, Real share) {
  int substeps = 0;
  for (ContactBodies* b : members_)
    substeps = std::max(substeps, b->substep(h, max_substep, share));
  return substeps;
}

}  // namespace mpm_sdem
