#include "grids.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>

#include <cmath>

#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/vtk/vtk_series.hpp"

namespace mpm_sdem::vtk_grids {

namespace {

// A named array of n tuples owned by data (the pointer stays valid while data holds it).
template <class Array>
Array* addArray(vtkFieldData* data, const char* name, int components, vtkIdType n) {
  vtkNew<Array> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(n);
  data->AddArray(a);
  return a;
}

// ParaView's names for the components of a symmetric tensor, in VTK's order.
template <class Array>
Array* addStress(vtkFieldData* data, vtkIdType n) {
  Array* a = addArray<Array>(data, "stress", 6, n);
  const char* names[6] = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};
  for (int c = 0; c < 6; ++c) a->SetComponentName(c, names[c]);
  return a;
}

template <class Array, class S>
void setStress(Array* a, vtkIdType i, const S& s) {
  const double v[6] = {s.xx, s.yy, s.zz, s.xy, 0, 0};
  a->SetTuple(i, v);
}

void setTime(vtkUnstructuredGrid* grid, double t) {
  addArray<vtkDoubleArray>(grid->GetFieldData(), "TimeValue", 1, 1)->SetValue(0, t);
}

// Cells of `size` points each: the point ids in nodes, or without nodes the points in order (one
// vertex per point).
void setCells(vtkUnstructuredGrid* grid, int type, int size, vtkIdType cells,
              const vtkIdType* nodes = nullptr) {
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(cells * size);
  for (vtkIdType k = 0; k < cells * size; ++k) connectivity->SetValue(k, nodes ? nodes[k] : k);
  vtkNew<vtkCellArray> array;
  array->SetData(size, connectivity);
  grid->SetCells(type, array);
}

}  // namespace

vtkSmartPointer<vtkUnstructuredGrid> points(const World& world) {
  const Particles& P = world.particles();
  const vtkIdType n = static_cast<vtkIdType>(P.size());
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToFloat();
  xyz->SetNumberOfPoints(n);
  vtkPointData* pd = grid->GetPointData();
  auto* velocity = addArray<vtkFloatArray>(pd, "velocity", 3, n);
  auto* speed = addArray<vtkFloatArray>(pd, "speed", 1, n);
  auto* stress = addStress<vtkFloatArray>(pd, n);
  auto* pressures = addArray<vtkFloatArray>(pd, "pressure", 1, n);
  auto* von_mises = addArray<vtkFloatArray>(pd, "von_mises", 1, n);
  auto* material = addArray<vtkIntArray>(pd, "material", 1, n);
  auto* kind = addArray<vtkIntArray>(pd, "kind", 1, n);
  auto* mass = addArray<vtkFloatArray>(pd, "mass", 1, n);
  auto* J = addArray<vtkFloatArray>(pd, "J", 1, n);
  for (vtkIdType p = 0; p < n; ++p) {
    xyz->SetPoint(p, P.x[p], P.y[p], 0);
    velocity->SetTuple3(p, P.vx[p], P.vy[p], 0);
    speed->SetValue(p, static_cast<float>(std::hypot(P.vx[p], P.vy[p])));
    const Stress s{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]};
    setStress(stress, p, s);
    pressures->SetValue(p, static_cast<float>(pressure(s)));
    von_mises->SetValue(p, static_cast<float>(vonMises(s)));
    material->SetValue(p, P.material[p]);
    kind->SetValue(p, P.kind[p]);
    mass->SetValue(p, static_cast<float>(P.mass[p]));
    J->SetValue(p, static_cast<float>(P.J[p]));
  }
  grid->SetPoints(xyz);
  setCells(grid, VTK_VERTEX, 1, n);
  setTime(grid, world.time());
  return grid;
}

vtkSmartPointer<vtkUnstructuredGrid> blocks(const World& world) {
  const Blocks& B = *world.blocks();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polygons;
  vtkCellData* cd = grid->GetCellData();
  auto* block = addArray<vtkIntArray>(cd, "block", 1, 0);
  auto* part = addArray<vtkIntArray>(cd, "part", 1, 0);
  auto* type = addArray<vtkIntArray>(cd, "type", 1, 0);
  auto* position = addArray<vtkDoubleArray>(cd, "position", 3, 0);
  auto* angle = addArray<vtkDoubleArray>(cd, "angle", 1, 0);
  auto* velocity = addArray<vtkDoubleArray>(cd, "velocity", 3, 0);
  auto* angular_velocity = addArray<vtkDoubleArray>(cd, "angular_velocity", 1, 0);
  auto* coupling_force = addArray<vtkDoubleArray>(cd, "coupling_force", 3, 0);
  auto* coupling_torque = addArray<vtkDoubleArray>(cd, "coupling_torque", 1, 0);
  auto* coupling_contacts = addArray<vtkIntArray>(cd, "coupling_contacts", 1, 0);
  auto* block_force = addArray<vtkDoubleArray>(cd, "block_force", 3, 0);
  auto* block_torque = addArray<vtkDoubleArray>(cd, "block_torque", 1, 0);
  auto* block_contacts = addArray<vtkIntArray>(cd, "block_contacts", 1, 0);
  vtkNew<vtkStringArray> names;
  names->SetName("block_names");
  for (int i = 0; i < B.count(); ++i) {
    names->InsertNextValue(B.def(i).name);
    const BlockState& s = B.state(i);
    const Blocks::Load& c = B.coupling()[i];
    const Blocks::Load& k = B.blockContact(i);
    const std::vector<Spheropolygon> parts = B.currentParts(i);
    for (std::size_t j = 0; j < parts.size(); ++j) {
      std::vector<Vec2> outline = roundedOutline(parts[j].core, parts[j].rounding, kCornerChords);
      outline.pop_back();  // it closes on its first point; a polygon cell closes itself
      polygons->InsertNextCell(static_cast<int>(outline.size()));
      for (const Vec2& q : outline)
        polygons->InsertCellPoint(xyz->InsertNextPoint(q.x(), q.y(), 0));
      block->InsertNextValue(i);
      part->InsertNextValue(static_cast<int>(j));
      type->InsertNextValue(static_cast<int>(B.def(i).type));
      position->InsertNextTuple3(s.position.x(), s.position.y(), 0);
      angle->InsertNextValue(s.angle);
      velocity->InsertNextTuple3(s.velocity.x(), s.velocity.y(), 0);
      angular_velocity->InsertNextValue(s.angular_velocity);
      coupling_force->InsertNextTuple3(c.force.x(), c.force.y(), 0);
      coupling_torque->InsertNextValue(c.torque);
      coupling_contacts->InsertNextValue(c.contacts);
      block_force->InsertNextTuple3(k.force.x(), k.force.y(), 0);
      block_torque->InsertNextValue(k.torque);
      block_contacts->InsertNextValue(k.contacts);
    }
  }
  grid->SetPoints(xyz);
  grid->SetCells(VTK_POLYGON, polygons);
  grid->GetFieldData()->AddArray(names);
  setTime(grid, world.time());
  return grid;
}

vtkSmartPointer<vtkUnstructuredGrid> fem(const World& world) {
  const FemBodies& F = *world.femBodies();
  const vtkIdType n = F.totalNodes(), cells = F.totalElements();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  xyz->SetNumberOfPoints(n);
  vtkPointData* pd = grid->GetPointData();
  auto* displacement = addArray<vtkDoubleArray>(pd, "displacement", 3, n);
  auto* velocity = addArray<vtkDoubleArray>(pd, "velocity", 3, n);
  auto* node_body = addArray<vtkIntArray>(pd, "body", 1, n);
  auto* held = addArray<vtkIntArray>(pd, "held", 1, n);
  vtkCellData* cd = grid->GetCellData();
  auto* von_mises = addArray<vtkDoubleArray>(cd, "von_mises", 1, cells);
  auto* stress = addStress<vtkDoubleArray>(cd, cells);
  auto* cell_body = addArray<vtkIntArray>(cd, "body", 1, cells);
  std::vector<vtkIdType> nodes(3 * cells);
  vtkNew<vtkStringArray> names;
  names->SetName("fem_names");
  for (int b = 0; b < F.count(); ++b) {
    names->InsertNextValue(F.def(b).name);
    for (int k = F.firstNode(b); k < F.firstNode(b) + F.nodeCount(b); ++k) {
      const Vec2 x = F.position(k), u = x - F.reference(k), v = F.velocity(k);
      xyz->SetPoint(k, x.x(), x.y(), 0);
      displacement->SetTuple3(k, u.x(), u.y(), 0);
      velocity->SetTuple3(k, v.x(), v.y(), 0);
      node_body->SetValue(k, b);
      held->SetValue(k, F.held(k) ? 1 : 0);
    }
    for (int e = F.firstElement(b); e < F.firstElement(b) + F.elementCount(b); ++e) {
      von_mises->SetValue(e, FemBodies::vonMises(F.stress(e)));
      setStress(stress, e, F.stress(e));
      cell_body->SetValue(e, b);
      for (int j = 0; j < 3; ++j) nodes[3 * e + j] = F.elementNodes(e)[j];
    }
  }
  grid->SetPoints(xyz);
  setCells(grid, VTK_TRIANGLE, 3, cells, nodes.data());
  grid->GetFieldData()->AddArray(names);
  setTime(grid, world.time());
  return grid;
}

}  // namespace mpm_sdem::vtk_grids
