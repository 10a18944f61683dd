#include "dist/piece_file.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dist/gather.h"
#include "io/field_arrays.h"
#include "io/polydata.h"

namespace isocurv::dist {
namespace fs = std::filesystem;
namespace {

std::string stem_of(const std::string& pvtp) { return fs::path(pvtp).stem().string(); }

vtkSmartPointer<vtkPolyData> piece_polydata(const Piece& p, const curvature::CurvatureField* field,
                                            const io::Metadata* context) {
  vtkSmartPointer<vtkPolyData> poly = io::to_polydata(p.mesh, field, context);
  auto ids = vtkSmartPointer<vtkIdTypeArray>::New();
  ids->SetName("vtkGlobalPointIds");
  ids->SetNumberOfTuples(vtkIdType(p.global_ids.size()));
  for (std::size_t i = 0; i < p.global_ids.size(); ++i) ids->SetValue(vtkIdType(i), vtkIdType(p.global_ids[i]));
  poly->GetPointData()->SetGlobalIds(ids);
  auto ghost_array = [](const std::vector<std::uint8_t>& flags) {
    auto a = vtkSmartPointer<vtkUnsignedCharArray>::New();
    a->SetName(vtkDataSetAttributes::GhostArrayName());
    a->SetNumberOfTuples(vtkIdType(flags.size()));
    std::copy(flags.begin(), flags.end(), a->GetPointer(0));
    return a;
  };
  poly->GetPointData()->AddArray(ghost_array(p.point_ghost));
  poly->GetCellData()->AddArray(ghost_array(p.cell_ghost));
  return poly;
}

// Gives an empty piece (a rank whose slab holds no surface) the point arrays the others carry,
// with no tuples: VTK's reader wants each piece to hold the arrays the .pvtp lists, and rank 0,
// which writes the .pvtp, may be the empty one. Collective.
void declare_arrays_of_others(const World& world, vtkPolyData* poly) {
  vtkPointData* pd = poly->GetPointData();
  std::string mine;  // "name type components" lines, from a piece with points
  if (poly->GetNumberOfPoints() > 0)
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
      if (vtkDataArray* a = pd->GetArray(i); a && a->GetName())
        mine += std::string(a->GetName()) + " " + std::to_string(a->GetDataType()) + " " +
                std::to_string(a->GetNumberOfComponents()) + "\n";
  std::vector<char> chosen;
  for (const std::vector<char>& part : world.gather(std::vector<char>(mine.begin(), mine.end())))
    if (chosen.empty()) chosen = part;
  chosen = world.broadcast(std::move(chosen));
  if (poly->GetNumberOfPoints() > 0) return;
  std::istringstream in(std::string(chosen.begin(), chosen.end()));
  std::string name;
  int type = 0, components = 0;
  while (in >> name >> type >> components) {
    if (pd->GetArray(name.c_str())) continue;
    vtkSmartPointer<vtkDataArray> a = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
    a->SetName(name.c_str());
    a->SetNumberOfComponents(components);
    if (name == "Normals")
      pd->SetNormals(a);
    else
      pd->AddArray(a);
  }
}

// The VTK XML type name of an array.
std::string xml_type(vtkDataArray* a) {
  switch (a->GetDataType()) {
    case VTK_FLOAT: return "Float32";
    case VTK_DOUBLE: return "Float64";
    case VTK_UNSIGNED_CHAR: return "UInt8";
    case VTK_CHAR: case VTK_SIGNED_CHAR: return "Int8";
    case VTK_SHORT: return "Int16";
    case VTK_UNSIGNED_SHORT: return "UInt16";
    case VTK_INT: return "Int32";
    case VTK_UNSIGNED_INT: return "UInt32";
    default: return a->GetDataTypeSize() == 8 ? "Int64" : "Int32";  // vtkIdType, long
  }
}

void list_arrays(std::ostream& out, vtkDataSetAttributes* data, const char* tag) {
  out << "    <" << tag;
  if (auto* n = data->GetNormals()) out << " Normals=\"" << n->GetName() << "\"";
  if (auto* g = data->GetGlobalIds()) out << " GlobalIds=\"" << g->GetName() << "\"";
  out << ">\n";
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = data->GetArray(i);
    if (!a || !a->GetName()) continue;
    // IdType="1": read back as vtkIdTypeArray (what GlobalIds must be), as the pieces declare it.
    out << "      <PDataArray type=\"" << xml_type(a) << "\"" << (a->GetDataType() == VTK_ID_TYPE ? " IdType=\"1\"" : "")
        << " Name=\"" << a->GetName()
        << "\" NumberOfComponents=\"" << a->GetNumberOfComponents() << "\"/>\n";
  }
  out << "    </" << tag << ">\n";
}

// The .pvtp `pvtp`, written at `path` (its temporary name).
void write_pvtp_file(const std::string& path, const std::string& pvtp, vtkPolyData* sample, int pieces) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path, "cannot open for writing");
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "  <PPolyData GhostLevel=\"1\">\n";
  list_arrays(out, sample->GetPointData(), "PPointData");
  list_arrays(out, sample->GetCellData(), "PCellData");
  out << "    <PPoints>\n      <PDataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
      << "    </PPoints>\n";
  for (int r = 0; r < pieces; ++r) out << "    <Piece Source=\"" << piece_source(pvtp, r) << "\"/>\n";
  out << "  </PPolyData>\n</VTKFile>\n";
  out.close();
  if (!out) throw Error(path, "write failed (disk full?)");
}

}  // namespace

bool is_pvtp(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".pvtp";
}

std::string piece_source(const std::string& pvtp, int rank) {
  const std::string stem = stem_of(pvtp);
  return stem + "/" + stem + "_" + std::to_string(rank) + ".vtp";
}

std::string piece_path(const std::string& pvtp, int rank) {
  return (fs::path(pvtp).parent_path() / piece_source(pvtp, rank)).string();
}

std::unique_ptr<NewFolder> require_writable_pieces(const World& world, const std::string& pvtp) {
  const fs::path folder = fs::path(piece_path(pvtp, 0)).parent_path();
  std::unique_ptr<NewFolder> made;
  together(world, [&] {
    if (world.rank() != 0) return;
    require_writable_file(pvtp);
    std::error_code ec;
    if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
      throw Error(folder.string(), "exists and is not a folder (the pieces of " + pvtp + " go there)");
    made = std::make_unique<NewFolder>(folder.string());
  });
  together(world, [&] { require_writable_file(piece_path(pvtp, world.rank())); });
  return made;
}

void write_pieces(const World& world, const std::string& pvtp, const Piece& piece,
                  const curvature::CurvatureField* field, const io::Compression& compression,
                  const io::Metadata* context) {
  vtkSmartPointer<vtkPolyData> poly;
  AtomicFileSet files;
  const std::string mine = piece_path(pvtp, world.rank());
  together(world, [&] { poly = piece_polydata(piece, field, context); });
  declare_arrays_of_others(world, poly);
  together(world, [&] {
    files.write(mine, [&](const std::string& tmp) { io::write_polydata(tmp, poly, compression); });
  });
  // Every piece is ready: into place, then the index. A rank whose rename failed, or rank 0's
  // .pvtp failing, takes every new piece away again.
  const std::string renamed = world.agree(guarded([&] { files.commit(); }));
  std::string error = renamed;
  if (renamed.empty())
    error = world.agree(guarded([&] {
      if (world.rank() == 0)
        write_atomically(pvtp, [&](const std::string& tmp) { write_pvtp_file(tmp, pvtp, poly, world.size()); });
    }));
  if (!error.empty()) {
    std::error_code ec;
    fs::remove(mine, ec);
    throw Error(error);
  }
}

void write_gathered(const World& world, const std::string& path, const Piece& piece,
                    const curvature::CurvatureField* field, const io::Compression& compression,
                    const io::Metadata* context) {
  Mesh mesh;
  curvature::CurvatureField whole;
  together(world, [&] { gather_mesh(world, piece, field, mesh, whole); });
  together(world, [&] {
    if (world.rank() == 0) io::write_mesh(path, mesh, field ? &whole : nullptr, compression, context);
  });
}

}  // namespace isocurv::dist
