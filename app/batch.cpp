#include "app/batch.h"
#include "app/commands.h"

#include <glob.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>
#include <map>
#include <memory>

#include "app/picture_title.h"
#include "app/shared_pictures.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "dist/world.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "volume/load.h"

namespace isocurv::app {
namespace {

namespace fs = std::filesystem;

bool has_glob_chars(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

/// One input as the batch sees it: a path, or a glob that matched nothing (an error entry).
struct Input {
  std::string path;
  std::string error;  ///< set when there is nothing to read
};

std::vector<Input> expand_inputs(const std::vector<std::string>& given) {
  std::vector<Input> out;
  for (const std::string& g : given) {
    std::error_code ec;
    if (!has_glob_chars(g) || fs::exists(g, ec)) {
      out.push_back({g, ""});
      continue;
    }
    glob_t found{};
    const int rc = ::glob(g.c_str(), 0, nullptr, &found);  // sorted by glob(3)
    if (rc == 0) {
      for (std::size_t i = 0; i < found.gl_pathc; ++i) out.push_back({found.gl_pathv[i], ""});
    } else {
      out.push_back({g, g + ": no file matches this pattern"});
    }
    globfree(&found);
  }
  return out;
}

/// A loaded input, or why it could not be loaded.
struct Loaded {
  std::optional<volume::Volume> volume;
  std::optional<Surface> mesh_file;  ///< a mesh input (curvature only)
  nlohmann::json load_timings = nlohmann::json::object();
  std::string error;
};

/// The command's name, for summary.json and messages.
std::string command_name(BatchKind kind, const BatchStep* step) {
  switch (kind) {
    case BatchKind::extract: return "extract";
    case BatchKind::curvature: return "curvature";
    case BatchKind::run: return "run";
    case BatchKind::step: break;
  }
  return step ? step->command : "batch";
}

Loaded load_input(const Input& in, BatchKind kind, const BatchStep* step, const CommonOptions& o,
                  bool sweep) {
  Loaded l;
  if (!in.error.empty()) {
    l.error = in.error;
    return l;
  }
  try {
    StageTimer timer;
    if (is_mesh_path(in.path)) {
      const bool takes_meshes =
          kind == BatchKind::curvature || (kind == BatchKind::step && step && step->mesh_input);
      if (!takes_meshes)
        throw Error(in.path, "isocurv " + command_name(kind, step) +
                                 " takes a volume, and this is a mesh file");
      if (sweep) throw Error(in.path, "--iso applies to volumes only, and this is a mesh file");
      l.mesh_file = load_surface(in.path, o, timer);  // also refuses volume options
    } else {
      timer.start("load");
      l.volume = volume::load(in.path, to_load_options(o.volume));
      timer.stop();
    }
    l.load_timings = timer.json();
  } catch (const std::exception& e) {
    l.error = e.what();
  }
  return l;
}

/// What writing one entry needs, so that it can run on the writer thread.
struct Pending {
  Surface surface;
  BatchStep::Output step;  ///< BatchKind::step: what the command's compute left to write
  std::string input, mesh_path, png_path, stats_path;
  nlohmann::json entry;  ///< filled in by the writer
  std::size_t tag = 0;   ///< the index its entry will have in the summary (shared pictures)
  StageTimer timer;
};

/// A BatchStep's entry: its output (at p.mesh_path) and stats.json (its report) together, and its
/// entry completed with the output, its size, the step's counts and the timings.
void write_step_outputs(Pending& p) {
  AtomicFileSet outputs;
  p.timer.start("write");
  std::uint64_t output_bytes = 0;
  outputs.write(p.mesh_path, [&](const std::string& tmp) {
    p.step.write(tmp);
    output_bytes = file_bytes(tmp);
  });
  p.timer.stop();
  nlohmann::json r = std::move(p.step.report);
  r["input"] = p.input;
  r["output"] = p.mesh_path;
  r["timings_ms"] = p.timer.json();
  outputs.write(p.stats_path,
                [&](const std::string& tmp) { write_text_file(tmp, r.dump(2) + "\n"); });
  outputs.commit();
  p.entry["status"] = "ok";
  p.entry["output"] = p.mesh_path;
  p.entry["output_bytes"] = output_bytes;
  p.entry["stats"] = p.stats_path;
  for (const std::string& key : p.step.summary_keys)
    if (r.contains(key)) p.entry[key] = r[key];
  p.entry["timings_ms"] = p.timer.json();
  p.step = {};  // what `write` held on to
}

/// Writes an entry's outputs together (mesh, PNG for run, stats.json) and completes its entry.
/// With `shared` (run's --range shared), the PNG is only noted, for shared->draw() at the end.
void write_outputs(Pending& p, BatchKind kind, const BatchRequest& rq, const CommonOptions& o,
                   SharedPictures* shared) {
  if (kind == BatchKind::step) return write_step_outputs(p);
  const Surface& s = p.surface;
  AtomicFileSet outputs;
  p.timer.start("write");
  std::uint64_t mesh_bytes = 0;
  outputs.write(p.mesh_path, [&](const std::string& tmp) {
    const io::Metadata context =
        context_metadata(s, p.input, rq.render ? rq.render->opts.length_unit : "");
    io::write_mesh(tmp, s.mesh, s.field ? &*s.field : nullptr, o.compress, &context);
    mesh_bytes = file_bytes(tmp);
  });
  if (kind == BatchKind::run) {
    p.timer.start("render");
    const viz::RenderOptions opts = render_options_for(
        *rq.render, p.input, surface_context(s), with_ao(estimator_title(s.estimator), o), &*s.field);
    if (shared)
      shared->add({p.mesh_path, p.png_path, opts, "", p.tag}, s.mesh, *s.field);
    else
      outputs.write(p.png_path,
                    [&](const std::string& tmp) { viz::render_png(tmp, s.mesh, *s.field, opts); });
  }
  p.timer.stop();
  nlohmann::json r = surface_report(s);
  r["input"] = p.input;
  r["mesh"] = p.mesh_path;
  if (kind == BatchKind::run) r["png"] = p.png_path;
  r["mesh_bytes"] = mesh_bytes;
  r["compression"] = io::to_string(o.compress);
  r["device"] = device_name(o);
  r["timings_ms"] = p.timer.json();
  outputs.write(p.stats_path,
                [&](const std::string& tmp) { write_text_file(tmp, r.dump(2) + "\n"); });
  outputs.commit();
  p.entry["status"] = "ok";
  p.entry["mesh"] = p.mesh_path;
  p.entry["mesh_bytes"] = mesh_bytes;
  if (kind == BatchKind::run) p.entry["png"] = p.png_path;
  p.entry["stats"] = p.stats_path;
  p.entry["vertices"] = r["vertices"];
  p.entry["triangles"] = r["triangles"];
  // The curvature statistics (stats.json's, which say what they count), so that one file
  // compares the inputs.
  if (r.contains("estimator")) p.entry["estimator"] = r["estimator"]["name"];
  if (r.contains("curvature")) p.entry["curvature"] = r["curvature"];
  p.entry["timings_ms"] = p.timer.json();
}

/// The probe of an output folder before any work: created if missing, and a file can be made in it.
void require_writable_folder(const std::string& dir) {
  make_output_folder(dir, "several inputs or isovalues");
  std::error_code ec;
  const std::string probe =
      (fs::path(dir) / (".isocurv-probe-" + std::to_string(getpid()))).string();
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) throw Error(dir, "the output folder is not writable");
  std::fclose(f);
  fs::remove(probe, ec);
}

}  // namespace

std::vector<float> parse_isovalues(const std::string& text) {
  std::vector<float> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const float v = std::strtof(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      throw Error("--iso '" + text + "': '" + item +
                  "' is not a finite number (expected V or V1,V2,...)");
    for (float seen : out)
      if (seen == v) throw Error("--iso '" + text + "': " + item + " is given twice");
    out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

bool is_batch(const std::vector<std::string>& inputs, const std::vector<float>& isovalues) {
  if (inputs.size() > 1 || isovalues.size() > 1) return true;
  std::error_code ec;
  return !inputs.empty() && has_glob_chars(inputs[0]) && !fs::exists(inputs[0], ec);
}

void add_batch_options(CLI::App& cmd, BatchCli& b, const std::string& input_name,
                       const std::string& input_help, const std::vector<std::string>& formats) {
  cmd.add_option(input_name, b.inputs,
                 input_help +
                     "; several files or globs make a batch: -o is then a folder, each "
                     "input written under DIR/<stem>/, and DIR/summary.json lists them")
      ->required();
  cmd.add_option(
         "--iso", b.iso,
         "Isovalue (default: the volume's suggested isovalue, see isocurv info); several, "
         "V1,V2,..., make a sweep of one loaded volume (outputs suffixed _iso<V>, -o a folder)")
      ->check([](const std::string& text) -> std::string {
        try {
          parse_isovalues(text);
          return "";
        } catch (const Error& e) {
          return e.what();
        }
      });
  cmd.add_option("--jobs", b.jobs,
                 "Batches: 2 or more loads the next input and writes the last one's mesh while the "
                 "current one is computed (1: one step at a time)")
      ->check(CLI::Range(1, 64))
      ->each([&b](const std::string&) { b.jobs_given = true; })
      ->capture_default_str();
  if (!formats.empty())
    cmd.add_option("--format", b.format, "Batches: the mesh format written under DIR/<stem>/")
        ->check(CLI::IsMember(formats))
        ->each([&b](const std::string&) { b.format_given = true; })
        ->capture_default_str();
}

namespace {

/// The isovalues of a batch, or nullopt for one input at one isovalue (then o.iso is set, and
/// --format and --jobs, for batches only, are an Error).
std::optional<std::vector<float>> batch_isovalues(const BatchCli& b, CommonOptions& o) {
  const std::vector<float> isos = b.iso.empty() ? std::vector<float>{} : parse_isovalues(b.iso);
  if (!is_batch(b.inputs, isos)) {
    if (b.format_given)
      throw Error(
          "--format applies to batches (several inputs or isovalues); for one output the "
          "extension of -o chooses the format");
    if (b.jobs_given) throw Error("--jobs applies to batches (several inputs or isovalues)");
    if (!isos.empty()) o.iso = isos[0];
    return std::nullopt;
  }
  if (o.labelled()) throw Error("--labels takes one label map at a time, not a batch or a sweep");
  return isos;
}

}  // namespace

namespace {

// Several ranks on one input of a command that only hands out batches (on_ranks: lines) would
// run it once per rank, every rank writing the same files.
void refuse_one_input_on_ranks(const std::string& command) {
  const int ranks = dist::World::get().size();
  if (ranks > 1 && on_ranks(command) == OnRanks::batches)
    throw Error(command + " with one input does not run on " + std::to_string(ranks) +
                " ranks: under mpirun it takes several inputs (a batch); docs/distributed.md");
}

}  // namespace

bool run_as_batch(const BatchCli& b, CommonOptions& o, BatchKind kind, const std::string& dir,
                  const RenderCli* render, const std::string& format) {
  if (kind == BatchKind::step) throw Error("internal: a step batch without its BatchStep");
  const std::optional<std::vector<float>> batch = batch_isovalues(b, o);
  if (!batch) return false;
  const std::vector<float>& isos = *batch;
  if (render && !render->dirs_out.empty())
    throw Error(render->dirs_out, "--dirs-out names one file: not with several inputs or isovalues");
  BatchRequest rq;
  rq.kind = kind;
  rq.inputs = b.inputs;
  rq.isovalues = isos;
  rq.dir = dir;
  rq.format = format.empty() ? b.format : format;
  rq.jobs = b.jobs;
  rq.render = render;
  run_batch(rq, o);
  return true;
}

bool run_as_batch(const BatchCli& b, CommonOptions& o, const BatchStep& step,
                  const std::string& dir, const std::function<void()>& before) {
  const std::optional<std::vector<float>> isos = batch_isovalues(b, o);
  if (!isos) {
    refuse_one_input_on_ranks(step.command);
    return false;
  }
  if (before) before();
  BatchRequest rq;
  rq.kind = BatchKind::step;
  rq.step = &step;
  rq.inputs = b.inputs;
  rq.isovalues = *isos;
  rq.dir = dir;
  rq.format = b.format;
  rq.jobs = b.jobs;
  run_batch(rq, o);
  return true;
}

void require_series_cli(const BatchCli& b, CommonOptions& o) {
  const std::vector<float> isos = b.iso.empty() ? std::vector<float>{} : parse_isovalues(b.iso);
  if (isos.size() > 1)
    throw Error("--iso: one isovalue with --time-series (every frame is cut at the same value)");
  if (b.format_given) throw Error("--format: a time series writes .vtp frames (ParaView's .pvd)");
  if (b.jobs_given) throw Error("--jobs applies to batches, not to --time-series");
  if (o.labelled()) throw Error("--labels takes one label map at a time, not a time series");
  if (!isos.empty()) o.iso = isos[0];
}

void require_folder_name(const std::string& dir, const std::string& what) {
  std::error_code ec;
  if (fs::exists(dir, ec)) return;  // an existing folder (or file: the callers' own error)
  std::string ext = fs::path(dir).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const char* const kFileLike[] = {".vtp", ".vtk", ".vtu", ".vti", ".pvtp", ".pvd", ".ply", ".obj",
                                          ".stl", ".png", ".jpg", ".svg", ".json", ".csv", ".txt", ".nrrd",
                                          ".nhdr", ".nii", ".gz", ".mhd", ".raw", ".vdb", ".vol"};
  for (const char* e : kFileLike)
    if (ext == e)
      throw Error(dir, "the output (-o) of " + what + " is a folder, and this names a file (give a folder, e.g. " +
                           (fs::path(dir).parent_path() / fs::path(dir).stem()).string() + "/)");
}

void make_output_folder(const std::string& dir, const std::string& what) {
  require_folder_name(dir, what);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(dir, "the output (-o) of " + what + " must be a folder, and this is a file");
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error(dir, "cannot create the output folder: " + ec.message());
}

std::string file_stem(const std::string& path, const std::string& fallback) {
  // std::filesystem drops the last extension and keeps a leading dot ("Al.100.vol" -> "Al.100",
  // ".hidden" stays); a compression suffix takes the extension before it too ("head.nii.gz").
  const fs::path name = fs::path(path).filename();
  fs::path stem = name.stem();
  for (const char* compressed : {".gz", ".bz2", ".xz", ".zst", ".lz4"})
    if (name.extension() == compressed) stem = stem.stem();
  return stem.empty() ? fallback : stem.string();
}

std::string iso_suffix(float iso) { return "_iso" + format_number(iso); }

namespace {

// Every rank's batch entries at rank 0, in input order (a sweep's isovalues in theirs), each
// tagged with the rank that made it when there are several; an empty list on the other ranks.
nlohmann::json gather_entries(const dist::World& world, const nlohmann::json& entries) {
  const std::string text = entries.dump();
  const std::vector<std::vector<char>> all = world.gather(std::vector<char>(text.begin(), text.end()));
  nlohmann::json out = nlohmann::json::array();
  if (world.rank() != 0) return out;
  std::vector<std::pair<std::size_t, nlohmann::json>> tagged;
  for (std::size_t r = 0; r < all.size(); ++r)
    for (nlohmann::json e : nlohmann::json::parse(all[r].begin(), all[r].end())) {
      const std::size_t index = e.value("input_index", std::size_t(0));
      e.erase("input_index");
      if (world.size() > 1) e["rank"] = r;
      tagged.emplace_back(index, std::move(e));
    }
  std::stable_sort(tagged.begin(), tagged.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& t : tagged) out.push_back(std::move(t.second));
  return out;
}

}  // namespace

void run_batch(const BatchRequest& rq, const CommonOptions& o) {
  const auto t_start = std::chrono::steady_clock::now();
  if (rq.kind == BatchKind::curvature || rq.kind == BatchKind::run)
    require_curvature_format("x." + rq.format);
  if (rq.kind == BatchKind::run && !rq.render)
    throw Error("internal: run batch without render options");
  if (rq.kind == BatchKind::step && (!rq.step || !rq.step->compute))
    throw Error("internal: step batch without its compute");
  const std::vector<Input> inputs = expand_inputs(rq.inputs);
  // Patterns that match nothing at all: one error, and no output folder made.
  if (!inputs.empty() &&
      std::all_of(inputs.begin(), inputs.end(), [](const Input& in) { return !in.error.empty(); }))
    throw Error(inputs.front().error);
  // Under mpirun every rank runs this: the inputs go to the ranks as they become free (a shared
  // counter), and rank 0 writes summary.json from every rank's entries.
  const dist::World& world = dist::World::get();
  const bool ranks = world.size() > 1;
  dist::together(world, [&] {
    if (world.rank() == 0) require_writable_folder(rq.dir);  // before any work
  });
  const bool sweep = rq.isovalues.size() > 1;
  if (!reference_device(o)) device_for(o);  // no OpenCL: one error before any input

  // Per-input folders, unique by stem.
  std::vector<std::string> folders;
  std::map<std::string, int> seen;
  for (const Input& in : inputs) {
    const std::string stem = file_stem(in.path, "input");
    const int n = ++seen[stem];
    folders.push_back(stem + (n > 1 ? "_" + std::to_string(n) : ""));
  }

  nlohmann::json entries = nlohmann::json::array();
  std::size_t failed = 0;
  auto fail = [&](nlohmann::json entry, const std::string& message) {
    std::fprintf(stderr, "isocurv: %s\n", one_line(message).c_str());
    entry["status"] = "failed";
    entry["error"] = one_line(message);
    entries.push_back(std::move(entry));
    ++failed;
  };

  // run: one colour range and camera for every picture (--range shared), drawn at the end.
  std::optional<SharedPictures> shared;
  if (rq.kind == BatchKind::run) shared.emplace(*rq.render);
  SharedPictures* pictures = shared && shared->active() ? &*shared : nullptr;
  if (pictures && ranks)
    throw Error("--range shared needs every picture on one process; under mpirun give each picture its own "
                "range (--range auto) or run the batch without mpirun");

  const bool overlap = rq.jobs >= 2;
  // The inputs in the order the counter hands them out: 0, 1, 2, ... on one process.
  dist::SharedCounter tickets(world);
  auto take = [&] { return std::size_t(tickets.draw()); };
  std::future<Loaded> next;
  std::size_t first = take();
  if (overlap && first < inputs.size())
    next = std::async(std::launch::async, load_input, inputs[first], rq.kind, rq.step, o, sweep);
  // At most one write in flight; its entry is appended when it is collected, in order.
  std::future<void> writing;
  std::unique_ptr<Pending> in_flight;
  auto collect = [&] {
    if (!in_flight) return;
    try {
      writing.get();
      entries.push_back(in_flight->entry);
    } catch (const std::exception& e) {
      fail(in_flight->entry, e.what());
    }
    in_flight.reset();
  };

  for (std::size_t i = first, following = 0; i < inputs.size(); i = following) {
    const Input& in = inputs[i];
    Loaded loaded = overlap ? next.get() : load_input(in, rq.kind, rq.step, o, sweep);
    following = take();
    if (overlap && following < inputs.size())
      next = std::async(std::launch::async, load_input, inputs[following], rq.kind, rq.step, o, sweep);
    const fs::path folder = fs::path(rq.dir) / folders[i];
    const std::string stem = file_stem(in.path, "input");
    std::vector<std::optional<float>> isos;
    if (rq.isovalues.empty() || loaded.mesh_file) isos.push_back(std::nullopt);
    for (float v : rq.isovalues)
      if (!loaded.mesh_file) isos.push_back(v);
    if (!loaded.error.empty()) {
      for (const auto& iso : isos) {
        nlohmann::json entry = {{"input", in.path}, {"input_index", i}};
        if (iso) entry["isovalue"] = *iso;
        fail(entry, loaded.error);
      }
      continue;
    }
    std::unique_ptr<mc::Mesher> mesher;  // one block index per volume, shared by its isovalues
    for (const auto& iso : isos) {
      nlohmann::json entry = {{"input", in.path}, {"input_index", i}};
      if (iso) entry["isovalue"] = *iso;
      auto p = std::make_unique<Pending>();
      p->input = in.path;
      try {
        Surface& s = p->surface;
        if (loaded.mesh_file) {
          s = *loaded.mesh_file;
          if (rq.kind != BatchKind::step) prepare_mesh_for_curvature(s, in.path, o);  // the step's own
        } else {
          s.volume = loaded.volume;
          s.isovalue = checked_isovalue(in.path, *s.volume, iso);
          entry["isovalue"] = s.isovalue;
          mc::Options mo;
          mo.cap = o.cap;
          mo.snap = o.snap;
          p->timer.start("extract");
          if (reference_device(o)) {
            s.mesh = mc::extract_reference(*s.volume, s.isovalue, mo);
          } else {
            if (!mesher) mesher = std::make_unique<mc::Mesher>(*loaded.volume, device_for(o));
            s.mesh = mesher->extract(s.isovalue, mo);
          }
          p->timer.stop();
          handle_empty_surface(
              s, in.path, o,
              rq.kind == BatchKind::extract ? EmptySurface::warn : EmptySurface::error);
        }
        if (rq.kind == BatchKind::step) {
          p->step = rq.step->compute(s, in.path, p->timer);
          p->timer.stop();  // its last stage ends here, not when the writer starts
        } else if (rq.kind != BatchKind::extract) {
          s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, p->timer,
                                       &s.normals, &s.estimator);
        }
        std::error_code ec;
        fs::create_directories(folder, ec);
        if (ec) throw Error(folder.string(), "cannot create the output folder: " + ec.message());
        const std::string suffix = sweep ? iso_suffix(s.isovalue) : "";
        p->mesh_path = (folder / (stem + suffix + "." + rq.format)).string();
        p->png_path = (folder / (stem + suffix + ".png")).string();
        p->stats_path = (folder / ("stats" + suffix + ".json")).string();
        entry["load_ms"] = loaded.load_timings.value("load", 0.0);
        p->entry = entry;
      } catch (const std::exception& e) {
        fail(entry, e.what());
        continue;
      }
      // The write of this entry may overlap the next entry's compute (not for run: VTK renders
      // on this thread).
      collect();
      if (overlap && rq.kind != BatchKind::run) {
        in_flight = std::move(p);
        Pending* raw = in_flight.get();
        writing =
            std::async(std::launch::async, [raw, &rq, &o] { write_outputs(*raw, rq.kind, rq, o, nullptr); });
      } else {
        try {
          p->tag = entries.size();  // the entry goes in next
          write_outputs(*p, rq.kind, rq, o, pictures);
          entries.push_back(p->entry);
        } catch (const std::exception& e) {
          fail(p->entry, e.what());
        }
      }
    }
    loaded = Loaded{};
  }
  collect();
  nlohmann::json picture_report;
  if (pictures) {
    const viz::ColorRange range = pictures->range();
    picture_report = {{"range", "shared"}, {"camera", rq.render->camera_file.empty() ? "shared" : "--camera"}};
    if (!rq.render->opts.range) picture_report["color_range"] = {range.lo, range.hi};
    for (const SharedPictureFailure& f : pictures->draw()) {
      nlohmann::json& entry = entries.at(f.tag);
      if (entry.value("status", "") != "ok") continue;  // failed already (its stats.json)
      std::fprintf(stderr, "isocurv: %s\n", one_line(f.message).c_str());
      entry["status"] = "failed";
      entry["error"] = one_line(f.message);
      ++failed;
    }
  }
  entries = gather_entries(world, entries);  // every rank's, in input order (rank 0; empty elsewhere)
  const std::vector<std::int64_t> counts = world.sum(std::vector<std::int64_t>{std::int64_t(failed), std::int64_t(entries.size())});
  failed = std::size_t(counts[0]);
  const std::size_t total_entries = std::size_t(counts[1]);
  if (world.rank() == 0)  // folders of inputs that wrote nothing are removed again (only when empty)
    for (const std::string& f : folders) {
      std::error_code ec;
      fs::remove(fs::path(rq.dir) / f, ec);
    }

  const double total_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start).count();
  nlohmann::json summary = {
      {"command", command_name(rq.kind, rq.step)},
      {"inputs", inputs.size()},
      {"entries", entries},
      {"ok", total_entries - failed},
      {"failed", failed},
      {"compression", io::to_string(o.compress)},
      {"jobs", rq.jobs},
      {"device", reference_device(o) ? device_name(o) : device_for(o).info().name},
      {"programs", program_report()},
      {"wall_ms", std::round(total_ms * 1000) / 1000}};
  if (!picture_report.is_null()) summary["pictures"] = picture_report;
  if (ranks) summary["ranks"] = world.size();
  const std::string summary_path = (fs::path(rq.dir) / "summary.json").string();
  dist::together(world, [&] {
    if (world.rank() == 0) write_text_file(summary_path, summary.dump(2) + "\n");
  });
  if (world.rank() == 0 && o.json) {
    std::cout << summary.dump(2) << "\n";
  } else if (world.rank() == 0 && !o.quiet) {
    std::cout << total_entries - failed << " of " << total_entries << " written under " << rq.dir
              << " (" << inputs.size() << " input" << (inputs.size() == 1 ? "" : "s") << ", "
              << format_number(std::round(total_ms)) << " ms); summary: " << summary_path << "\n";
  }
  if (failed > 0)  // on every rank (rank 0 prints it), so that every rank exits with status 1
    throw Error(std::to_string(failed) + " of " + std::to_string(total_entries) +
                " entries failed (listed above and in " + summary_path + ")");
}

}  // namespace isocurv::app
