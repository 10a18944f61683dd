#include "io/vtk_errors.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkLogger.h>
#include <vtkObject.h>
#include <vtkOutputWindow.h>
#include <vtkXMLReader.h>

namespace isocurv::io {
namespace {

/// "ERROR: In /path/file.cxx, line 12\nvtkFoo (0x1234): message\n\n" -> "message", on one line.
std::string clean(std::string text) {
  if (text.rfind("ERROR: In ", 0) == 0 || text.rfind("Warning: In ", 0) == 0) {
    const auto marker = text.find("): ");
    if (marker != std::string::npos) text = text.substr(marker + 3);
  }
  // The executive appends a dump of the failed request: keep the sentence before it.
  const auto dump = text.find(" for request: vtkInformation");
  if (dump != std::string::npos) text = text.substr(0, dump);
  std::string line;
  for (char c : text) {
    const char d = (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
    if (!(d == ' ' && (line.empty() || line.back() == ' '))) line.push_back(d);
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line.empty() ? "VTK reported an error" : line;
}

}  // namespace

void silence_vtk_output() {
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
}

VtkErrorCapture::VtkErrorCapture(vtkObject* object) : command_(vtkSmartPointer<vtkCallbackCommand>::New()) {
  command_->SetCallback(&VtkErrorCapture::on_event);
  command_->SetClientData(this);
  watch(object);
  if (auto* algorithm = vtkAlgorithm::SafeDownCast(object)) watch(algorithm->GetExecutive());
  if (auto* reader = vtkXMLReader::SafeDownCast(object)) {
    reader->SetParserErrorObserver(command_);
    parser_owner_ = reader;
  }
}

VtkErrorCapture::~VtkErrorCapture() {
  if (auto* reader = vtkXMLReader::SafeDownCast(parser_owner_)) reader->SetParserErrorObserver(nullptr);
  for (const auto& object : watched_) object->RemoveObserver(command_);
}

void VtkErrorCapture::watch(vtkObject* other) {
  if (!other) return;
  other->AddObserver(vtkCommand::ErrorEvent, command_);
  watched_.emplace_back(other);
}

void VtkErrorCapture::on_event(vtkObject*, unsigned long, void* self, void* call_data) {
  auto* capture = static_cast<VtkErrorCapture*>(self);
  if (capture->message_.empty()) capture->message_ = clean(call_data ? static_cast<const char*>(call_data) : "");
}

}  // namespace isocurv::io
