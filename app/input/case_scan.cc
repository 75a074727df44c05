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

void for_each_prm_line(const std::string& text, const std::function<void(const PrmLine&)>& visit)
{
  std::istringstream in(text);
  std::vector<std::string> path;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line))
  {
    PrmLine l;
    l.line = ++lineno;
    l.text = line;
    // deal.II joins a line ending in '\' with the next one (before comments are removed)
    while (!trim(line).empty() && trim(line).back() == '\\')
    {
      std::string next;
      if (!std::getline(in, next))
        break;
      ++lineno;
      l.text += "\n" + next;
      line = trim(line);
      line.pop_back();
      line += " " + next;
    }
    if (const auto hash = line.find('#'); hash != std::string::npos)
      line.erase(hash);
    const std::string t = collapse(line);
    if (t.rfind("subsection ", 0) == 0)
    {
      l.kind = PrmLine::Kind::subsection;
      path.push_back(collapse(t.substr(11)));
      l.path = path;
    }
    else if (t == "end")
    {
      l.kind = PrmLine::Kind::end;
      l.path = path;
      if (!path.empty())
        path.pop_back();
    }
    else if (t.rfind("set ", 0) == 0)
    {
      l.kind = PrmLine::Kind::set;
      l.path = path;
      const std::string kept = trim(line);
      const auto eq = kept.find('=');
      l.well_formed = eq != std::string::npos;
      if (l.well_formed)
      {
        l.key = collapse(kept.substr(4, eq - 4));
        l.value = trim(kept.substr(eq + 1));
      }
    }
    else
      l.path = path;
    visit(l);
  }
}

std::string
rewrite_prm_lines(const std::string& text,
                  const std::function<std::optional<std::string>(const PrmLine&)>& rewrite)
{
  std::ostringstream out;
  for_each_prm_line(text,
                    [&](const PrmLine& l)
                    {
                      if (const auto kept = rewrite(l))
                        out << *kept << '\n';
                    });
  return out.str();
}

std::map<std::string, std::string> prm_entries(const std::string& text)
{
  std::map<std::string, std::string> out;
  for_each_prm_line(text,
                    [&](const PrmLine& l)
                    {
                      if (l.kind == PrmLine::Kind::set && l.well_formed)
                        out[join(l.path) + (l.path.empty() ? "" : "/") + l.key] = l.value;
                    });
  return out;
}

CaseScan scan_case_text(const std::string& text, const std::string& name)
{
  CaseScan scan;
  std::map<std::string, int> first_line; // "key:A/B/x" or "sub:A/B" -> line
  for_each_prm_line(
      text,
      [&](const PrmLine& l)
      {
        if (l.kind == PrmLine::Kind::subsection)
        {
          const std::string key = "sub:" + join(l.path);
          if (const auto seen = first_line.find(key); seen != first_line.end())
            throw std::runtime_error(name + ":" + std::to_string(l.line) + ": subsection '" +
                                     join(l.path) + "' is opened twice (first on line " +
                                     std::to_string(seen->second) +
                                     "); deal.II would merge the two, the later values winning");
          first_line[key] = l.line;
          scan.subsections.insert(join(l.path));
        }
        else if (l.kind == PrmLine::Kind::set)
        {
          ++scan.entries;
          if (!l.well_formed)
            return; // deal.II reports the malformed line
          auto full = l.path;
          full.push_back(l.key);
          const std::string key = "key:" + join(full);
          if (const auto seen = first_line.find(key); seen != first_line.end())
            throw std::runtime_error(name + ":" + std::to_string(l.line) + ": " + join(full) +
                                     " is set twice (first on line " +
                                     std::to_string(seen->second) + "); only one value can hold");
          first_line[key] = l.line;
        }
      });
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
