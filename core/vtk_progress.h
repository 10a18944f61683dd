#pragma once
// Forwards a VTK algorithm's progress (its ProgressEvent, 0..1) to the running stage's bar
// (core/progress.h). Header-only, for the stages that run VTK readers and writers (volume, io);
// whoever includes it links VTK's CommonCore.
// Tested in tests/io/test_mesh_file.cpp (progress while writing).
#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>

#include "core/progress.h"

namespace isocurv {

/// While alive, reports `algorithm`'s progress to report_stage_progress. Create it before
/// Update()/Write(); not copyable. Same thread as the algorithm.
class VtkProgressReport {
 public:
  explicit VtkProgressReport(vtkAlgorithm* algorithm) : algorithm_(algorithm) {
    command_->SetCallback(&VtkProgressReport::on_progress);
    tag_ = algorithm_->AddObserver(vtkCommand::ProgressEvent, command_);
  }
  ~VtkProgressReport() { algorithm_->RemoveObserver(tag_); }
  VtkProgressReport(const VtkProgressReport&) = delete;
  VtkProgressReport& operator=(const VtkProgressReport&) = delete;

 private:
  static void on_progress(vtkObject*, unsigned long, void*, void* call_data) {
    if (call_data) report_stage_progress(*static_cast<const double*>(call_data));
  }
  vtkAlgorithm* algorithm_;
  vtkNew<vtkCallbackCommand> command_;
  unsigned long tag_ = 0;
};

}  // namespace isocurv
