#pragma once
// dembridge verify: a DEM specimen run against the finite-element model of the same specimen.
// One command runs the DEM case (or reads a finished run), derives the FE problem
// (geometry = the specimen's extent, the same supports and load, isotropic E and nu from a
// uniaxial DEM test), runs it, and reports side by side: deflections, support reactions,
// strain energy and the layer-averaged stress through the depth (DEM eq. 54 slab averages vs FE
// averages over the same slabs). Outputs in the output folder D:
//   D/dem/       the DEM run (summary.json, history/ParaView files)
//   D/fem/       case.prm (the derived FE case, runnable by `dembridge run`), summary.json, .vtu
//   D/summary.json, D/comparison.csv, D/comparison.png (matplotlib via python3)
// Every input is checked before anything is written; results are written under temporary names
// and renamed, summary.json last, so a failed verification leaves no summary.json.
#include "dem/measurements/elasticity_tensor.h"
#include <deal.II/base/parameter_handler.h>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Changes the working directory for its lifetime (case-relative paths).
class WorkingDirectory
{
public:
  explicit WorkingDirectory(const std::filesystem::path& dir)
      : previous_(std::filesystem::current_path())
  {
    std::filesystem::current_path(dir);
  }
  ~WorkingDirectory() { std::filesystem::current_path(previous_); }
  WorkingDirectory(const WorkingDirectory&) = delete;
  WorkingDirectory& operator=(const WorkingDirectory&) = delete;

private:
  std::filesystem::path previous_;
};

struct VerifyOptions
{
  std::string case_file;
  std::vector<std::string> overrides; ///< --set "Section/Key=value"
  std::string output_dir;             ///< empty: output/verify_<case stem>
  std::string material_from;          ///< uniaxial DEM summary.json giving E and nu
  std::optional<double> youngs_modulus, poisson_ratio;
  std::optional<double> shear_modulus; ///< cubic FE material with C44 = G (e.g. a lattice's G)
  std::string dem_run; ///< folder of a finished DEM run of the same case (skip the DEM run)
  bool plot = true;
  /// FE material: the stiffness tensor measured on the case's own packing
  /// (dem/measurements/elasticity_tensor.h, as `dembridge elasticity` measures it)
  bool measured_tensor = false;
};

/// Constants of the FE material and where they came from: isotropic (E, nu), or with a shear
/// modulus G > 0 cubic along the axes (uniaxial E and nu along every axis, C44 = G), or a full
/// 6x6 stiffness tensor (a packing's measured one; E and nu then only describe it: E_x and the
/// mean of its six Poisson's ratios).
struct ElasticConstants
{
  double youngs_modulus = 0;
  double poisson_ratio = 0;
  double shear_modulus = 0;                     ///< 0: isotropic, G = E / 2(1 + nu)
  std::optional<dem::Matrix6> stiffness_tensor; ///< Pa, Voigt order xx, yy, zz, yz, xz, xy
  std::string source;
};

/// The material of a stiffness tensor (checked symmetric positive definite); throws
/// std::runtime_error "<where>: <reason>".
ElasticConstants material_from_tensor(const dem::Matrix6& C, const std::string& where);

/// The stiffness_tensor of an elasticity.json (`dembridge elasticity`); throws
/// std::runtime_error "<where>: <reason>" if it is missing, not 6x6 numbers, or not positive
/// definite.
ElasticConstants material_from_elasticity(const nlohmann::json& elasticity,
                                          const std::string& where);

/// E and nu of a uniaxial test summary: youngs_modulus and the mean of its poisson_ratio_*
/// entries. Throws std::runtime_error "<where>: <reason>" if they are missing or unphysical.
ElasticConstants material_from_summary(const nlohmann::json& summary, const std::string& where);

/// Reads and parses a JSON file; one-line errors naming the file.
nlohmann::json read_json_file(const std::string& file, const std::string& what);

/// Runs the verification; returns the exit code. Throws std::runtime_error (one line).
int verify(const VerifyOptions& options);
} // namespace dembridge::app
