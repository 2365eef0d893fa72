#include "vtu_writer.hpp"

#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstdio>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "core/particle_fields.hpp"

namespace seismpm {

namespace {

struct ArrayName {
  VtuArray array;
  const char* name;
  int components;
};
constexpr ArrayName kArrays[] = {
    {VtuArray::Id, "id", 1},
    {VtuArray::Body, "body", 1},
    {VtuArray::Material, "material", 1},
    {VtuArray::Mass, "mass", 1},
    {VtuArray::Volume, "volume", 1},
    {VtuArray::Density, "density", 1},
    {VtuArray::Displacement, "displacement", 3},
    {VtuArray::Velocity, "velocity", 3},
    {VtuArray::Stress, "stress", 6},
    {VtuArray::Strain, "strain", 6},
    {VtuArray::Pressure, "pressure", 1},
    {VtuArray::Q, "q", 1},
    {VtuArray::ShearStrain, "shear_strain", 1},
    {VtuArray::PlasticStrain, "plastic_strain", 1},
    {VtuArray::Yield, "yield", 1},
};

const ArrayName& info(VtuArray a) { return kArrays[static_cast<int>(a)]; }

// Time and phase as field data, which ParaView shows and reads.
void add_meta(vtkUnstructuredGrid* grid, const VtuMeta& meta) {
  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->InsertNextValue(meta.time);
  grid->GetFieldData()->AddArray(time);
  vtkNew<vtkStringArray> phase;
  phase->SetName("phase");
  phase->InsertNextValue(meta.phase);
  grid->GetFieldData()->AddArray(phase);
}

void write(const std::string& path, vtkUnstructuredGrid* grid) {
  const std::string tmp = path + ".tmp";
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    std::remove(tmp.c_str());
    throw OutputError("cannot write " + path + " (VTK error code " + std::to_string(writer->GetErrorCode()) +
                      "; disk full or directory not writable?)");
  }
  commit_file(tmp, path);
}

}  // namespace

std::vector<VtuArray> all_vtu_arrays() {
  std::vector<VtuArray> out;
  for (const auto& a : kArrays) out.push_back(a.array);
  return out;
}

VtuArray parse_vtu_array(const std::string& name) {
  for (const auto& a : kArrays)
    if (name == a.name) return a.array;
  if (name == "ux" || name == "uy" || name == "uz") return VtuArray::Displacement;
  if (name == "vx" || name == "vy" || name == "vz") return VtuArray::Velocity;
  if (name == "sxx" || name == "syy" || name == "szz" || name == "sxy" || name == "syz" || name == "sxz")
    return VtuArray::Stress;
  std::string names;
  for (const auto& a : kArrays) names += std::string(names.empty() ? "" : " ") + a.name;
  throw InputError("unknown output field '" + name + "' (fields: " + names +
                   ", or component names such as ux, vy, sxx)");
}

template <int Dim>
void write_particles_vtu(const std::string& path, const Particles<Dim>& P, const std::vector<std::size_t>& index,
                         const std::vector<VtuArray>& arrays, const VtuMeta& meta) {
  const vtkIdType n = static_cast<vtkIdType>(index.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType k = 0; k < n; ++k) {
    const auto& x = P.x[index[k]];
    points->SetPoint(k, x[0], x[1], Dim == 3 ? x[Dim - 1] : 0.0);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->Allocate(n);
  for (vtkIdType k = 0; k < n; ++k) grid->InsertNextCell(VTK_VERTEX, 1, &k);

  for (VtuArray a : arrays) {
    const ArrayName& ai = info(a);
    if (a == VtuArray::Id || a == VtuArray::Body || a == VtuArray::Material || a == VtuArray::Yield) {
      vtkNew<vtkIntArray> arr;
      arr->SetName(ai.name);
      arr->SetNumberOfValues(n);
      const Field f = a == VtuArray::Id ? Field::Id : a == VtuArray::Body ? Field::Body
                                                   : a == VtuArray::Material ? Field::Material : Field::Yield;
      for (vtkIdType k = 0; k < n; ++k) arr->SetValue(k, static_cast<int>(field_value(P, index[k], f)));
      grid->GetPointData()->AddArray(arr);
      continue;
    }
    vtkNew<vtkDoubleArray> arr;
    arr->SetName(ai.name);
    arr->SetNumberOfComponents(ai.components);
    arr->SetNumberOfTuples(n);
    for (vtkIdType k = 0; k < n; ++k) {
      const std::size_t p = index[k];
      double t[6] = {0, 0, 0, 0, 0, 0};
      switch (a) {
        case VtuArray::Mass: t[0] = P.mass[p]; break;
        case VtuArray::Volume: t[0] = P.volume[p]; break;
        case VtuArray::Density: t[0] = P.density(p); break;
        case VtuArray::Displacement: for (int d = 0; d < Dim; ++d) t[d] = P.u[p][d]; break;
        case VtuArray::Velocity: for (int d = 0; d < Dim; ++d) t[d] = P.v[p][d]; break;
        case VtuArray::Stress: for (int c = 0; c < 6; ++c) t[c] = P.stress[p][c]; break;
        case VtuArray::Strain: for (int c = 0; c < 6; ++c) t[c] = P.strain[p][c]; break;
        case VtuArray::Pressure: t[0] = pressure(P.stress[p]); break;
        case VtuArray::Q: t[0] = von_mises(P.stress[p]); break;
        case VtuArray::ShearStrain: t[0] = equivalent_shear_strain(P.strain[p]); break;
        case VtuArray::PlasticStrain: t[0] = P.plastic_strain[p]; break;
        default: break;
      }
      arr->SetTypedTuple(k, t);
    }
    grid->GetPointData()->AddArray(arr);
  }
  add_meta(grid, meta);
  write(path, grid);
}

template <int Dim>
void write_grid_vtu(const std::string& path, const Grid<Dim>& G, double mass_threshold, const VtuMeta& meta) {
  std::vector<int> nodes;
  for (int i = 0; i < G.node_count(); ++i)
    if (G.mass[i] > mass_threshold || G.fixity(i)) nodes.push_back(i);
  const vtkIdType n = static_cast<vtkIdType>(nodes.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> mass, velocity;
  vtkNew<vtkIntArray> fixity;
  mass->SetName("mass");
  mass->SetNumberOfValues(n);
  velocity->SetName("velocity");
  velocity->SetNumberOfComponents(3);
  velocity->SetNumberOfTuples(n);
  fixity->SetName("fixity");  // bit mask of the held directions: 1 x, 2 y, 4 z
  fixity->SetNumberOfValues(n);
  for (vtkIdType k = 0; k < n; ++k) {
    const int i = nodes[k];
    const auto x = G.node_position(i);
    points->SetPoint(k, x[0], x[1], Dim == 3 ? x[Dim - 1] : 0.0);
    mass->SetValue(k, G.mass[i]);
    double v[3] = {0, 0, 0};
    for (int d = 0; d < Dim; ++d) v[d] = G.velocity[i][d];
    velocity->SetTypedTuple(k, v);
    fixity->SetValue(k, static_cast<int>(G.fixity(i)));
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->Allocate(n);
  for (vtkIdType k = 0; k < n; ++k) grid->InsertNextCell(VTK_VERTEX, 1, &k);
  grid->GetPointData()->AddArray(mass);
  grid->GetPointData()->AddArray(velocity);
  grid->GetPointData()->AddArray(fixity);
  add_meta(grid, meta);
  write(path, grid);
}

template void write_particles_vtu<2>(const std::string&, const Particles<2>&, const std::vector<std::size_t>&,
                                     const std::vector<VtuArray>&, const VtuMeta&);
template void write_particles_vtu<3>(const std::string&, const Particles<3>&, const std::vector<std::size_t>&,
                                     const std::vector<VtuArray>&, const VtuMeta&);
template void write_grid_vtu<2>(const std::string&, const Grid<2>&, double, const VtuMeta&);
template void write_grid_vtu<3>(const std::string&, const Grid<3>&, double, const VtuMeta&);

}  // namespace seismpm
