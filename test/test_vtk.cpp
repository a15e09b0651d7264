// ParaView files (mpm_sdem/vtk/vtk_series.hpp) read back with VTK's own readers: a world of sand,
// a tilted spheropolygon box resting on it, a disc cluster falling onto the box and an FEM
// barrier, written three times; every array against the world it came from, the outlines against
// the blocks' rounded outlines, and the .pvd collections (parsed with vtkXMLDataParser: VTK 9.1
// reads collections only inside ParaView) against the frames' times. Then the runner's
// --vtk-every schedule and its refusals.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "helpers.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "mpm_sdem/vtk/vtk_series.hpp"

using namespace mpm_sdem;
namespace fs = std::filesystem;

namespace {

// test/data/valid_fem.yaml (sand and an FEM barrier) with the sand a bed 25 x 4 cm (400
// points), a box tilted by 0.05 rad 0.3 mm above the bed and a cluster of three discs 0.3 mm
// above the box: from 34 ms on the box rests on the sand and the cluster on the box (measured:
// both loads non-zero at every 2 ms to 58 ms), so the last frame's loads are not zeros.
World makeWorld() {
  Scene s =
      loadScene(test::sourcePath("test/data/valid_fem.yaml"), {"bodies.column.max=[0.25, 0.04]"});
  BlockDef box;
  box.name = "box";
  box.core = {{-0.02, -0.008}, {0.02, -0.008}, {0.02, 0.008}, {-0.02, 0.008}};
  box.rounding = 0.002;
  box.angle = 0.05;
  box.position = Vec2(0.1, 0.04 + 0.008 * std::cos(0.05) + 0.02 * std::sin(0.05) + 0.002 + 3e-4);
  box.density = 500;
  BlockDef cluster;
  cluster.name = "cluster";
  cluster.discs = {{{0, 0}, 0.005}, {{0.008, 0}, 0.005}, {{0.004, 0.007}, 0.005}};
  cluster.position = Vec2(0.095, box.position.y() + 0.0102 + 0.005 + 3e-4);
  cluster.density = 500;
  cluster.restitution = 0.05;  // it stays on the box once landed
  s.world.blocks = {box, cluster};
  return World(s.world);
}

vtkSmartPointer<vtkUnstructuredGrid> readGrid(const fs::path& file) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

// A .pvd's frames: (time, file) in order.
std::vector<std::pair<double, std::string>> readCollection(const fs::path& pvd) {
  std::vector<std::pair<double, std::string>> out;
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(pvd.c_str());
  if (!parser->Parse()) return out;
  vtkXMLDataElement* root = parser->GetRootElement();
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* list = root->FindNestedElementWithName("Collection");
  if (!list) return out;
  for (int i = 0; i < list->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = list->GetNestedElement(i);
    double t = NAN;
    EXPECT_TRUE(e->GetScalarAttribute("timestep", t));
    out.emplace_back(t, e->GetAttribute("file"));
  }
  return out;
}

vtkDataArray* array(vtkFieldData* data, const char* name, int components) {
  vtkDataArray* a = data->GetArray(name);
  EXPECT_NE(a, nullptr) << name;
  if (a) {
    EXPECT_EQ(a->GetNumberOfComponents(), components) << name;
  }
  return a;
}

double timeValue(vtkUnstructuredGrid* g) {
  vtkDataArray* t = g->GetFieldData()->GetArray("TimeValue");
  return t ? t->GetComponent(0, 0) : NAN;
}

// Every point in single precision, as written: positions, velocities, and pressure and von Mises
// equal to the core's functions of the same stress.
void expectPoints(vtkUnstructuredGrid* g, const World& w) {
  const Particles& P = w.particles();
  const vtkIdType n = static_cast<vtkIdType>(P.size());
  ASSERT_EQ(g->GetNumberOfPoints(), n);
  ASSERT_EQ(g->GetNumberOfCells(), n);
  EXPECT_EQ(timeValue(g), w.time());
  vtkPointData* pd = g->GetPointData();
  vtkDataArray *velocity = array(pd, "velocity", 3), *speed = array(pd, "speed", 1),
               *stress = array(pd, "stress", 6), *pressures = array(pd, "pressure", 1),
               *von_mises = array(pd, "von_mises", 1), *material = array(pd, "material", 1),
               *kind = array(pd, "kind", 1), *mass = array(pd, "mass", 1), *J = array(pd, "J", 1);
  ASSERT_FALSE(!velocity || !speed || !stress || !pressures || !von_mises || !material || !kind ||
               !mass || !J);
  auto f = [](double v) { return static_cast<float>(v); };
  for (vtkIdType p = 0; p < n; ++p) {
    double x[3];
    g->GetPoint(p, x);
    ASSERT_EQ(f(x[0]), f(P.x[p])) << p;
    ASSERT_EQ(f(x[1]), f(P.y[p])) << p;
    ASSERT_EQ(x[2], 0);
    ASSERT_EQ(f(velocity->GetComponent(p, 0)), f(P.vx[p])) << p;
    ASSERT_EQ(f(velocity->GetComponent(p, 1)), f(P.vy[p])) << p;
    ASSERT_EQ(f(speed->GetComponent(p, 0)), f(std::hypot(P.vx[p], P.vy[p]))) << p;
    const Stress s{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]};
    ASSERT_EQ(f(pressures->GetComponent(p, 0)), f(pressure(s))) << p;
    ASSERT_EQ(f(von_mises->GetComponent(p, 0)), f(vonMises(s))) << p;
    ASSERT_EQ(f(stress->GetComponent(p, 2)), f(s.zz)) << p;  // ZZ, third in VTK's order
    ASSERT_EQ(f(stress->GetComponent(p, 3)), f(s.xy)) << p;
    ASSERT_EQ(material->GetComponent(p, 0), P.material[p]);
    ASSERT_EQ(kind->GetComponent(p, 0), P.kind[p]);
    ASSERT_EQ(f(mass->GetComponent(p, 0)), f(P.mass[p]));
    ASSERT_EQ(f(J->GetComponent(p, 0)), f(P.J[p]));
  }
  for (const vtkIdType p : {vtkIdType{0}, n / 2, n - 1}) {
    EXPECT_EQ(g->GetCellType(p), VTK_VERTEX);
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    g->GetCellPoints(p, count, ids);
    ASSERT_EQ(count, 1);
    EXPECT_EQ(ids[0], p);
  }
}

// How far a chord of an arc of radius a spanning `angle` cuts inside it.
Real sagitta(Real a, Real angle) {
  return a * (1 - std::cos(angle / 2));
}

// The largest angle one chord spans on this part's outline: a disc has 4 kCornerChords chords,
// a capsule's ends turn by pi, a polygon's corners by their exterior angles.
Real chordAngle(const std::vector<Vec2>& core) {
  const int n = static_cast<int>(core.size());
  if (n == 1) return 2 * M_PI / (4 * kCornerChords);
  if (n == 2) return M_PI / kCornerChords;
  Real turn = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2 e_in = core[i] - core[(i + n - 1) % n], e_out = core[(i + 1) % n] - core[i];
    turn = std::max(turn, std::atan2(cross(e_in, e_out), e_in.dot(e_out)));
  }
  return turn / kCornerChords;
}

// Each polygon follows its part's rounded outline: its vertices at the rounding from the core,
// its chords inside by at most their sagitta (reached at the arcs' chords' midpoints), counter-
// clockwise; its cell data are the block's state and loads.
void expectBlocks(vtkUnstructuredGrid* g, const World& w, bool loaded) {
  const Blocks& B = *w.blocks();
  vtkIdType parts = 0;
  for (int i = 0; i < B.count(); ++i) parts += static_cast<vtkIdType>(B.parts(i).size());
  ASSERT_EQ(g->GetNumberOfCells(), parts);
  EXPECT_EQ(timeValue(g), w.time());
  auto* names = vtkStringArray::SafeDownCast(g->GetFieldData()->GetAbstractArray("block_names"));
  ASSERT_NE(names, nullptr);
  ASSERT_EQ(names->GetNumberOfValues(), B.count());
  for (int i = 0; i < B.count(); ++i) EXPECT_EQ(names->GetValue(i), B.def(i).name);
  vtkCellData* cd = g->GetCellData();
  vtkDataArray *block = array(cd, "block", 1), *part = array(cd, "part", 1),
               *type = array(cd, "type", 1), *position = array(cd, "position", 3),
               *angle = array(cd, "angle", 1), *velocity = array(cd, "velocity", 3),
               *angular_velocity = array(cd, "angular_velocity", 1),
               *coupling_force = array(cd, "coupling_force", 3),
               *coupling_torque = array(cd, "coupling_torque", 1),
               *coupling_contacts = array(cd, "coupling_contacts", 1),
               *block_force = array(cd, "block_force", 3),
               *block_torque = array(cd, "block_torque", 1),
               *block_contacts = array(cd, "block_contacts", 1);
  ASSERT_FALSE(!block || !part || !type || !position || !angle || !velocity || !angular_velocity ||
               !coupling_force || !coupling_torque || !coupling_contacts || !block_force ||
               !block_torque || !block_contacts);
  bool material_load = false, block_load = false;
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    const int i = static_cast<int>(block->GetComponent(c, 0));
    const int j = static_cast<int>(part->GetComponent(c, 0));
    ASSERT_TRUE(i >= 0 && i < B.count() && j >= 0 && j < static_cast<int>(B.parts(i).size()));
    const Spheropolygon sp = B.currentParts(i)[j];
    const int n = static_cast<int>(sp.core.size());
    const Real a = sp.rounding;
    EXPECT_EQ(g->GetCellType(c), VTK_POLYGON);
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    g->GetCellPoints(c, count, ids);
    ASSERT_EQ(count, n == 1 ? 4 * kCornerChords : n * (kCornerChords + 1)) << B.def(i).name;
    const Real chord_error = sagitta(a, chordAngle(sp.core));
    Real deepest = 0, area = 0;
    for (vtkIdType k = 0; k < count; ++k) {
      double p[3], q[3];
      g->GetPoint(ids[k], p);
      g->GetPoint(ids[(k + 1) % count], q);
      const Vec2 u(p[0], p[1]), v(q[0], q[1]);
      EXPECT_NEAR(closestOnCore(sp.core.data(), n, u).distance, a, 1e-12) << B.def(i).name;
      const Real mid = closestOnCore(sp.core.data(), n, 0.5 * (u + v)).distance;
      EXPECT_LE(mid, a + 1e-12);
      EXPECT_GE(mid, a - chord_error - 1e-12);
      deepest = std::max(deepest, a - mid);
      area += 0.5 * cross(u, v);
    }
    EXPECT_NEAR(deepest, chord_error, 1e-12) << B.def(i).name;
    EXPECT_GT(area, 0) << "clockwise outline of " << B.def(i).name;
    const BlockState& s = B.state(i);
    const Blocks::Load& m = B.coupling()[i];
    const Blocks::Load& o = B.blockContact(i);
    EXPECT_EQ(type->GetComponent(c, 0), static_cast<int>(B.def(i).type));
    EXPECT_EQ(position->GetComponent(c, 0), s.position.x());
    EXPECT_EQ(position->GetComponent(c, 1), s.position.y());
    EXPECT_EQ(angle->GetComponent(c, 0), s.angle);
    EXPECT_EQ(velocity->GetComponent(c, 0), s.velocity.x());
    EXPECT_EQ(velocity->GetComponent(c, 1), s.velocity.y());
    EXPECT_EQ(angular_velocity->GetComponent(c, 0), s.angular_velocity);
    EXPECT_EQ(coupling_force->GetComponent(c, 0), m.force.x());
    EXPECT_EQ(coupling_force->GetComponent(c, 1), m.force.y());
    EXPECT_EQ(coupling_force->GetComponent(c, 2), 0);
    EXPECT_EQ(coupling_torque->GetComponent(c, 0), m.torque);
    EXPECT_EQ(coupling_contacts->GetComponent(c, 0), m.contacts);
    EXPECT_EQ(block_force->GetComponent(c, 0), o.force.x());
    EXPECT_EQ(block_force->GetComponent(c, 1), o.force.y());
    EXPECT_EQ(block_torque->GetComponent(c, 0), o.torque);
    EXPECT_EQ(block_contacts->GetComponent(c, 0), o.contacts);
    material_load = material_load || coupling_force->GetComponent(c, 1) != 0;
    block_load = block_load || block_force->GetComponent(c, 1) != 0;
  }
  if (loaded) {
    EXPECT_TRUE(material_load) << "no block carries the material: the comparison proves little";
    EXPECT_TRUE(block_load) << "no block carries another";
  }
}

void expectFem(vtkUnstructuredGrid* g, const World& w) {
  const FemBodies& F = *w.femBodies();
  ASSERT_EQ(F.count(), 1);
  ASSERT_EQ(g->GetNumberOfPoints(), static_cast<vtkIdType>(F.def(0).mesh.nodes.size()));
  ASSERT_EQ(g->GetNumberOfCells(), static_cast<vtkIdType>(F.def(0).mesh.triangles.size()));
  EXPECT_EQ(timeValue(g), w.time());
  vtkPointData* pd = g->GetPointData();
  vtkCellData* cd = g->GetCellData();
  vtkDataArray *displacement = array(pd, "displacement", 3), *velocity = array(pd, "velocity", 3),
               *held = array(pd, "held", 1), *von_mises = array(cd, "von_mises", 1),
               *stress = array(cd, "stress", 6), *body = array(cd, "body", 1);
  ASSERT_FALSE(!displacement || !velocity || !held || !von_mises || !stress || !body);
  for (int k = 0; k < F.totalNodes(); ++k) {
    double x[3];
    g->GetPoint(k, x);
    const Vec2 u = F.position(k) - F.reference(k);
    EXPECT_EQ(x[0], F.position(k).x());
    EXPECT_EQ(x[1], F.position(k).y());
    EXPECT_EQ(displacement->GetComponent(k, 0), u.x());
    EXPECT_EQ(displacement->GetComponent(k, 1), u.y());
    EXPECT_EQ(velocity->GetComponent(k, 1), F.velocity(k).y());
    EXPECT_EQ(held->GetComponent(k, 0), F.held(k) ? 1 : 0);
  }
  bool stressed = false;
  for (int e = 0; e < F.totalElements(); ++e) {
    EXPECT_EQ(g->GetCellType(e), VTK_TRIANGLE);
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    g->GetCellPoints(e, count, ids);
    ASSERT_EQ(count, 3);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(ids[j], F.elementNodes(e)[j]);
    EXPECT_EQ(von_mises->GetComponent(e, 0), FemBodies::vonMises(F.stress(e)));
    EXPECT_EQ(stress->GetComponent(e, 0), F.stress(e).xx);
    EXPECT_EQ(body->GetComponent(e, 0), 0);
    stressed = stressed || von_mises->GetComponent(e, 0) > 0;
  }
  EXPECT_TRUE(stressed || w.time() == 0);
}

int run(const std::string& args, const fs::path& log) {
  const std::string cmd = std::string(MPM_SDEM_RUNNER) + " " + args + " >" + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string text(const fs::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(Vtk, FramesReadBackAsTheWorldAndTheCollectionsListThem) {
  const fs::path dir =
      fs::temp_directory_path() / ("mpm_sdem_test_vtk_" + std::to_string(getpid()));
  fs::remove_all(dir);
  World w = makeWorld();
  VtkSeries series((dir / "new" / "vtk").string());  // made with its parents
  std::vector<double> times;
  for (int f = 0; f < 3; ++f) {
    if (f > 0) runUntil(w, 0.02 * f);
    ASSERT_TRUE(series.write(w));
    times.push_back(w.time());
    EXPECT_FALSE(series.write(w)) << "a second frame at the same time";
    // Each collection lists every frame so far at its time; its last one is this world.
    for (const char* kind : {"points", "blocks", "fem"}) {
      const auto frames = readCollection(dir / "new" / "vtk" / (std::string(kind) + ".pvd"));
      ASSERT_EQ(frames.size(), times.size()) << kind;
      for (std::size_t k = 0; k < frames.size(); ++k) {
        EXPECT_EQ(frames[k].first, times[k]) << kind << " frame " << k;
        EXPECT_TRUE(fs::exists(dir / "new" / "vtk" / frames[k].second)) << frames[k].second;
      }
      const auto grid = readGrid(dir / "new" / "vtk" / frames.back().second);
      SCOPED_TRACE(std::string(kind) + " frame " + std::to_string(f));
      if (kind == std::string("points")) expectPoints(grid, w);
      if (kind == std::string("blocks")) expectBlocks(grid, w, f == 2);
      if (kind == std::string("fem")) expectFem(grid, w);
    }
  }
  EXPECT_EQ(series.frames(), 3);
  EXPECT_GT(times[2], times[1]);
  // The frames differ: the last collection entry is not an earlier frame's file.
  const auto frames = readCollection(dir / "new" / "vtk" / "points.pvd");
  const auto first = readGrid(dir / "new" / "vtk" / frames[1].second);
  const auto last = readGrid(dir / "new" / "vtk" / frames[2].second);
  EXPECT_NE(first->GetPoint(0)[1], last->GetPoint(0)[1]);
  EXPECT_FALSE(fs::exists(dir / "new" / "vtk" / "points.pvd.tmp"));
  fs::remove_all(dir);
}

TEST(Vtk, DirectoryProblems) {
  const fs::path dir =
      fs::temp_directory_path() / ("mpm_sdem_test_vtk_dir_" + std::to_string(getpid()));
  EXPECT_EQ(vtkDirProblem((dir / "a" / "b").string()).text(), "");
  EXPECT_NE(vtkDirProblem("").text(), "");
  EXPECT_NE(vtkDirProblem("/dev/null").message.find("not a directory"), std::string::npos);
  EXPECT_NE(vtkDirProblem("/dev/null/vtk").message.find("not a directory"), std::string::npos);
  EXPECT_THROW({ VtkSeries s("/dev/null"); }, std::runtime_error);
  EXPECT_FALSE(fs::exists(dir)) << "a check must not make the directory";
}

// The runner's frames: at the start, at the first step past each multiple of --vtk-every and at
// the end; no fem.pvd without FEM bodies: --vtk-every 0.008 to 0.02 s gives frames at 0, the
// first steps past 0.008 and 0.016, and 0.02. Bad intervals are a bad command line (exit 2).
TEST(Vtk, RunnerWritesFramesFromStartToEnd) {
  const fs::path out =
      fs::temp_directory_path() / ("mpm_sdem_test_vtk_runner_" + std::to_string(getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string scene = test::sourcePath("test/data/valid_cluster.yaml");
  ASSERT_EQ(run(scene + " --set time.end=0.02 --vtk-every 0.008 --threads 1 --quiet --out " +
                    (out / "run").string(),
                out / "log"),
            0)
      << text(out / "log");
  const auto frames = readCollection(out / "run" / "vtk" / "points.pvd");
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].first, 0);
  for (int k = 1; k <= 2; ++k) {
    EXPECT_GE(frames[k].first, 0.008 * k * (1 - 1e-6)) << k;
    EXPECT_LT(frames[k].first, 0.008 * k + 1e-3) << k;  // within a step (about 1e-4 s)
  }
  EXPECT_DOUBLE_EQ(frames[3].first, 0.02);
  EXPECT_EQ(readCollection(out / "run" / "vtk" / "blocks.pvd").size(), 4u);
  EXPECT_FALSE(fs::exists(out / "run" / "vtk" / "fem.pvd"));
  EXPECT_EQ(readGrid(out / "run" / "vtk" / frames[3].second)->GetNumberOfPoints(), 400);
  for (const std::string bad : {"-1", "nan", "abc", "0", "inf"}) {
    EXPECT_EQ(run(scene + " --vtk-every " + bad + " --quiet --out " + (out / "bad").string(),
                  out / "log"),
              2)
        << bad;
    EXPECT_NE(text(out / "log").find("--vtk-every takes an interval > 0 s"), std::string::npos)
        << text(out / "log");
  }
  EXPECT_FALSE(fs::exists(out / "bad"));
  fs::remove_all(out);
}
