// check_summary FILE KEY OP VALUE [TOL] ...
// Asserts values of summary.json: OP is "near" (relative tolerance TOL), "lt" or "gt", or
// "near_in" with VALUE another summary.json whose KEY is the reference (two solvers compared).
// Nested keys use dots (energy.kinetic), array elements their index (rve_stress.0.0). Prints every
// comparison; exit 1 on any failure.
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

int main(int argc, char** argv)
{
  if (argc < 5)
  {
    std::cerr << "usage: check_summary FILE KEY near|lt|gt VALUE [TOL] ...\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in)
  {
    std::cerr << argv[1] << ": cannot open\n";
    return 1;
  }
  const nlohmann::json j = nlohmann::json::parse(in);
  bool ok = true;
  for (int a = 2; a < argc;)
  {
    std::string key = argv[a], op = argv[a + 1];
    auto lookup = [&](const nlohmann::json& doc, const std::string& k)
    {
      const nlohmann::json* node = &doc;
      std::stringstream path(k);
      for (std::string part; std::getline(path, part, '.');)
      {
        if (node->is_array() && !part.empty() &&
            part.find_first_not_of("0123456789") == std::string::npos)
        {
          const std::size_t index = std::stoul(part);
          if (index >= node->size())
            throw std::runtime_error("FAIL " + k + ": index " + part + " out of range");
          node = &(*node)[index];
          continue;
        }
        if (!node->contains(part))
          throw std::runtime_error("FAIL " + k + ": missing");
        node = &(*node)[part];
      }
      // true / false read as 1 / 0 (flags such as damage_reached_band)
      return node->is_boolean() ? double(node->get<bool>()) : node->get<double>();
    };
    double value;
    if (op == "near_in")
    {
      std::ifstream other(argv[a + 2]);
      if (!other)
      {
        std::cerr << argv[a + 2] << ": cannot open\n";
        return 1;
      }
      value = lookup(nlohmann::json::parse(other), key);
      op = "near";
    }
    else
      value = std::stod(argv[a + 2]);
    a += 3;
    double got;
    try
    {
      got = lookup(j, key);
    }
    catch (const std::exception& e)
    {
      std::cerr << e.what() << "\n";
      return 1;
    }
    bool pass;
    if (op == "near")
    {
      const double tol = std::stod(argv[a++]);
      pass = std::abs(got - value) <= tol * std::abs(value);
      std::cout << (pass ? "ok   " : "FAIL ") << key << " = " << got << ", expected " << value
                << " within " << tol * 100 << " % (error " << (got - value) / value * 100
                << " %)\n";
    }
    else
    {
      pass = op == "lt" ? got < value : got > value;
      std::cout << (pass ? "ok   " : "FAIL ") << key << " = " << got << " " << op << " " << value
                << "\n";
    }
    ok = ok && pass;
  }
  return ok ? 0 : 1;
}
