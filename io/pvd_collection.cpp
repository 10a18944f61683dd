// .pvd collections: written by hand (a few lines of XML), read with VTK's XML parser.
#include "io/pvd_collection.h"

#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "core/atomic_file.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace isocurv::io {
namespace {

// The five characters XML does not allow verbatim in an attribute value.
std::string xml_escaped(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// `frame` as seen from the .pvd's folder (generic '/' separators, so the file reads the same on
// every system).
std::string relative_to_collection(const std::string& pvd_path, const std::string& frame) {
  const fs::path folder = fs::absolute(fs::path(pvd_path)).parent_path();
  return fs::absolute(fs::path(frame))
      .lexically_normal()
      .lexically_relative(folder)
      .generic_string();
}

std::string collection_text(const std::vector<PvdFrame>& frames) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const PvdFrame& f : frames) {
    char time[32];
    std::snprintf(time, sizeof time, "%.17g", f.time);
    out << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\""
        << xml_escaped(f.file) << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
  return out.str();
}

}  // namespace

PvdCollection::PvdCollection(std::string path) : path_(std::move(path)) {}

void PvdCollection::add(double time, const std::string& frame_path) {
  if (!std::isfinite(time)) throw Error(path_, "frame time is not a finite number");
  if (!frames_.empty() && !(time > frames_.back().time))
    throw Error(path_, "frame times must increase (" + std::to_string(time) + " after " +
                           std::to_string(frames_.back().time) + ")");
  std::vector<PvdFrame> next = frames_;
  next.push_back({time, relative_to_collection(path_, frame_path)});
  const std::string text = collection_text(next);
  write_atomically(path_, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw Error(tmp, "cannot write the collection");
  });
  frames_ = std::move(next);
}

std::vector<PvdFrame> read_pvd(const std::string& path) {
  if (!fs::is_regular_file(path)) throw Error(path, "no such file");
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.c_str());
  // The parser reports malformed XML through VTK's error output; its return value is what counts.
  parser->SetGlobalWarningDisplay(0);
  if (parser->Parse() != 1 || parser->GetRootElement() == nullptr)
    throw Error(path, "not a readable XML file");
  vtkXMLDataElement* root = parser->GetRootElement();
  const char* type = root->GetAttribute("type");
  if (std::string(root->GetName()) != "VTKFile" || type == nullptr ||
      std::string(type) != "Collection")
    throw Error(path, "not a VTK collection (.pvd): the root is not <VTKFile type=\"Collection\">");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (collection == nullptr) throw Error(path, "no <Collection> element");
  const fs::path folder = fs::path(path).parent_path();
  std::vector<PvdFrame> frames;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = collection->GetNestedElement(i);
    if (std::string(e->GetName()) != "DataSet") continue;
    double t = 0;
    const char* file = e->GetAttribute("file");
    if (e->GetScalarAttribute("timestep", t) == 0 || !std::isfinite(t) || file == nullptr)
      throw Error(path, "DataSet " + std::to_string(frames.size()) +
                            " lacks a numeric timestep or a file attribute");
    const fs::path f(file);
    frames.push_back({t, (f.is_absolute() ? f : folder / f).lexically_normal().string()});
  }
  return frames;
}

}  // namespace isocurv::io
