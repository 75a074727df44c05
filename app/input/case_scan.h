#pragma once
// What deal.II's ParameterHandler accepts silently in a .prm case file and a user most likely
// did not mean: an empty file (it would run every default), a key set twice in one subsection,
// a subsection opened twice at the same level (the later value wins in both), and a name in
// Groups/names or Loads/names without its `subsection Group NAME` / `subsection Load NAME` (the
// group would silently take the defaults). The scan reads the file's lines as deal.II does
// ('#' comments, a trailing '\' continues a line) before deal.II parses it.
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace dembridge::app
{
/// One logical line of a .prm text as deal.II reads it: a trailing '\' joins the next line,
/// '#' starts a comment, blanks in subsection and key names collapse to one.
struct PrmLine
{
  enum class Kind
  {
    other, ///< blank, comment, or text deal.II would refuse
    subsection,
    end,
    set
  };
  Kind kind = Kind::other;
  /// subsection: the path with the one it opens; end: the path with the one it closes; set and
  /// other: the enclosing subsections
  std::vector<std::string> path;
  bool well_formed = false; ///< set: has '=' (deal.II reports a set line without one)
  std::string key;          ///< set: the entry's name
  std::string value;        ///< set: the value, trimmed (not collapsed: deal.II keeps its blanks)
  int line = 0;             ///< the first physical line, 1-based
  std::string text;         ///< the physical line(s) as written, joined by '\n'
};

/// Calls @p visit for every logical line of @p text, in order. The one reader of .prm text in
/// app/ besides deal.II's own: the checks below, provenance's rewrite of file paths, the
/// checkpoint's comparison of case files.
void for_each_prm_line(const std::string& text, const std::function<void(const PrmLine&)>& visit);

/// @p text with each logical line replaced by what @p rewrite returns for it (its `text` to keep
/// it, an empty optional to drop it); lines end in '\n'.
std::string
rewrite_prm_lines(const std::string& text,
                  const std::function<std::optional<std::string>(const PrmLine&)>& rewrite);

/// "Section/Sub/key" -> value of every set line.
std::map<std::string, std::string> prm_entries(const std::string& text);

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
