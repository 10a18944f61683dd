#pragma once
// Turning VTK's error reports (printed to stderr by default) into exceptions.
// Tested in tests/app/cli.h, python/tests/test_isocurv.py (through its users).
#include <string>
#include <vector>

#include <vtkSmartPointer.h>

class vtkObject;
class vtkCallbackCommand;

namespace isocurv::io {

/// Stops VTK from printing anything itself, for the whole process: its logger's stderr output
/// (vtkLogger, with colour codes) and its output window (where errors go that no observer takes).
/// VTK errors still reach VtkErrorCapture observers, which turn them into one-line exceptions.
/// Call once, early in main().
void silence_vtk_output();

/// For its lifetime, observes the ErrorEvent of a VTK object and keeps the first message instead
/// of letting VTK print it. For an algorithm it also observes the algorithm's executive (which
/// reports "returned failure for request"), and for an XML reader its internal parser. Typical
/// use: attach to a reader or writer, run it, then
/// `if (capture.failed()) throw Error(path, capture.message())`.
class VtkErrorCapture {
 public:
  explicit VtkErrorCapture(vtkObject* object);
  ~VtkErrorCapture();
  VtkErrorCapture(const VtkErrorCapture&) = delete;
  VtkErrorCapture& operator=(const VtkErrorCapture&) = delete;

  /// Also observes `other` (kept alive until the capture ends).
  void watch(vtkObject* other);

  bool failed() const { return !message_.empty(); }
  /// The first error's text without VTK's "ERROR: In file, line" prefix, on one line.
  const std::string& message() const { return message_; }

 private:
  static void on_event(vtkObject*, unsigned long, void* self, void* call_data);
  vtkSmartPointer<vtkCallbackCommand> command_;
  std::vector<vtkSmartPointer<vtkObject>> watched_;
  vtkObject* parser_owner_ = nullptr;  // the XML reader whose parser observer we set
  std::string message_;
};

}  // namespace isocurv::io
