#pragma once
// ParaView data collections (.pvd): the index file that makes a folder of per-frame meshes open
// in ParaView as one time series.
//
//   <VTKFile type="Collection" version="0.1">
//     <Collection>
//       <DataSet timestep="0.25" group="" part="0" file="frame_0001.vtp"/>
//       ...
//
// File names are stored relative to the .pvd's folder (so the folder can be moved), with the
// five XML special characters escaped. Times are written with 17 significant digits, so they read
// back exactly.
// Tested in tests/io/test_pvd_collection.cpp, tests/app/test_deform_cli.cpp.
#include <string>
#include <vector>

namespace isocurv::io {

/// One frame of a collection: its time and its file (as stored: relative to the .pvd's folder
/// when written by PvdCollection; read_pvd resolves it, see there).
struct PvdFrame {
  double time = 0.0;
  std::string file;
};

/// Writes a .pvd as frames are produced. Every add() rewrites the whole collection atomically
/// (core/atomic_file.h), so at any moment the file on disk is a valid collection listing exactly
/// the frames added so far: a series that fails at frame k leaves a .pvd naming frames 0..k-1.
/// Not thread-safe: one writer per collection.
class PvdCollection {
 public:
  /// @param path the .pvd to write (its folder must exist). Nothing is written before the first
  ///        add(); an existing file at `path` is replaced then.
  explicit PvdCollection(std::string path);

  /// Records a frame already written at `frame_path` (absolute, or relative to the current
  /// directory) with time `time`, and rewrites the collection.
  /// @throw Error when `time` is not finite or not greater than the previous frame's time, or when
  ///        the .pvd cannot be written (the previous version then stays in place).
  void add(double time, const std::string& frame_path);

  /// The frames added so far, file names as stored in the .pvd.
  const std::vector<PvdFrame>& frames() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<PvdFrame> frames_;
};

/// Reads a .pvd collection: its DataSet entries in file order, each file resolved against the
/// .pvd's folder (so the returned paths can be opened directly).
/// @throw Error naming the file when it is missing, not XML, not a VTK Collection, or has a
///        DataSet without a numeric timestep or a file attribute.
std::vector<PvdFrame> read_pvd(const std::string& path);

}  // namespace isocurv::io
