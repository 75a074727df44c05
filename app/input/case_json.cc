#include "app/input/case_json.h"
#include "app/input/case_file.h"
#include <algorithm>
#include <regex>
#include <set>
#include <stdexcept>
#include <vector>

namespace dembridge::app
{
namespace
{
using Json = nlohmann::ordered_json;

std::string join(const std::vector<std::string>& path, const std::string& last = "")
{
  std::string s;
  for (const auto& p : path)
    s += (s.empty() ? "" : "/") + p;
  if (!last.empty())
    s += (s.empty() ? "" : "/") + last;
  return s;
}

/// Text fit for a one-line message: control bytes and bytes outside ASCII as '?', cut at 80.
std::string printable(const std::string& s)
{
  std::string out;
  for (unsigned char c : s.substr(0, 80))
    out += c >= 0x20 && c < 0x7f ? char(c) : '?';
  return s.size() > 80 ? out + "..." : out;
}

/// Builds the case's tree with every value as text, refusing what a case file cannot mean: a
/// key given twice in one object (nlohmann and deal.II keep the last silently), a list, a null.
class CaseSax final : public nlohmann::json_sax<Json>
{
public:
  CaseSax(const std::string& text, const std::string& file) : text_(text), file_(file) {}
  Json tree;
  int values = 0;

  bool null() override
  {
    fail_at_key("null is no value (give a string, a number or true/false)");
    return false;
  }
  bool boolean(bool v) override { return value(v ? "true" : "false"); }
  bool number_integer(number_integer_t v) override { return value(std::to_string(v)); }
  bool number_unsigned(number_unsigned_t v) override { return value(std::to_string(v)); }
  // the number as written (deal.II reads the text; 1e9 stays 1e9)
  bool number_float(number_float_t, const string_t& text) override { return value(text); }
  bool string(string_t& s) override { return value(s); }
  bool binary(binary_t&) override { return false; } // only binary formats produce these

  bool start_object(std::size_t) override
  {
    if (open_.empty())
    {
      if (!tree.is_null())
        fail("a case file holds one JSON object");
      tree = Json::object();
      open_.push_back({&tree, {}, {}, {}});
      return true;
    }
    Frame& parent = open_.back();
    // why: every frame holds its path, and no case nests subsections this deep
    if (open_.size() > 16)
      fail_at_key("nested deeper than any subsection (16 levels)");
    if (parent.repeated)
      fail("subsection '" + printable(join(parent.path, parent.key)) +
           "' is given twice (JSON would keep only the last; give each subsection once)");
    Json& child = (*parent.node)[parent.key] = Json::object();
    auto path = parent.path;
    path.push_back(parent.key);
    open_.push_back({&child, path, {}, {}});
    return true;
  }
  bool key(string_t& k) override
  {
    Frame& f = open_.back();
    f.repeated = !f.keys.insert(k).second;
    f.key = k;
    return true;
  }
  bool end_object() override
  {
    open_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override
  {
    fail_at_key("a JSON list is no value; write the list as one string, as in a .prm "
                "(\"0, 0, -1\")");
    return false;
  }
  bool end_array() override { return true; }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& e) override
  {
    const std::string at = file_ + ":" + std::to_string(line_of(position)) + ": ";
    // why: JSON has no comments; nlohmann reads '/' as an invalid literal
    if (last_token.find('/') != std::string::npos)
      throw std::runtime_error(at + "JSON has no comments ('//' or '/* */'); remove them, or "
                                    "write the case as a .prm file, where '#' starts a comment");
    // "[json.exception.parse_error.101] parse error at line 2, column 3: syntax error ..."
    std::string what = std::regex_replace(e.what(),
                                          std::regex("^\\[json\\.exception\\.[^\\]]*\\] "
                                                     "(parse error at line \\d+, "
                                                     "column \\d+: )?"),
                                          "");
    throw std::runtime_error(at + printable(what));
  }

private:
  struct Frame
  {
    Json* node;
    std::vector<std::string> path; ///< keys from the top to this object
    std::set<std::string> keys;
    std::string key; ///< the key whose value comes next
    bool repeated = false;
  };

  bool value(const std::string& v)
  {
    if (open_.empty())
      fail("a case file is a JSON object ({\"Mode\": \"dem\", \"Particles\": {...}, ...})");
    Frame& f = open_.back();
    if (f.repeated)
      fail(printable(join(f.path, f.key)) +
           " is set twice (JSON would keep only the last value; give each entry once)");
    (*f.node)[f.key] = v;
    ++values;
    return true;
  }
  [[noreturn]] void fail(const std::string& what) const
  {
    throw std::runtime_error(file_ + ": " + what);
  }
  [[noreturn]] void fail_at_key(const std::string& what) const
  {
    if (open_.empty())
      fail(what);
    fail(printable(join(open_.back().path, open_.back().key)) + ": " + what);
  }
  long line_of(std::size_t position) const
  {
    const auto end = text_.begin() + long(std::min(position, text_.size()));
    return 1 + std::count(text_.begin(), end, '\n');
  }

  const std::string& text_;
  std::string file_;
  std::vector<Frame> open_;
};

/// The message of a deal.II exception without its frame: "The string <x> does not match the
/// given pattern <[Double 0...MAX_DOUBLE]>." -> "the value 'x' does not match [Double ...]".
std::string pattern_message(const std::string& what)
{
  std::smatch m;
  const std::string text = one_line(what);
  if (std::regex_search(text, m,
                        std::regex("The string <([^\\n]*)> does not match the given "
                                   "pattern <([^\\n]*)>\\.")))
    return "the value '" + printable(m[1]) + "' does not match " + m[2].str();
  return printable(text);
}

void set_entries(dealii::ParameterHandler& prm, const Json& object, std::vector<std::string>& path,
                 const std::string& file, bool skip_undefined)
{
  for (const auto& [key, value] : object.items())
  {
    const std::string where = file + ": " + printable(join(path, key));
    std::string text;
    if (value.is_object())
    {
      if (prm.subsection_path_exists({key}))
      {
        prm.enter_subsection(key);
        path.push_back(key);
        set_entries(prm, value, path, file, skip_undefined);
        path.pop_back();
        prm.leave_subsection();
        continue;
      }
      // deal.II's long form of an entry: {"value": ..., "documentation": ..., ...}
      if (!value.contains("value") || !value["value"].is_string())
      {
        if (skip_undefined)
          continue;
        throw std::runtime_error(where + ": no such subsection" +
                                 (path.empty() ? "" : " in '" + join(path) + "'") +
                                 " (dembridge print-parameters lists them)");
      }
      text = value["value"].get<std::string>();
    }
    else if (prm.subsection_path_exists({key}))
      throw std::runtime_error(
          where + ": a subsection, given a value (write it as an object: {\"key\": value, ...})");
    else
      text = value.get<std::string>();
    // as deal.II's .prm reader does: blanks around a value are not part of it
    const auto b = text.find_first_not_of(" \t"), e = text.find_last_not_of(" \t");
    text = b == std::string::npos ? std::string() : text.substr(b, e - b + 1);
    try
    {
      prm.set(key, text);
    }
    catch (const dealii::ParameterHandler::ExcEntryUndeclared&)
    {
      if (skip_undefined)
        continue;
      throw std::runtime_error(where + ": no such parameter" +
                               (path.empty() ? "" : " in '" + join(path) + "'") +
                               " (dembridge print-parameters lists them)");
    }
    catch (const dealii::ParameterHandler::ExcValueDoesNotMatchPattern& e)
    {
      throw std::runtime_error(where + ": " + pattern_message(e.what()));
    }
  }
}
} // namespace

JsonCase parse_json_case(const std::string& text, const std::string& file)
{
  CaseSax sax(text, file);
  Json::sax_parse(text, &sax, Json::input_format_t::json, /*strict=*/true,
                  /*ignore_comments=*/false);
  JsonCase c;
  c.tree = std::move(sax.tree);
  c.scan.entries = sax.values;
  if (!c.tree.is_object())
    throw std::runtime_error(file + ": the file is empty (a case file is a JSON object)");
  for (const auto& [key, value] : c.tree.items())
    if (value.is_object())
      c.scan.subsections.insert(key);
  if (c.scan.entries == 0)
    throw std::runtime_error(file + ": the case file sets no parameter (it would run every "
                                    "default); see dembridge print-parameters");
  return c;
}

void set_json_case(dealii::ParameterHandler& prm, const JsonCase& json, const std::string& file,
                   bool skip_undefined)
{
  std::vector<std::string> path;
  set_entries(prm, json.tree, path, file, skip_undefined);
}
} // namespace dembridge::app
