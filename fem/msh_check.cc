// dembridge::fem — a gmsh .msh text checked before deal.II 9.4's GridIn::read_msh reads it.
// deal.II trusts the counts and node numbers of a file: fuzzing (docs/trust.md, fuzz/findings/)
// found it looping forever on an unclosed section, writing out of bounds on an unknown version
// and crashing on an element node beyond the nodes. Here every section must be closed before the
// next opens, the version must be 2.2 or 4.1, and the sections deal.II sizes its arrays from are
// checked against their own contents:
//   2.2   $Nodes, $Elements: the count line, one node per line, each element line's fields for
//         its type and tags, every element node defined (line by line);
//   4.1   $Entities: the four counts and each entity's physical and bounding lists;
//         $Nodes: blocks "dim tag parametric count" whose counts sum to the declared total, tags
//         then x y z per node (parametric coordinates are refused: deal.II 9.4 does not read
//         them); $Elements: blocks "dim tag type count", each element its tag and the nodes of
//         its type, every node defined, counts summing to the declared total (token by token,
//         as gmsh's format is whitespace-separated: MSH file format 4.1, gmsh manual 10.1).
// A .geo script, an empty file, a file that does not begin with $MeshFormat and binary data are
// refused first (deal.II says only that "the string <//> is not recognized"); text quoted from
// the file is cut to 40 printable characters, never a binary file's bytes.
#include "mesh.h"

#include <filesystem>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace dembridge::fem
{
namespace
{
/// File text fit for a one-line message: bytes outside printable ASCII as '?', at most 40.
std::string shown(const std::string& text)
{
  std::string out;
  for (unsigned char c : text.substr(0, 40))
    out += c >= 0x20 && c < 0x7f ? char(c) : '?';
  return text.size() > 40 ? out + "..." : out;
}

/// A control byte other than blanks: the file is not text (no ASCII .msh holds one).
bool holds_binary(const std::string& line)
{
  for (unsigned char c : line)
    if ((c < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f') || c == 0x7f)
      return true;
  return false;
}

/// Nodes of a gmsh element type (gmsh manual, "MSH file format"; the same numbers in 2.2 and
/// 4.1); 0: a type this check does not know.
int msh_nodes_of_type(long type)
{
  static const int nodes[] = {0, 2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1, 8, 20};
  return type > 0 && type < long(std::size(nodes)) ? nodes[type] : 0;
}

/// The tokens of one 4.1 section with the line each came from, read in order by the checks.
class Tokens
{
public:
  Tokens(const std::string& file, const std::string& section) : file_(file), section_(section) {}
  void add_line(const std::string& line, long n)
  {
    std::istringstream in(line);
    for (std::string t; in >> t;)
      tokens_.emplace_back(std::move(t), n);
  }
  /// The next token as an integer at least @p least; @p what names it in the error.
  long integer(const std::string& what, long least = 0)
  {
    const auto& [text, n] = next(what);
    std::size_t used = 0;
    long v = 0;
    try
    {
      v = std::stol(text, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used != text.size() || v < least)
      fail(n,
           what + " '" + shown(text) + "' is not an integer of at least " + std::to_string(least));
    return v;
  }
  void real(const std::string& what)
  {
    const auto& [text, n] = next(what);
    std::size_t used = 0;
    try
    {
      std::stod(text, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used != text.size())
      fail(n, what + " '" + shown(text) + "' is not a number");
  }
  /// Skips @p count tokens (checked to exist, so a huge count fails at once).
  void skip(long count, const std::string& what)
  {
    if (count > long(tokens_.size() - at_))
      fail(last_line(), what + ": " + std::to_string(count) + " entries declared, " +
                            std::to_string(tokens_.size() - at_) + " values left in the section");
    at_ += std::size_t(count);
  }
  /// Fails unless the section's values are used up.
  void finish()
  {
    if (at_ != tokens_.size())
      fail(tokens_[at_].second,
           "'" + shown(tokens_[at_].first) + "' after the last entry the counts declare");
  }
  long last_line() const
  {
    return tokens_.empty() ? 0 : tokens_[std::min(at_, tokens_.size() - 1)].second;
  }
  [[noreturn]] void fail(long n, const std::string& what) const
  {
    throw std::runtime_error("FEM/Mesh/file: " + file_ + ": line " + std::to_string(n) + ": " +
                             section_ + ": " + what);
  }

private:
  const std::pair<std::string, long>& next(const std::string& what)
  {
    if (at_ == tokens_.size())
      fail(last_line(), "ends before " + what);
    return tokens_[at_++];
  }
  std::string file_, section_;
  std::vector<std::pair<std::string, long>> tokens_;
  std::size_t at_ = 0;
};

void check_msh41_entities(Tokens& t)
{
  const long points = t.integer("the number of points"), curves = t.integer("the number of curves"),
             surfaces = t.integer("the number of surfaces"),
             volumes = t.integer("the number of volumes");
  const char* bounded_by[] = {"", "bounding points", "bounding curves", "bounding surfaces"};
  for (int dim = 0; dim <= 3; ++dim)
    for (long e = 0, n = (dim == 0   ? points
                          : dim == 1 ? curves
                          : dim == 2 ? surfaces
                                     : volumes);
         e < n; ++e)
    {
      t.integer("an entity tag", 1);
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k)
        t.real("a coordinate of the entity's box");
      t.skip(t.integer("the number of physical tags"), "physical tags");
      if (dim > 0)
        t.skip(t.integer(std::string("the number of ") + bounded_by[dim]), bounded_by[dim]);
    }
  t.finish();
}

/// The entity blocks of a 4.1 $Nodes or $Elements section: the header "blocks total min-tag
/// max-tag", then per block its count, whose running sum must stay within the declared total
/// and reach it at the end. @p entry names one entry ("node", "element") in the errors.
class Blocks
{
public:
  Blocks(Tokens& t, const std::string& entry) : t_(t), entry_(entry)
  {
    blocks_ = t.integer("the number of entity blocks");
    total_ = t.integer("the number of " + entry + "s");
    t.integer("the smallest " + entry + " tag");
    t.integer("the largest " + entry + " tag");
  }
  long size() const { return blocks_; }
  /// The next block's number of entries, counted against the declared total.
  long count()
  {
    const long n = t_.integer("the number of " + entry_ + "s in the block");
    listed_ += n;
    if (listed_ > total_)
      t_.fail(t_.last_line(), "the blocks list more " + entry_ + "s than the " +
                                  std::to_string(total_) + " declared");
    return n;
  }
  /// After the last block: every declared entry listed, and nothing after them.
  void finish()
  {
    if (listed_ != total_)
      t_.fail(t_.last_line(), std::to_string(total_) + " " + entry_ + "s declared, " +
                                  std::to_string(listed_) + " listed");
    t_.finish();
  }

private:
  Tokens& t_;
  std::string entry_;
  long blocks_ = 0, total_ = 0, listed_ = 0;
};

void check_msh41_nodes(Tokens& t, std::set<long>& nodes)
{
  Blocks blocks(t, "node");
  for (long b = 0; b < blocks.size(); ++b)
  {
    t.integer("an entity dimension");
    t.integer("an entity tag");
    if (t.integer("the parametric flag") != 0)
      t.fail(t.last_line(), "parametric node coordinates are not read (save without them)");
    const long count = blocks.count();
    for (long k = 0; k < count; ++k)
      if (!nodes.insert(t.integer("a node tag", 1)).second)
        t.fail(t.last_line(), "node tag defined twice");
    for (long k = 0; k < 3 * count; ++k)
      t.real("a node coordinate");
  }
  blocks.finish();
}

void check_msh41_elements(Tokens& t, const std::set<long>& nodes)
{
  Blocks blocks(t, "element");
  for (long b = 0; b < blocks.size(); ++b)
  {
    t.integer("an entity dimension");
    t.integer("an entity tag");
    const long type = t.integer("an element type", 1);
    const int per_element = msh_nodes_of_type(type);
    if (per_element == 0)
      t.fail(t.last_line(), "element type " + std::to_string(type) + " is not read");
    const long count = blocks.count();
    for (long k = 0; k < count; ++k)
    {
      const long tag = t.integer("an element tag", 1);
      for (int j = 0; j < per_element; ++j)
      {
        const long node = t.integer("a node of element " + std::to_string(tag), 1);
        if (!nodes.count(node))
          t.fail(t.last_line(), "element " + std::to_string(tag) + " refers to node " +
                                    std::to_string(node) + ", which $Nodes does not define");
      }
    }
  }
  blocks.finish();
}
} // namespace

void check_msh_sections(std::istream& in, const std::string& file)
{
  std::string line, open, version;
  long open_line = 0, declared = 0, listed = 0;
  std::set<long> nodes;
  std::optional<Tokens> tokens41; // the open 4.1 section's values
  const auto fail = [&](long n, const std::string& what)
  {
    throw std::runtime_error("FEM/Mesh/file: " + file + ": line " + std::to_string(n) + ": " +
                             what);
  };
  const auto checked41 = [&](const std::string& s)
  { return version == "4.1" && (s == "$Entities" || s == "$Nodes" || s == "$Elements"); };
  // why: deal.II says only that "the string <//> is not recognized" for these
  const std::filesystem::path path(file);
  if (path.extension() == ".geo")
    throw std::runtime_error(
        "FEM/Mesh/file: " + file + ": a gmsh geometry script, not a mesh; mesh it first (gmsh -3 " +
        file + " writes " + std::filesystem::path(path).replace_extension(".msh").string() +
        ") and give the .msh file");
  bool begun = false; // a line other than blanks read
  for (long n = 1; std::getline(in, line); ++n)
  {
    if (!begun && line.find_first_not_of(" \t\r\v\f") == std::string::npos)
      continue;
    if (!begun)
    {
      begun = true;
      const auto b = line.find_first_not_of(" \t\r\v\f");
      const std::string first_word = line.substr(b, line.find_first_of(" \t\r\v\f", b) - b);
      // gmsh writes $MeshFormat first (deal.II also reads gmsh 1's $NOD files)
      if (first_word != "$MeshFormat" && first_word != "$NOD")
        fail(n, holds_binary(line)
                    ? "not a gmsh .msh file (binary data where $MeshFormat should begin it)"
                    : "not a gmsh .msh file: it begins with '" + shown(line.substr(b)) +
                          "', not $MeshFormat (a gmsh geometry script is meshed first: gmsh -3 "
                          "FILE.geo writes FILE.msh)");
    }
    // why: deal.II reads the file token by token, so an indented "\t$PhysicalNames" opens a
    // section for it too (and it then looked for the end marker forever: a fuzz_mesh finding)
    const auto first = line.find_first_not_of(" \t\r\v\f");
    line = first == std::string::npos
               ? std::string()
               : line.substr(first, line.find_last_not_of(" \t\r\v\f") - first + 1);
    if (open == "$MeshFormat" && n == open_line + 1)
    {
      // why: deal.II 9.4 reads other version numbers with the wrong layout and writes out of
      // bounds on some (fuzz/findings/mesh_deal_ii_*.msh)
      version = line.substr(0, line.find(' '));
      if (version != "2.2" && version != "4.1")
        fail(n, "gmsh format version '" + shown(version) +
                    "' is not read (2.2 or 4.1: gmsh -format msh22 or msh41)");
      if (line.find(" 0 ") == std::string::npos)
        fail(n, "a binary .msh file; only ASCII ones are read (convert it: gmsh " + file +
                    " -save -format msh41 -o ASCII.msh)");
    }
    if (holds_binary(line))
      fail(n, "binary data in a .msh file read as ASCII (a damaged file, or a binary mesh "
              "with an ASCII header: gmsh FILE -save -format msh41 -o ASCII.msh writes ASCII)");
    if (tokens41 && (line.empty() || line[0] != '$'))
      tokens41->add_line(line, n);
    // Version 2.2 nodes and elements: counts, fields and node numbers checked, since deal.II
    // 9.4 reads an element's node numbers unchecked (a number beyond the nodes crashed it).
    if (version == "2.2" && (open == "$Nodes" || open == "$Elements") && !line.empty() &&
        line[0] != '$')
    {
      std::istringstream fields(line);
      std::vector<long> v;
      for (long x; fields >> x;)
        v.push_back(x);
      if (n == open_line + 1)
      {
        if (v.size() != 1 || v[0] < 0)
          fail(n, open + " must begin with its number of entries");
        declared = v[0], listed = 0;
        continue;
      }
      ++listed;
      if (open == "$Nodes")
      {
        if (v.empty())
          fail(n, "a node line must begin with the node's number");
        nodes.insert(v[0]);
      }
      else
      {
        const int count = v.size() >= 3 ? msh_nodes_of_type(v[1]) : 0;
        if (count == 0 || v[2] < 0 || long(v.size()) != 3 + v[2] + count)
          fail(n, "element line with a wrong number of fields for its type and tags");
        for (std::size_t k = 3 + v[2]; k < v.size(); ++k)
          if (!nodes.count(v[k]))
            fail(n, "element " + std::to_string(v[0]) + " refers to node " + std::to_string(v[k]) +
                        ", which $Nodes does not define");
      }
    }
    if (version == "2.2" && (open == "$Nodes" || open == "$Elements") &&
        line == "$End" + open.substr(1) && listed != declared)
      fail(n, open + " declares " + std::to_string(declared) + " entries and lists " +
                  std::to_string(listed));
    if (line.empty() || line[0] != '$')
      continue;
    if (line.rfind("$End", 0) == 0)
    {
      if (open.empty() || line != "$End" + open.substr(1))
        throw std::runtime_error("FEM/Mesh/file: " + file + ": line " + std::to_string(n) + ": '" +
                                 shown(line) + "' closes no open section" +
                                 (open.empty() ? "" : " (" + open + " is open)"));
      if (tokens41)
      {
        if (open == "$Entities")
          check_msh41_entities(*tokens41);
        else if (open == "$Nodes")
          check_msh41_nodes(*tokens41, nodes);
        else
          check_msh41_elements(*tokens41, nodes);
        tokens41.reset();
      }
      open.clear();
    }
    else if (!open.empty())
      throw std::runtime_error("FEM/Mesh/file: " + file + ": " + open + " (line " +
                               std::to_string(open_line) + ") is not closed by $End" +
                               open.substr(1) + " before " + shown(line) + " (line " +
                               std::to_string(n) + ")");
    else
    {
      open = line, open_line = n;
      if (checked41(open))
        tokens41.emplace(file, open);
    }
  }
  if (!begun)
    throw std::runtime_error("FEM/Mesh/file: " + file +
                             ": the file is empty (a gmsh .msh file begins with $MeshFormat)");
  if (!open.empty())
    throw std::runtime_error("FEM/Mesh/file: " + file + ": " + open + " (line " +
                             std::to_string(open_line) + ") is not closed by $End" +
                             open.substr(1));
}
} // namespace dembridge::fem
