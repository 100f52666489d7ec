#pragma once
// The dump folder of `huygens run`: DIR/<field>_NNNNNN[_J].npy per dumped step (and with the VTK
// format DIR/grid_NNNNNN[_J].vti, DIR/particles_NNNNNN.vtu and DIR/run.pvd, vtk_writer.hpp) and
// DIR/meta.json, rewritten after every dump so it always lists exactly the complete dumps
// (docs/robustness.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "huygens/common/atomic_file.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens {

/// A file `huygens run` writes into a dump folder (meta.json, run.pvd, *.npy, *.vti, *.vtu) or its
/// temporary.
bool is_run_file(const std::filesystem::path& p);

/// The formats of a dump (`--dump-format npy|vtk|both`): .npy files, VTK XML files for ParaView.
struct DumpFormat {
  bool npy = true, vtk = false;
};

/// Parses "npy", "vtk" or "both"; UsageError otherwise.
DumpFormat parse_dump_format(const std::string& text);

class DumpWriter {
 public:
  /// Makes DIR (or checks it) before the run: a folder that holds another run's files (meta.json,
  /// *.npy) is refused with UsageError unless `overwrite`, which removes those files only; DIR
  /// must take a new file (IoError otherwise).
  static void prepare(const std::string& dir, bool overwrite);

  /// `sync`: Sync::to_disk flushes every file and the folder before meta.json lists them.
  DumpWriter(std::string dir, const std::string& scene_file, Solver& solver, Sync sync = Sync::to_disk,
             DumpFormat format = {});
  /// Writes the current step's fields (and the displayed frames interpolated inside the last
  /// step), then meta.json, then (VTK) run.pvd. Throws IoError naming the file; the earlier dumps
  /// stay listed.
  void dump();
  /// Records how the run ended ("stopped": stage, step, reason or signal) and writes meta.json.
  void stopped(const nlohmann::json& entry);
  /// Marks the run complete and writes meta.json.
  void complete();

 private:
  void write_entry(nlohmann::json entry, const std::vector<OutputField>& fields, const std::string& suffix);
  void write_vtk(const std::vector<OutputField>& fields, const std::string& stem, nlohmann::json& files);
  void write_step();
  void save_meta();
  void save_pvd();

  std::string dir_;
  Solver& solver_;
  Sync sync_;
  DumpFormat format_;
  nlohmann::json meta_;
  std::vector<std::string> written_;  // the files of the dump being written
};

}  // namespace huygens
