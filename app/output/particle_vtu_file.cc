#include "app/output/particle_vtu_file.h"
#include "dem/core/output_file.h"
#include <bit>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace dembridge::app
{
namespace
{
template <class T> const char* vtk_type();
template <> const char* vtk_type<double>()
{
  return "Float64";
}
template <> const char* vtk_type<std::int32_t>()
{
  return "Int32";
}
template <> const char* vtk_type<std::int64_t>()
{
  return "Int64";
}
template <> const char* vtk_type<std::uint8_t>()
{
  return "UInt8";
}
template <> const char* vtk_type<std::uint32_t>()
{
  return "UInt32";
}

/// One DataArray: the UInt64 byte count and the little-endian values, base64 in one stream.
template <class T>
std::string data_array(const std::string& name, const T* values, std::size_t n, int components)
{
  static_assert(std::endian::native == std::endian::little, "the files say LittleEndian");
  const std::uint64_t bytes = n * sizeof(T);
  std::string raw(sizeof bytes + bytes, '\0');
  std::memcpy(raw.data(), &bytes, sizeof bytes);
  if (bytes > 0)
    std::memcpy(raw.data() + sizeof bytes, values, bytes);
  std::string xml = "<DataArray type=\"" + std::string(vtk_type<T>()) + "\"";
  if (!name.empty())
    xml += " Name=\"" + name + "\"";
  if (components > 1)
    xml += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  xml += " format=\"binary\">\n" + base64(raw) + "\n</DataArray>\n";
  return xml;
}

template <class T>
std::string data_array(const std::string& name, const std::vector<T>& v, int components,
                       std::size_t tuples)
{
  if (v.size() != tuples * std::size_t(components))
    throw std::logic_error("VtuFile: array '" + name + "' has " + std::to_string(v.size()) +
                           " values for " + std::to_string(tuples) + " tuples");
  return data_array(name, v.data(), v.size(), components);
}
/// The line of a .pvtu record that announces an array of the pieces.
template <class T> std::string p_data_array(const std::string& name, int components)
{
  std::string xml = "<PDataArray type=\"" + std::string(vtk_type<T>()) + "\"";
  if (!name.empty())
    xml += " Name=\"" + name + "\"";
  if (components > 1)
    xml += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  return xml + "/>\n";
}
} // namespace

std::string base64(const std::string& bytes)
{
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t k = 0;
  for (; k + 2 < bytes.size(); k += 3)
  {
    const auto a = std::uint8_t(bytes[k]), b = std::uint8_t(bytes[k + 1]),
               c = std::uint8_t(bytes[k + 2]);
    out += table[a >> 2];
    out += table[((a & 3) << 4) | (b >> 4)];
    out += table[((b & 15) << 2) | (c >> 6)];
    out += table[c & 63];
  }
  if (k < bytes.size())
  {
    const auto a = std::uint8_t(bytes[k]);
    const auto b = k + 1 < bytes.size() ? std::uint8_t(bytes[k + 1]) : std::uint8_t(0);
    out += table[a >> 2];
    out += table[((a & 3) << 4) | (b >> 4)];
    out += k + 1 < bytes.size() ? table[(b & 15) << 2] : '=';
    out += '=';
  }
  return out;
}

VtuFile::VtuFile(const std::vector<dem::Vec3>& points, Cells cells)
    : n_points_(points.size()), n_cells_(0)
{
  static_assert(sizeof(dem::Vec3) == 3 * sizeof(double));
  points_ = data_array("", points.empty() ? nullptr : points[0].data(), 3 * points.size(), 3);
  if (cells == Cells::vertices)
  {
    std::vector<std::int64_t> connectivity(n_points_), offsets(n_points_);
    for (std::size_t i = 0; i < n_points_; ++i)
      connectivity[i] = std::int64_t(i), offsets[i] = std::int64_t(i + 1);
    const std::vector<std::uint8_t> types(n_points_, 1); // VTK_VERTEX
    n_cells_ = n_points_;
    cells_ = data_array("connectivity", connectivity, 1, n_cells_) +
             data_array("offsets", offsets, 1, n_cells_) + data_array("types", types, 1, n_cells_);
  }
}

void VtuFile::lines(const std::vector<std::int64_t>& pairs)
{
  n_cells_ = pairs.size() / 2;
  std::vector<std::int64_t> offsets(n_cells_);
  for (std::size_t c = 0; c < n_cells_; ++c)
    offsets[c] = std::int64_t(2 * c + 2);
  for (std::int64_t i : pairs)
    if (i < 0 || std::size_t(i) >= n_points_)
      throw std::logic_error("VtuFile: a line names a point outside the file");
  const std::vector<std::uint8_t> types(n_cells_, 3); // VTK_LINE
  cells_ = data_array("connectivity", pairs, 1, pairs.size()) +
           data_array("offsets", offsets, 1, n_cells_) + data_array("types", types, 1, n_cells_);
}

void VtuFile::point_data(const std::string& name, const std::vector<double>& v, int components)
{
  point_data_ += data_array(name, v, components, n_points_);
  point_arrays_ += p_data_array<double>(name, components);
}
void VtuFile::point_data(const std::string& name, const std::vector<std::int32_t>& v)
{
  point_data_ += data_array(name, v, 1, n_points_);
  point_arrays_ += p_data_array<std::int32_t>(name, 1);
}
void VtuFile::point_data(const std::string& name, const std::vector<std::int64_t>& v)
{
  point_data_ += data_array(name, v, 1, n_points_);
  point_arrays_ += p_data_array<std::int64_t>(name, 1);
}
void VtuFile::point_data(const std::string& name, const std::vector<std::uint32_t>& v)
{
  point_data_ += data_array(name, v, 1, n_points_);
  point_arrays_ += p_data_array<std::uint32_t>(name, 1);
}
void VtuFile::cell_data(const std::string& name, const std::vector<double>& v, int components)
{
  cell_data_ += data_array(name, v, components, n_cells_);
  cell_arrays_ += p_data_array<double>(name, components);
}
void VtuFile::cell_data(const std::string& name, const std::vector<std::uint8_t>& v)
{
  cell_data_ += data_array(name, v, 1, n_cells_);
  cell_arrays_ += p_data_array<std::uint8_t>(name, 1);
}
void VtuFile::cell_data(const std::string& name, const std::vector<std::int64_t>& v)
{
  cell_data_ += data_array(name, v, 1, n_cells_);
  cell_arrays_ += p_data_array<std::int64_t>(name, 1);
}

void VtuFile::field_strings(const std::string& name, const std::vector<std::string>& values)
{
  // VTK's ASCII string arrays: each string as its character codes, ended by a 0
  std::string codes;
  for (const auto& s : values)
  {
    for (unsigned char c : s)
      codes += std::to_string(int(c)) + " ";
    codes += "0\n";
  }
  field_data_ += "<Array type=\"String\" Name=\"" + name + "\" NumberOfTuples=\"" +
                 std::to_string(values.size()) + "\" format=\"ascii\">\n" + codes + "</Array>\n";
}

void write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& entries)
{
  dem::OutputFile out(file); // failures name the file and the reason
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
         "byte_order=\"LittleEndian\">\n<Collection>\n";
  for (const auto& [time, name] : entries)
  {
    char t[64];
    std::snprintf(t, sizeof t, "%.17g", time);
    out << "  <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << name << "\"/>\n";
  }
  out << "</Collection>\n</VTKFile>\n";
  out.close();
}

void VtuFile::write(const std::filesystem::path& file, double time, long step) const
{
  dem::OutputFile out(file, std::ios::binary | std::ios::trunc);
  char t[64];
  std::snprintf(t, sizeof t, "%.17g", time);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<UnstructuredGrid>\n<FieldData>\n"
         "<DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">"
      << t
      << "</DataArray>\n<DataArray type=\"Int64\" Name=\"CYCLE\" NumberOfTuples=\"1\" "
         "format=\"ascii\">"
      << step << "</DataArray>\n"
      << field_data_ << "</FieldData>\n<Piece NumberOfPoints=\"" << n_points_
      << "\" NumberOfCells=\"" << n_cells_ << "\">\n<Points>\n"
      << points_ << "</Points>\n<Cells>\n"
      << cells_ << "</Cells>\n<PointData>\n"
      << point_data_ << "</PointData>\n<CellData>\n"
      << cell_data_ << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  out.close();
}

void VtuFile::write_pvtu(const std::filesystem::path& file,
                         const std::vector<std::string>& pieces) const
{
  dem::OutputFile out(file); // failures name the file and the reason
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints>\n"
      << p_data_array<double>("", 3) << "</PPoints>\n<PPointData>\n"
      << point_arrays_ << "</PPointData>\n<PCellData>\n"
      << cell_arrays_ << "</PCellData>\n";
  for (const auto& piece : pieces)
    out << "<Piece Source=\"" << piece << "\"/>\n";
  out << "</PUnstructuredGrid>\n</VTKFile>\n";
  out.close();
}
} // namespace dembridge::app
