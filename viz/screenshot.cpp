#include "viz/screenshot.h"

#include <stdexcept>

#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/vtk_errors.h"

namespace isocurv::viz {

void save_png(vtkRenderWindow* window, const std::string& path) {
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  {
    io::VtkErrorCapture errors(grab);
    grab->Update();
    if (errors.failed()) throw Error(path, "cannot read the rendered image: " + errors.message());
  }
  write_atomically(path, [&](const std::string& tmp) {
    vtkNew<vtkPNGWriter> writer;
    io::VtkErrorCapture errors(writer);
    writer->SetInputConnection(grab->GetOutputPort());
    writer->SetFileName(tmp.c_str());
    writer->Write();
    if (errors.failed() || writer->GetErrorCode() != vtkErrorCode::NoError)
      throw Error(path, "cannot write PNG: " + (errors.failed() ? errors.message()
                                                                : std::string(vtkErrorCode::GetStringFromErrorCode(
                                                                      writer->GetErrorCode()))));
  });
}

}  // namespace isocurv::viz
