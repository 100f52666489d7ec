#pragma once
// VTK XML files that ParaView opens (docs/design.md 6, "ParaView output"): a dump's grid fields as
// one .vti (ImageData, the fields as point data at the grid's samples), its particles as one .vtu
// (UnstructuredGrid: the points, one vertex cell per particle, the fields as point data), and the
// .pvd collection that lists the files of a run with their times. Arrays are float32 (the cells'
// connectivity and offsets Int64), appended raw after the XML, each after its byte count (UInt64),
// in this machine's byte order, which the file names. Each file is written atomically (AtomicFile).
#include <string>
#include <vector>

#include "huygens/common/atomic_file.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens {

/// Where a grid field's samples sit: point (r, c) at (x0 + c dx, y0 + r dx, 0) (unit: m).
struct VtkGrid {
  double dx_m = 1.0, x0_m = 0.0, y0_m = 0.0;
};

/// Writes grid fields that share their (rows, cols) as the point data of one .vti, each array named
/// as its field; a field (rows, cols, k) has k components, k = 2 written as 3 with z = 0 (ParaView's
/// vectors are 3D). Throws IoError naming the file; std::logic_error for fields that do not fit.
void write_vti(const std::string& path, const std::vector<OutputField>& fields, const VtkGrid& grid, Sync sync);

/// Writes per-particle fields as one .vtu: the field "pos" (n, 3) as the points, every other field
/// (n) or (n, k) as point data named as its field. Throws IoError naming the file; std::logic_error
/// for fields that do not fit.
void write_vtu(const std::string& path, const std::vector<OutputField>& fields, Sync sync);

/// One data set of a .pvd collection: its time (unit: s), its part and name (one per kind of file:
/// ParaView reads the data sets of one time as the blocks of one data set, named so) and its file,
/// relative to the .pvd.
struct PvdDataSet {
  double time_s = 0.0;
  int part = 0;
  std::string name, file;
};

/// The text of a .pvd collection that lists `sets` in order.
std::string pvd_text(const std::vector<PvdDataSet>& sets);

}  // namespace huygens
