#include "output.hpp"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "mpm_sdem/core/mpm/constitutive.hpp"

namespace mpm_sdem::runner {

namespace {

// A CSV file with its header line; for a resumed run, the rows of an existing file whose time
// (first column, written to 10 digits) is at most resume_after, and open for more.
std::ofstream openCsv(const std::string& path, const char* header = nullptr,
                      Real resume_after = -1) {
  std::vector<std::string> kept;
  if (resume_after >= 0) {
    std::ifstream old(path);
    std::string line;
    for (bool first = true; std::getline(old, line); first = false)
      if (!first && std::strtod(line.c_str(), nullptr) <= resume_after * (1 + 1e-9) + 1e-12)
        kept.push_back(line);
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.precision(10);
  if (header) out << header << '\n';
  for (const std::string& line : kept) out << line << '\n';
  out.flush();
  return out;
}

}  // namespace

namespace {

std::string timeSeriesHeader(const std::vector<MassGauge>& gauges) {
  std::string h =
      "time,step,dt,dt_limit,kinetic_energy,elastic_energy,gravity_energy,total_energy,"
      "momentum_x,momentum_y,angular_momentum,com_x,com_y,max_speed,max_mach";
  for (const MassGauge& g : gauges) h += "," + g.name + "_mass";
  return h;
}

}  // namespace

TimeSeriesWriter::TimeSeriesWriter(const std::string& path, const Simulation& sim,
                                   Real resume_after, std::vector<MassGauge> gauges)
    : sim_(sim),
      gauges_(std::move(gauges)),
      out_(openCsv(path, timeSeriesHeader(gauges_).c_str(), resume_after)) {}

void TimeSeriesWriter::sample(const World& w, const Diagnostics& d) {
  const TimeStepChoice& dt = sim_.stableStep();
  out_ << w.time() << ',' << w.stepCount() << ',' << dt.dt << ',' << stepLimitName(dt.limit) << ','
       << d.kinetic << ',' << d.elastic << ',' << d.gravity << ',' << d.total() << ','
       << d.momentum.x() << ',' << d.momentum.y() << ',' << d.angular_momentum << ','
       << d.center_of_mass.x() << ',' << d.center_of_mass.y() << ',' << d.max_speed << ','
       << d.max_mach;
  for (const MassGauge& g : gauges_) out_ << ',' << gaugeMass(w.particles(), g);
  out_ << '\n';
  out_.flush();
}

BlockSeriesWriter::BlockSeriesWriter(const std::string& path, Real resume_after)
    : out_(openCsv(path,
                   "time,block,name,x,y,angle,vx,vy,angular_velocity,coupling_force_x,"
                   "coupling_force_y,coupling_torque,contacts,block_force_x,block_force_y,"
                   "block_torque,block_contacts,min_x,max_x,min_y,max_y",
                   resume_after)) {}

void BlockSeriesWriter::sample(const World& w, const Diagnostics&) {
  const Blocks& B = *w.blocks();
  for (int b = 0; b < B.count(); ++b) {
    const BlockState& s = B.state(b);
    const Blocks::Load& c = B.coupling()[b];    // from the material
    const Blocks::Load& k = B.blockContact(b);  // from the other blocks
    Box box = B.bounds(B.firstShape(b));
    for (int sh = B.firstShape(b) + 1; sh < B.firstShape(b) + B.shapesOf(b); ++sh) {
      box.min = box.min.cwiseMin(B.bounds(sh).min);
      box.max = box.max.cwiseMax(B.bounds(sh).max);
    }
    out_ << w.time() << ',' << b << ',' << B.def(b).name << ',' << s.position.x() << ','
         << s.position.y() << ',' << s.angle << ',' << s.velocity.x() << ',' << s.velocity.y()
         << ',' << s.angular_velocity << ',' << c.force.x() << ',' << c.force.y() << ',' << c.torque
         << ',' << c.contacts << ',' << k.force.x() << ',' << k.force.y() << ',' << k.torque << ','
         << k.contacts << ',' << box.min.x() << ',' << box.max.x() << ',' << box.min.y() << ','
         << box.max.y() << '\n';
  }
  out_.flush();
}

FemSeriesWriter::FemSeriesWriter(const std::string& nodes_path, const std::string& elements_path,
                                 Real resume_after)
    : nodes_(openCsv(nodes_path, "time,body,name,node,x,y,ux,uy,vx,vy,held", resume_after)),
      elements_(openCsv(elements_path, "time,body,name,element,sxx,syy,sxy,szz,von_mises",
                        resume_after)) {}

void FemSeriesWriter::sample(const World& w, const Diagnostics&) {
  const FemBodies& F = *w.femBodies();
  for (int b = 0; b < F.count(); ++b) {
    const std::string& name = F.def(b).name;
    for (int k = F.firstNode(b); k < F.firstNode(b) + F.nodeCount(b); ++k) {
      const Vec2 x = F.position(k), u = x - F.reference(k), v = F.velocity(k);
      nodes_ << w.time() << ',' << b << ',' << name << ',' << k - F.firstNode(b) << ',' << x.x()
             << ',' << x.y() << ',' << u.x() << ',' << u.y() << ',' << v.x() << ',' << v.y() << ','
             << (F.held(k) ? 1 : 0) << '\n';
    }
    for (int e = F.firstElement(b); e < F.firstElement(b) + F.elementCount(b); ++e) {
      const FemBodies::Stress& s = F.stress(e);
      elements_ << w.time() << ',' << b << ',' << name << ',' << e - F.firstElement(b) << ','
                << s.xx << ',' << s.yy << ',' << s.xy << ',' << s.zz << ','
                << FemBodies::vonMises(s) << '\n';
    }
  }
  nodes_.flush();
  elements_.flush();
}

void writeParticles(const World& world, const std::string& path) {
  std::ofstream out = openCsv(path);
  const Particles& P = world.particles();
  out << "id,body,material,kind,x,y,vx,vy,mass,volume,sxx,syy,sxy,szz,pressure\n";
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Stress s{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]};
    out << p << ',' << P.body[p] << ',' << P.material[p] << ',' << int{P.kind[p]} << ',' << P.x[p]
        << ',' << P.y[p] << ',' << P.vx[p] << ',' << P.vy[p] << ',' << P.mass[p] << ','
        << P.volume0[p] * P.J[p] << ',' << s.xx << ',' << s.yy << ',' << s.xy << ',' << s.zz << ','
        << pressure(s) << '\n';
  }
}

void writeProfile(const World& world, const std::string& path) {
  std::ofstream out = openCsv(path);
  const Profile& prof = world.profile();
  out << "stage,seconds,seconds_per_step,fraction\n";
  const double total = prof.total();
  for (const Stage stage : prof.usedStages()) {
    const double s = prof.seconds[static_cast<int>(stage)];
    out << stageName(stage) << ',' << s << ',' << (prof.steps ? s / prof.steps : 0) << ','
        << (total > 0 ? s / total : 0) << '\n';
  }
}

void writeSummary(const World& world, int status, double wall_seconds, const std::string& path) {
  std::ofstream out = openCsv(path);
  out << "status,time,steps,points,wall_s\n"
      << status << ',' << world.time() << ',' << world.stepCount() << ','
      << world.particles().size() << ',' << wall_seconds << '\n';
}

}  // namespace mpm_sdem::runner
