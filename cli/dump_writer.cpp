#include "dump_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <regex>

#include "huygens/common/atomic_file.hpp"
#include "huygens/common/comm.hpp"
#include "huygens/common/npy.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "vtk_writer.hpp"

namespace huygens {

// The names a dump writes: meta.json, run.pvd and FIELD_NNNNNN[_J].npy|vti|vtu (FIELD a lower-case
// identifier, the step in six or more digits, J the display frame inside a step), each also with
// ".tmp". Any other file in the folder (an input bed .npy, notes) is not a run's and is never removed.
bool is_run_file(const std::filesystem::path& p) {
  static const std::regex name(R"((meta\.json|run\.pvd|[a-z][a-z0-9_]*_[0-9]{6,}(_[0-9]+)?\.(npy|vti|vtu))(\.tmp)?)");
  return std::regex_match(p.filename().string(), name);
}

DumpFormat parse_dump_format(const std::string& text) {
  if (text == "npy") return {true, false};
  if (text == "vtk") return {false, true};
  if (text == "both") return {true, true};
  throw UsageError("--dump-format " + text + ": choose npy, vtk or both");
}

namespace {

#ifdef HUYGENS_HAVE_MPI
// The reason of a failed MPI call, or "" when it succeeded.
std::string mpi_error(int code) {
  if (code == MPI_SUCCESS) return "";
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(code, text, &len);
  return std::string(text, static_cast<std::size_t>(len));
}

// One .npy from the rows of every rank (a collective): PATH.tmp is opened by all ranks and emptied,
// rank 0 writes the header, each rank writes its rows at header + row0 * row bytes
// (MPI_File_write_at_all), the file is flushed to the disk (MPI_File_sync, Sync::to_disk) and
// closed, and only when every rank succeeded rank 0 renames it onto PATH (the folder is flushed
// once per dump, DumpWriter::write_step). Any failure: every rank throws IoError, no file under PATH.
void write_npy_ranks(const std::string& path, const OutputField& f, Sync sync) {
  const std::string tmp = path + ".tmp", header = npy_header(f.full_shape());
  std::size_t row_elems = 1;
  for (std::size_t i = 1; i < f.shape.size(); ++i) row_elems *= f.shape[i];
  MPI_File fh;
  std::string err =
      mpi_error(MPI_File_open(comm::world(), tmp.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &fh));
  const bool opened = !comm::any(!err.empty());
  if (opened) {
    auto step = [&](int code) {
      if (err.empty()) err = mpi_error(code);
    };
    step(MPI_File_set_size(fh, 0));  // a stale temporary from an earlier run may be longer
    if (comm::root())
      step(MPI_File_write_at(fh, 0, header.data(), static_cast<int>(header.size()), MPI_BYTE, MPI_STATUS_IGNORE));
    MPI_Datatype row;
    MPI_Type_contiguous(static_cast<int>(row_elems), MPI_FLOAT, &row);
    MPI_Type_commit(&row);
    const MPI_Offset at = static_cast<MPI_Offset>(header.size() + f.row0 * row_elems * sizeof(float));
    step(MPI_File_write_at_all(fh, at, f.data.data(), static_cast<int>(f.shape.empty() ? 0 : f.shape[0]), row,
                               MPI_STATUS_IGNORE));
    MPI_Type_free(&row);
    if (sync == Sync::to_disk) step(MPI_File_sync(fh));  // collective
    step(MPI_File_close(&fh));
  }
  bool failed = comm::any(!err.empty());
  if (!failed && comm::root()) {
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
      err = std::strerror(errno);
    }
  }
  failed = comm::any(!err.empty());
  if (!failed) return;
  if (comm::root()) std::remove(tmp.c_str());
  throw IoError(path, err.empty() ? "another rank could not write its rows" : err);
}
#endif

// One dumped field: the whole array in one process, the rows of every rank on MPI ranks.
void write_field(const std::string& path, const OutputField& f, Sync sync) {
#ifdef HUYGENS_HAVE_MPI
  if (comm::size() > 1) return write_npy_ranks(path, f, sync);
#endif
  if (!f.global_shape.empty() && f.global_shape != f.shape)
    throw std::logic_error("a field of " + f.name + " holds part of the rows in a run of one rank");
  write_npy(path, f.data, f.shape, sync == Sync::to_disk ? Sync::file : sync);  // the folder: once a dump
}

// Where the grid's samples sit: meta.json's "dx" and "visible"/"origin_m" (every solver's meta()).
VtkGrid vtk_grid(const nlohmann::json& meta) {
  const auto& o = meta.at("visible").at("origin_m");
  return {meta.at("dx").get<double>(), o.at(0).get<double>(), o.at(1).get<double>()};
}

// The files that list others (meta.json, run.pvd): removed first by --overwrite.
bool is_index_file(const std::filesystem::path& p) { return p.filename() == "meta.json" || p.filename() == "run.pvd"; }

// Runs fn on rank 0 alone (meta.json, the folder) and agrees on the outcome: when it throws
// IoError there, every rank throws one (no rank waits in a collective for one that stopped).
void agreed_on_root(const std::string& what, const std::function<void()>& fn) {
  std::exception_ptr failure;
  if (comm::root()) try {
      fn();
    } catch (const IoError&) {
      failure = std::current_exception();
    }
  if (!comm::any(failure != nullptr)) return;
  if (failure) std::rethrow_exception(failure);
  throw IoError(what, "rank 0 could not write it");
}

}  // namespace

void DumpWriter::prepare(const std::string& dir, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw IoError(dir, ec ? ec.message() : "not a folder");
  std::vector<fs::path> old;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && is_run_file(e.path())) old.push_back(e.path());
  if (!old.empty() && !overwrite)
    throw UsageError("the dump folder " + dir + " holds another run's files (" + std::to_string(old.size()) +
                     ", e.g. " + old.front().filename().string() + "): choose an empty folder or add --overwrite");
  comm::barrier();  // every rank looked before rank 0 removes
  // meta.json and run.pvd go first, and their removal reaches the disk before the files they list
  // go: a crash part-way leaves unlisted files, never a meta.json or run.pvd that lists a removed one
  std::stable_partition(old.begin(), old.end(), is_index_file);
  agreed_on_root(dir, [&] {
    for (const auto& p : old) {
      if (!fs::remove(p, ec)) throw IoError(p.string(), "cannot remove: " + ec.message());
      if (is_index_file(p)) sync_folder(dir, p.string());
    }
    check_output_file(dir + "/meta.json");  // the folder takes a new file
  });
}

DumpWriter::DumpWriter(std::string dir, const std::string& scene_file, Solver& solver, Sync sync, DumpFormat format)
    : dir_(std::move(dir)), solver_(solver), sync_(sync), format_(format), meta_(solver.meta()) {
  meta_["scene"] = scene_file;
  meta_["dump_format"] = format_.npy && format_.vtk ? "both" : format_.vtk ? "vtk" : "npy";
  meta_["dumps"] = nlohmann::json::array();
  meta_["complete"] = false;
  meta_["ranks"] = comm::size();
  meta_["fsync"] = sync_ == Sync::to_disk;  // false: --no-fsync (a crash of the machine may lose dumps)
}

// meta.json carries the solver's meta refreshed (step counts, adaptive dt history)
void DumpWriter::save_meta() {
  const nlohmann::json now = solver_.meta();
  for (const auto& [key, value] : now.items()) meta_[key] = value;
  agreed_on_root(dir_ + "/meta.json", [&] { write_file_atomic(dir_ + "/meta.json", meta_.dump(2) + "\n", sync_); });
}

// run.pvd: every VTK file meta.json lists, at its dump's time; the grid files are part 0 "grid", the
// particles part 1 "particles" (ParaView reads both of a time as the two blocks of one data set).
void DumpWriter::save_pvd() {
  std::vector<PvdDataSet> sets;
  for (const auto& d : meta_["dumps"])
    for (const auto& f : d["files"]) {
      const std::string name = f.get<std::string>();
      const bool vtu = name.ends_with(".vtu");
      if (vtu || name.ends_with(".vti"))
        sets.push_back({d["time_s"].get<double>(), vtu ? 1 : 0, vtu ? "particles" : "grid", name});
    }
  const std::string path = dir_ + "/run.pvd";
  agreed_on_root(path, [&] { write_file_atomic(path, pvd_text(sets), sync_); });
}

// The grid fields as grid<stem>.vti, the per-particle fields as particles<stem>.vtu.
void DumpWriter::write_vtk(const std::vector<OutputField>& fields, const std::string& stem, nlohmann::json& files) {
  std::vector<OutputField> grid, particles;
  for (const auto& f : fields) (f.per_particle ? particles : grid).push_back(f);
  const Sync sync = sync_ == Sync::to_disk ? Sync::file : sync_;  // the folder: once a dump
  if (!grid.empty()) {
    files.push_back("grid" + stem + ".vti");
    written_.push_back(dir_ + "/" + files.back().get<std::string>());
    write_vti(written_.back(), grid, vtk_grid(meta_), sync);
  }
  if (!particles.empty()) {
    files.push_back("particles" + stem + ".vtu");
    written_.push_back(dir_ + "/" + files.back().get<std::string>());
    write_vtu(written_.back(), particles, sync);
  }
}

void DumpWriter::write_entry(nlohmann::json entry, const std::vector<OutputField>& fields, const std::string& suffix) {
  entry["files"] = nlohmann::json::array();
  const std::string stem = fmt("_%06lld%s", entry["step"].get<long long>(), suffix.c_str());
  if (format_.npy)
    for (const auto& f : fields) {
      const std::string name = f.name + stem + ".npy";
      written_.push_back(dir_ + "/" + name);
      write_field(written_.back(), f, sync_);
      entry["files"].push_back(name);
    }
  if (format_.vtk) write_vtk(fields, stem, entry["files"]);
  entry["index"] = static_cast<long long>(meta_["dumps"].size());
  meta_["dumps"].push_back(entry);
}

// A dump that fails part-way removes the files it wrote and its entries: no unlisted step is left
// under a final name, and meta.json (written last) still lists the earlier dumps.
void DumpWriter::dump() {
  const nlohmann::json before = meta_["dumps"];
  written_.clear();
  try {
    write_step();
  } catch (...) {
    std::error_code ec;
    if (comm::root())
      for (const auto& f : written_) std::filesystem::remove(f, ec);
    meta_["dumps"] = before;
    throw;
  }
  // after meta.json: run.pvd never lists a dump that meta.json does not (a crash or a failed write
  // between the two leaves it one dump behind)
  if (format_.vtk) save_pvd();
}

void DumpWriter::write_step() {
  const long long s = solver_.steps();
  const int per_step = solver_.display_per_step();
  // displayed frames interpolated inside the last step (s - 1, s): written before the full step
  if (per_step > 1 && s >= 1) {
    const double dt = meta_.value("dt", 0.0);
    for (int j = 1; j < per_step; ++j) {
      const double sj = static_cast<double>(j) / per_step;
      nlohmann::json entry = {{"step", s - 1},
                              {"time_s", (static_cast<double>(s - 1) + sj) * dt},
                              {"interpolated", true},
                              {"s", sj},
                              {"display_frame", (s - 1) * per_step + j}};
      write_entry(entry, solver_.display_outputs(j), fmt("_%d", j));
    }
  }
  nlohmann::json entry = {
      {"step", s}, {"time_s", solver_.time()}, {"interpolated", false}, {"s", 0.0}, {"display_frame", s * per_step}};
  write_entry(entry, solver_.outputs(), "");
  // every file of the dump is on the disk (Sync::file); their renames too before meta.json lists them
  if (sync_ == Sync::to_disk) agreed_on_root(dir_, [&] { sync_folder(dir_, dir_); });
  save_meta();
}

void DumpWriter::stopped(const nlohmann::json& entry) {
  meta_["stopped"] = entry;
  save_meta();
}

void DumpWriter::complete() {
  meta_["complete"] = true;
  save_meta();
}

}  // namespace huygens
