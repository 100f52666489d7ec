#include "dump_writer.hpp"

#include <filesystem>

#include "huygens/common/atomic_file.hpp"
#include "huygens/common/npy.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"

namespace huygens {

namespace {

// A file `huygens run` writes into a dump folder (or its temporary).
bool is_run_file(const std::filesystem::path& p) {
  const std::string name = p.filename().string();
  auto ends = [&](const std::string& s) {
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  return name == "meta.json" || name == "meta.json.tmp" || ends(".npy") || ends(".npy.tmp");
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
  for (const auto& p : old)
    if (!fs::remove(p, ec)) throw IoError(p.string(), "cannot remove: " + ec.message());
  check_output_file(dir + "/meta.json");  // the folder takes a new file
}

DumpWriter::DumpWriter(std::string dir, const std::string& scene_file, Solver& solver)
    : dir_(std::move(dir)), solver_(solver), meta_(solver.meta()) {
  meta_["scene"] = scene_file;
  meta_["dumps"] = nlohmann::json::array();
  meta_["complete"] = false;
}

// meta.json carries the solver's meta refreshed (step counts, adaptive dt history)
void DumpWriter::save_meta() {
  const nlohmann::json now = solver_.meta();
  for (const auto& [key, value] : now.items()) meta_[key] = value;
  write_file_atomic(dir_ + "/meta.json", meta_.dump(2) + "\n");
}

void DumpWriter::write_entry(nlohmann::json entry, const std::vector<OutputField>& fields, const std::string& suffix) {
  entry["files"] = nlohmann::json::array();
  for (const auto& f : fields) {
    const std::string name = fmt("%s_%06lld%s.npy", f.name.c_str(), entry["step"].get<long long>(), suffix.c_str());
    written_.push_back(dir_ + "/" + name);
    write_npy(written_.back(), f.data, f.shape);
    entry["files"].push_back(name);
  }
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
    for (const auto& f : written_) std::filesystem::remove(f, ec);
    meta_["dumps"] = before;
    throw;
  }
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
