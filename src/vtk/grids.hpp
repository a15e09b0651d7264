// A world's state as VTK unstructured grids, one per kind of file (vtk_series.hpp lists the
// arrays and their units). Private to mpm_sdem_vtk: the only place VTK types meet the core's.
#pragma once

#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::vtk_grids {

// One vertex cell per material point and SPH particle.
vtkSmartPointer<vtkUnstructuredGrid> points(const World& world);
// The blocks' outlines as polygons; world.blocks() must not be null.
vtkSmartPointer<vtkUnstructuredGrid> blocks(const World& world);
// The FEM bodies' triangles; world.femBodies() must not be null.
vtkSmartPointer<vtkUnstructuredGrid> fem(const World& world);

}  // namespace mpm_sdem::vtk_grids
