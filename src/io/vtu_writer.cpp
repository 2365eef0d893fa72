#include "vtu_writer.hpp"

#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
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

namespace seismpm {

namespace {

// Time, phase and the names of the material and body indices as field data, which ParaView shows.
void add_meta(vtkUnstructuredGrid* grid, const VtuMeta& meta) {
  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->InsertNextValue(meta.time);
  grid->GetFieldData()->AddArray(time);
  vtkNew<vtkDoubleArray> phase_time;
  phase_time->SetName("phase_time");
  phase_time->InsertNextValue(meta.phase_time);
  grid->GetFieldData()->AddArray(phase_time);
  vtkNew<vtkStringArray> phase;
  phase->SetName("phase");
  phase->InsertNextValue(meta.phase);
  grid->GetFieldData()->AddArray(phase);
  const auto add_names = [&](const char* array, const std::vector<std::string>& names) {
    if (names.empty()) return;
    vtkNew<vtkStringArray> a;
    a->SetName(array);
    for (const auto& name : names) a->InsertNextValue(name);
    grid->GetFieldData()->AddArray(a);
  };
  add_names("material_names", meta.material_names);
  add_names("body_names", meta.body_names);
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
  for (const QuantityInfo& q : kQuantities)
    if (q.vtu_array) out.push_back(q.quantity);
  return out;
}

VtuArray parse_vtu_array(const std::string& name) {
  for (const QuantityInfo& q : kQuantities)
    if (q.vtu_array && name == q.name) return q.quantity;
  // A field name selects the array it is a component of (any dimension: "uz" is valid in 2D too).
  for (const FieldInfo& f : kFields)
    if (quantity_info(f.quantity).vtu_array && name == f.name) return f.quantity;
  std::string names;
  for (const QuantityInfo& q : kQuantities)
    if (q.vtu_array) names += (names.empty() ? "" : " ") + std::string(q.name);
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
    const QuantityInfo& q = quantity_info(a);
    if (!q.vtu_array) continue;  // the position: the points themselves
    const std::string name(q.name);
    if (a == Quantity::Id) {
      // The global-id array, which ParaView's selections and temporal filters follow across files.
      vtkNew<vtkIdTypeArray> arr;
      arr->SetName(name.c_str());
      arr->SetNumberOfValues(n);
      for (vtkIdType k = 0; k < n; ++k) arr->SetValue(k, P.id[index[k]]);
      grid->GetPointData()->SetGlobalIds(arr);
      continue;
    }
    if (q.integer) {
      vtkNew<vtkIntArray> arr;
      arr->SetName(name.c_str());
      arr->SetNumberOfValues(n);
      for (vtkIdType k = 0; k < n; ++k) {
        double value;
        quantity_value(P, index[k], a, &value);
        arr->SetValue(k, static_cast<int>(value));
      }
      grid->GetPointData()->AddArray(arr);
      continue;
    }
    vtkNew<vtkDoubleArray> arr;
    arr->SetName(name.c_str());
    arr->SetNumberOfComponents(q.components);
    arr->SetNumberOfTuples(n);
    for (vtkIdType k = 0; k < n; ++k) {
      double t[6];
      quantity_value(P, index[k], a, t);
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
