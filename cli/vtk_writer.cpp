#include "vtk_writer.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>

#include "huygens/common/report.hpp"

namespace huygens {

namespace {

const char* byte_order() { return std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian"; }

std::string file_head(const char* type) {
  return fmt(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"%s\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\">\n", type,
      byte_order());
}

template <class T>
void write_values(AtomicFile& f, std::span<const T> values) {
  f.write(std::as_bytes(values));
}

// Writes count values gen(i), i = 0 ... count - 1, a chunk at a time (no array of count values).
template <class T, class Gen>
void write_generated(AtomicFile& f, std::size_t count, Gen gen) {
  std::vector<T> chunk(std::min<std::size_t>(count, 1 << 14));
  for (std::size_t i0 = 0; i0 < count; i0 += chunk.size()) {
    const std::size_t m = std::min(chunk.size(), count - i0);
    for (std::size_t i = 0; i < m; ++i) chunk[i] = gen(i0 + i);
    write_values<T>(f, std::span<const T>(chunk.data(), m));
  }
}

// The appended data of one file: each array's <DataArray/> element, with its offset into the data,
// and how to write its bytes.
class Appended {
 public:
  /// Adds an array of `tuples` x `comps` values of `type` (`bytes` each) and returns its element.
  std::string add(const char* type, std::size_t value_bytes, const std::string& name, std::size_t comps,
                  std::size_t tuples, std::function<void(AtomicFile&)> write) {
    const std::uint64_t bytes = static_cast<std::uint64_t>(value_bytes * comps * tuples);
    const std::string e =
        fmt("        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%zu\" format=\"appended\" "
            "offset=\"%llu\"/>\n",
            type, name.c_str(), comps, static_cast<unsigned long long>(offset_));
    offset_ += sizeof(std::uint64_t) + bytes;
    blocks_.push_back({bytes, std::move(write)});
    return e;
  }
  /// A float32 array from a field of `tuples` x `k` values, written with `comps` >= k components
  /// (the missing ones zero).
  std::string add_field(const OutputField& f, std::size_t tuples, std::size_t k, std::size_t comps) {
    const std::span<const float> d = f.data;
    if (comps == k) return add("Float32", 4, f.name, comps, tuples, [d](AtomicFile& a) { write_values(a, d); });
    return add("Float32", 4, f.name, comps, tuples, [d, tuples, k, comps](AtomicFile& a) {
      write_generated<float>(a, tuples * comps, [&](std::size_t i) {
        const std::size_t t = i / comps, c = i % comps;
        return c < k ? d[t * k + c] : 0.0f;
      });
    });
  }
  /// Writes the <AppendedData> element and closes the file's XML: "_", then each array's byte
  /// count (UInt64) and bytes.
  void write(AtomicFile& f) const {
    f.write("  <AppendedData encoding=\"raw\">\n   _");
    for (const auto& b : blocks_) {
      write_values(f, std::span<const std::uint64_t>(&b.bytes, 1));
      b.write(f);
    }
    f.write("\n  </AppendedData>\n</VTKFile>\n");
  }

 private:
  struct Block {
    std::uint64_t bytes;
    std::function<void(AtomicFile&)> write;
  };
  std::vector<Block> blocks_;
  std::uint64_t offset_ = 0;
};

// The number of values of a shape.
std::size_t count_of(const std::vector<std::size_t>& shape) {
  std::size_t n = 1;
  for (auto s : shape) n *= s;
  return n;
}

// The components a field of k values per point is written with: a 2-vector as a 3-vector.
std::size_t vtk_components(std::size_t k) { return k == 2 ? 3 : k; }

// The <PointData> element of the fields: the first scalar and the first vector field are its
// active ones (ParaView colours and warps by them).
std::string point_data(const std::vector<std::string>& arrays, const std::vector<std::size_t>& comps,
                       const std::vector<std::string>& names) {
  std::string attrs;
  const auto scalar = std::find(comps.begin(), comps.end(), 1u), vector = std::find(comps.begin(), comps.end(), 3u);
  if (scalar != comps.end()) attrs += " Scalars=\"" + names[scalar - comps.begin()] + "\"";
  if (vector != comps.end()) attrs += " Vectors=\"" + names[vector - comps.begin()] + "\"";
  std::string out = "      <PointData" + attrs + ">\n";
  for (const auto& a : arrays) out += a;
  return out + "      </PointData>\n";
}

}  // namespace

void write_vti(const std::string& path, const std::vector<OutputField>& fields, const VtkGrid& grid, Sync sync) {
  if (fields.empty()) throw std::logic_error("write_vti: no field for " + path);
  const std::size_t rows = fields[0].shape.at(0), cols = fields[0].shape.at(1);
  Appended data;
  std::vector<std::string> arrays, names;
  std::vector<std::size_t> comps;
  for (const auto& f : fields) {
    const std::size_t k = f.shape.size() == 3 ? f.shape[2] : 1;
    if (f.per_particle || f.shape.size() < 2 || f.shape.size() > 3 || f.shape[0] != rows || f.shape[1] != cols ||
        f.data.size() != count_of(f.shape))
      throw std::logic_error("write_vti: the field " + f.name + " is not on the grid of " + fields[0].name);
    names.push_back(f.name);
    comps.push_back(vtk_components(k));
    arrays.push_back(data.add_field(f, rows * cols, k, comps.back()));
  }
  const std::string extent = fmt("0 %zu 0 %zu 0 0", cols - 1, rows - 1);
  std::string xml = file_head("ImageData");
  xml += fmt("  <ImageData WholeExtent=\"%s\" Origin=\"%.17g %.17g 0\" Spacing=\"%.17g %.17g %.17g\">\n",
             extent.c_str(), grid.x0_m, grid.y0_m, grid.dx_m, grid.dx_m, grid.dx_m);
  xml +=
      "    <Piece Extent=\"" + extent + "\">\n" + point_data(arrays, comps, names) + "    </Piece>\n  </ImageData>\n";
  AtomicFile f(path, sync);
  f.write(xml);
  data.write(f);
  f.commit();
}

void write_vtu(const std::string& path, const std::vector<OutputField>& fields, Sync sync) {
  const auto pos = std::find_if(fields.begin(), fields.end(), [](const OutputField& f) { return f.name == "pos"; });
  if (pos == fields.end() || pos->shape.size() != 2 || pos->shape[1] != 3 || pos->data.size() != count_of(pos->shape))
    throw std::logic_error("write_vtu: no (n, 3) field \"pos\" for " + path);
  const std::size_t n = pos->shape[0];
  Appended data;
  std::vector<std::string> arrays, names;
  std::vector<std::size_t> comps;
  for (const auto& f : fields) {
    if (&f == &*pos) continue;
    if (!f.per_particle || f.shape.empty() || f.shape.size() > 2 || f.shape[0] != n ||
        f.data.size() != count_of(f.shape))
      throw std::logic_error("write_vtu: the field " + f.name + " does not hold one value per particle");
    const std::size_t k = f.shape.size() == 2 ? f.shape[1] : 1;
    names.push_back(f.name);
    comps.push_back(vtk_components(k));
    arrays.push_back(data.add_field(f, n, k, comps.back()));
  }
  std::string xml = file_head("UnstructuredGrid");
  xml += fmt("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", n, n);
  xml += point_data(arrays, comps, names);
  xml += "      <Points>\n" + data.add_field(*pos, n, 3, 3) + "      </Points>\n      <Cells>\n";
  // one vertex (VTK_VERTEX = 1) per particle, so ParaView draws every point
  xml += data.add("Int64", 8, "connectivity", 1, n, [n](AtomicFile& a) {
    write_generated<std::int64_t>(a, n, [](std::size_t i) { return static_cast<std::int64_t>(i); });
  });
  xml += data.add("Int64", 8, "offsets", 1, n, [n](AtomicFile& a) {
    write_generated<std::int64_t>(a, n, [](std::size_t i) { return static_cast<std::int64_t>(i + 1); });
  });
  xml += data.add("UInt8", 1, "types", 1, n, [n](AtomicFile& a) {
    write_generated<std::uint8_t>(a, n, [](std::size_t) { return std::uint8_t{1}; });
  });
  xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
  AtomicFile f(path, sync);
  f.write(xml);
  data.write(f);
  f.commit();
}

std::string pvd_text(const std::vector<PvdDataSet>& sets) {
  std::string out = file_head("Collection") + "  <Collection>\n";
  for (const auto& s : sets)
    out += fmt("    <DataSet timestep=\"%.17g\" part=\"%d\" name=\"%s\" file=\"%s\"/>\n", s.time_s, s.part,
               s.name.c_str(), s.file.c_str());
  return out + "  </Collection>\n</VTKFile>\n";
}

}  // namespace huygens
