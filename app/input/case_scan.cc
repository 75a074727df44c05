#include "app/input/case_scan.h"
#include <map>
#include <sstream>
#include <stdexcept>

namespace dembridge::app
{
namespace
{
std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

/// Collapses runs of blanks to one blank, as deal.II does for entry and section names.
std::string collapse(const std::string& s)
{
  std::string out;
  for (char c : trim(s))
    if (!((c == ' ' || c == '\t') && !out.empty() && out.back() == ' '))
      out += c == '\t' ? ' ' : c;
  return out;
}

std::string join(const std::vector<std::string>& path)
{
  std::string s;
  for (const auto& p : path)
    s += (s.empty() ? "" : "/") + p;
  return s;
}
} // namespace

CaseScan scan_case_text(const std::string& text, const std::string& name)
{
  CaseScan scan;
  std::istringstream in(text);
  std::vector<std::string> path;
  std::map<std::string, int> first_line; // "key:A/B/x" or "sub:A/B" -> line
  std::string line;
  int lineno = 0;
  while (std::getline(in, line))
  {
    const int first = ++lineno;
    // deal.II joins a line ending in '\' with the next one (before comments are removed)
    while (!trim(line).empty() && trim(line).back() == '\\')
    {
      std::string next;
      if (!std::getline(in, next))
        break;
      ++lineno;
      line = trim(line);
      line.pop_back();
      line += " " + next;
    }
    if (const auto hash = line.find('#'); hash != std::string::npos)
      line.erase(hash);
    const std::string t = collapse(line);
    if (t.rfind("subsection ", 0) == 0)
    {
      path.push_back(collapse(t.substr(11)));
      const std::string key = "sub:" + join(path);
      if (const auto seen = first_line.find(key); seen != first_line.end())
        throw std::runtime_error(name + ":" + std::to_string(first) + ": subsection '" +
                                 join(path) + "' is opened twice (first on line " +
                                 std::to_string(seen->second) +
                                 "); deal.II would merge the two, the later values winning");
      first_line[key] = first;
      scan.subsections.insert(join(path));
    }
    else if (t == "end")
    {
      if (!path.empty())
        path.pop_back();
    }
    else if (t.rfind("set ", 0) == 0)
    {
      ++scan.entries;
      const auto eq = t.find('=');
      if (eq == std::string::npos)
        continue; // deal.II reports the malformed line
      auto full = path;
      full.push_back(collapse(t.substr(4, eq - 4)));
      const std::string key = "key:" + join(full);
      if (const auto seen = first_line.find(key); seen != first_line.end())
        throw std::runtime_error(name + ":" + std::to_string(first) + ": " + join(full) +
                                 " is set twice (first on line " + std::to_string(seen->second) +
                                 "); only one value can hold");
      first_line[key] = first;
    }
  }
  if (scan.entries == 0)
    throw std::runtime_error(name + ": the case file sets no parameter (it would run every "
                                    "default); see dembridge print-parameters");
  return scan;
}

void check_named_subsections(const CaseScan& scan, const std::vector<std::string>& overrides,
                             const std::vector<std::string>& names, const std::string& list,
                             const std::string& prefix)
{
  for (const auto& n : names)
  {
    const std::string section = prefix + " " + n;
    if (scan.subsections.count(section))
      continue;
    bool overridden = false;
    for (const auto& o : overrides)
      overridden = overridden || collapse(o.substr(0, o.find('/'))) == section;
    if (!overridden)
      throw std::runtime_error(list + ": '" + n + "' is listed but the file has no 'subsection " +
                               section + "'");
  }
}
} // namespace dembridge::app
