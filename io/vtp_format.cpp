// .vtp: VTK XML PolyData through vtkXMLPolyDataWriter/Reader (binary appended, zlib).
#include <stdexcept>

#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/polydata.h"
#include "io/vtk_errors.h"

namespace isocurv::io::detail {

void write_vtp(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  VtkErrorCapture errors(writer);
  writer->SetInputData(to_polydata(mesh, field));
  writer->SetFileName(path.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary, not base64
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();  // arrays over 4 GiB
  const int ok = writer->Write();
  if (!ok || errors.failed() || writer->GetErrorCode() != vtkErrorCode::NoError)
    throw std::runtime_error(errors.failed() ? errors.message()
                                             : vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode()));
}

MeshFile read_vtp(const std::string& path) {
  vtkNew<vtkXMLPolyDataReader> reader;
  VtkErrorCapture errors(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  if (errors.failed() || reader->GetErrorCode() != vtkErrorCode::NoError || !poly)
    throw Error(path, "not a readable VTK XML PolyData file" +
                          (errors.failed() ? " (" + errors.message() + ")" : std::string()));
  return from_polydata(poly, path);
}

}  // namespace isocurv::io::detail
