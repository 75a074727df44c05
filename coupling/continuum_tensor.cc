#include "coupling/continuum_tensor.h"
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace dembridge::coupling
{
Voigt6x6 simple_cubic_tensor(const double kn, const double ks, const double d)
{
  Voigt6x6 C{};
  for (int i = 0; i < 3; ++i)
  {
    C[6 * i + i] = kn / d;                   // C11
    C[6 * (i + 3) + (i + 3)] = ks / (2 * d); // C44
  }
  return C;
}

void check_positive_definite(const Voigt6x6& c, const std::string& where)
{
  Eigen::Matrix<double, 6, 6> C;
  double scale = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
    {
      C(i, j) = c[6 * i + j];
      if (!std::isfinite(C(i, j)))
        throw std::runtime_error(where + ": the continuum tensor has a non-finite entry");
      scale = std::max(scale, std::abs(C(i, j)));
    }
  if ((C - C.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale)
    throw std::runtime_error(where + ": the continuum tensor is not symmetric");
  Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(C);
  const bool pd = scale > 0 && llt.info() == Eigen::Success &&
                  llt.matrixL().toDenseMatrix().diagonal().minCoeff() > 1e-6 * std::sqrt(scale);
  if (!pd)
    throw std::runtime_error(where + ": the continuum tensor is not positive definite");
}

Voigt6x6 read_elasticity_json(const std::string& file, const std::string& where)
{
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(where + ": cannot open '" + file + "'");
  nlohmann::json j;
  try
  {
    in >> j;
  }
  catch (const std::exception&)
  {
    throw std::runtime_error(where + ": '" + file + "' is not valid JSON");
  }
  const auto& t = j.contains("stiffness_tensor") ? j["stiffness_tensor"] : nlohmann::json();
  if (!t.is_array() || t.size() != 6)
    throw std::runtime_error(where + ": '" + file + "' has no 6x6 stiffness_tensor");
  Voigt6x6 C{};
  for (int i = 0; i < 6; ++i)
  {
    if (!t[i].is_array() || t[i].size() != 6)
      throw std::runtime_error(where + ": '" + file + "' has no 6x6 stiffness_tensor");
    for (int k = 0; k < 6; ++k)
      C[6 * i + k] = t[i][k].get<double>();
  }
  return C;
}
} // namespace dembridge::coupling
