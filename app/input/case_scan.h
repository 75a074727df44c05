#pragma once
// What deal.II's ParameterHandler accepts silently in a .prm case file and a user most likely
// did not mean: an empty file (it would run every default), a key set twice in one subsection,
// a subsection opened twice at the same level (the later value wins in both), and a name in
// Groups/names or Loads/names without its `subsection Group NAME` / `subsection Load NAME` (the
// group would silently take the defaults). The scan reads the file's lines as deal.II does
// ('#' comments, a trailing '\' continues a line) before deal.II parses it.
#include <set>
#include <string>
#include <vector>

namespace dembridge::app
{
struct CaseScan
{
  int entries = 0;                   ///< "set" lines
  std::set<std::string> subsections; ///< every subsection path, "A/B"
};

/// Scans the text of a .prm case; throws std::runtime_error "NAME:LINE: ..." for a key set twice
/// or a subsection opened twice, and "NAME: ..." for a file that sets nothing.
CaseScan scan_case_text(const std::string& text, const std::string& name);

/// Throws std::runtime_error naming `Groups/names` (or `Loads/names`) for a listed name without
/// its subsection in the file nor in a --set override ("Group NAME/key=value").
void check_named_subsections(const CaseScan& scan, const std::vector<std::string>& overrides,
                             const std::vector<std::string>& names, const std::string& list,
                             const std::string& prefix);
} // namespace dembridge::app
