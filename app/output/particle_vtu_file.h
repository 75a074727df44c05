#pragma once
// A VTK XML unstructured grid (.vtu) of vertices or lines, written directly: deal.II's
// DataOutBase writes every array as Float32 point data, which loses integer ids above 2^24,
// cannot put a bond's quantities on its line cell, and has no place for the group names. Here
// points are Float64, integers stay integers (Int32, Int64, UInt8, UInt32), arrays go on points
// or cells, the time and step are field data (TIME, CYCLE, as ParaView expects) and so can be a
// list of names (a string array). Data are inline base64 ("binary", UInt64 headers), the form
// VTK itself writes; ParaView reads them (tests/app/paraview_reads.py checks types and names).
#include "dem/core/types.h"
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dembridge::app
{
class VtuFile
{
public:
  enum class Cells
  {
    vertices, ///< one vertex cell per point
    lines     ///< line cells between point pairs (set by lines())
  };
  VtuFile(const std::vector<dem::Vec3>& points, Cells cells);
  /// Line cells: point index pairs (Cells::lines).
  void lines(const std::vector<std::int64_t>& pairs);

  // Arrays on the points or on the cells; vectors (3 components) and tensors (9, row-major).
  void point_data(const std::string& name, const std::vector<double>& v, int components = 1);
  void point_data(const std::string& name, const std::vector<std::int32_t>& v);
  void point_data(const std::string& name, const std::vector<std::int64_t>& v);
  void point_data(const std::string& name, const std::vector<std::uint32_t>& v);
  void cell_data(const std::string& name, const std::vector<double>& v, int components = 1);
  void cell_data(const std::string& name, const std::vector<std::uint8_t>& v);
  void cell_data(const std::string& name, const std::vector<std::int64_t>& v);
  /// A list of names as field data (a VTK string array).
  void field_strings(const std::string& name, const std::vector<std::string>& values);

  /// Writes the file (time and step as field data TIME and CYCLE); throws naming the file.
  void write(const std::filesystem::path& file, double time, long step) const;
  /// Writes a ParaView record (.pvtu) of @p pieces, files like this one (the same point and
  /// cell arrays); throws naming the file.
  void write_pvtu(const std::filesystem::path& file, const std::vector<std::string>& pieces) const;

private:
  std::size_t n_points_, n_cells_;
  std::string points_, cells_, point_data_, cell_data_, field_data_;
  std::string point_arrays_, cell_arrays_; ///< their PDataArray lines (write_pvtu)
};

/// A ParaView collection (.pvd) of (time, file) entries; unlike deal.II's it carries no date, so
/// two runs of the same case write the same bytes.
void write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& entries);

/// Base64 of @p bytes (RFC 4648, with padding).
std::string base64(const std::string& bytes);
} // namespace dembridge::app
