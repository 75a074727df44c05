// dembridge verify: the report's rows from the DEM and FE summaries (see verify_rows.h).
#include "app/studies/verify_rows.h"
#include <cmath>
#include <string>

namespace dembridge::app::verify_detail
{
using coupling::SpecimenLayers;
using coupling::SpecimenTest;
using nlohmann::json;

namespace
{
const char* const axis_name = "xyz";

std::optional<double> number_at(const json& j, std::initializer_list<const char*> path)
{
  const json* node = &j;
  for (const char* key : path)
  {
    if (!node->is_object() || !node->contains(key))
      return std::nullopt;
    node = &(*node)[key];
  }
  return node->is_number() ? std::optional<double>(node->get<double>()) : std::nullopt;
}

std::optional<double> component(const json& j, std::initializer_list<const char*> path, int d)
{
  const json* node = &j;
  for (const char* key : path)
  {
    if (!node->is_object() || !node->contains(key))
      return std::nullopt;
    node = &(*node)[key];
  }
  return node->is_array() && node->size() == 3 ? std::optional<double>((*node)[d].get<double>())
                                               : std::nullopt;
}

std::optional<double> dem_strain_energy(const json& dem)
{
  if (auto e = number_at(dem, {"strain_energy"}))
    return e;
  return number_at(dem, {"energy", "strain"});
}

void add_uniaxial_rows(Report& r, const SpecimenTest& p, const json& dem, const json& fe)
{
  const std::string a(1, axis_name[p.axis]);
  const int d = p.axis;
  const char* f = p.fixed_group.c_str();
  const char* l = p.loaded_group.c_str();
  r.scalars.push_back(
      {"youngs_modulus",
       "Pa",
       dem_youngs_modulus(p, dem),
       number_at(fe, {"youngs_modulus"}),
       {},
       p.displacement_control ? "thesis eq. 64" : "thesis eq. 64, from the fixed-end reaction"});
  r.scalars.push_back({"reaction_" + p.fixed_group + "_" + a,
                       "N",
                       component(dem, {"groups", f, "force"}, d),
                       component(fe, {"reactions", p.fixed_face.c_str()}, d),
                       {},
                       "support on the specimen"});
  if (p.displacement_control)
    r.scalars.push_back({"reaction_" + p.loaded_group + "_" + a,
                         "N",
                         component(dem, {"groups", l, "force"}, d),
                         component(fe, {"reactions", p.loaded_face.c_str()}, d),
                         {},
                         "grip on the specimen"});
  std::optional<double> du;
  if (auto ul = component(dem, {"groups", l, "mean_displacement"}, d))
    if (auto uf = component(dem, {"groups", f, "mean_displacement"}, d))
      du = *ul - *uf;
  r.scalars.push_back({"end_displacement",
                       "m",
                       du,
                       number_at(fe, {"elongation"}),
                       {},
                       "loaded minus fixed end along " + a});
}

void add_bending_rows(Report& r, const SpecimenTest& p, const json& dem, const json& fe)
{
  auto fe_top = component(fe, {"mean_displacements", "top"}, 2);
  auto fe_bottom = component(fe, {"mean_displacements", "bottom"}, 2);
  std::optional<double> fe_mean, fe_load, dem_top;
  if (fe_top && fe_bottom)
    fe_mean = 0.5 * (std::abs(*fe_top) + std::abs(*fe_bottom));
  const auto dem_mean = number_at(dem, {"midspan_deflection"});
  const auto dem_bottom = number_at(dem, {"bottom_deflection"});
  if (dem_mean && dem_bottom)
    dem_top = 2 * *dem_mean - *dem_bottom;
  auto fe_pin = component(fe, {"reactions", p.pin.c_str()}, 2);
  auto fe_roller = component(fe, {"reactions", p.roller.c_str()}, 2);
  if (fe_pin && fe_roller)
    fe_load = std::abs(*fe_pin + *fe_roller);
  r.scalars.push_back(
      {"midspan_deflection", "m", dem_mean, fe_mean, {}, "mean of top and bottom midspan"});
  r.scalars.push_back({"top_deflection",
                       "m",
                       dem_top,
                       fe_top ? std::optional<double>(std::abs(*fe_top)) : std::nullopt,
                       {},
                       "under the load"});
  r.scalars.push_back({"bottom_deflection",
                       "m",
                       dem_bottom,
                       fe_bottom ? std::optional<double>(std::abs(*fe_bottom)) : std::nullopt,
                       {},
                       "bottom midspan"});
  r.scalars.push_back({"flexural_load",
                       "N",
                       number_at(dem, {"flexural_load"}),
                       fe_load,
                       {},
                       "sum of the support reactions"});
  r.scalars.push_back({"reaction_" + p.pin + "_z",
                       "N",
                       component(dem, {"groups", p.pin.c_str(), "force"}, 2),
                       fe_pin,
                       {},
                       ""});
  r.scalars.push_back({"reaction_" + p.roller + "_z",
                       "N",
                       component(dem, {"groups", p.roller.c_str(), "force"}, 2),
                       fe_roller,
                       {},
                       ""});
  // eq. 69 with the FE deflection and load (same span, load length, section, nu)
  std::optional<double> fe_modulus;
  const auto dem_modulus = number_at(dem, {"flexural_modulus"});
  const auto dem_load = number_at(dem, {"flexural_load"});
  if (dem_modulus && dem_mean && dem_load && fe_mean && fe_load && *fe_mean > 0 && *dem_load > 0)
    fe_modulus = *dem_modulus * (*fe_load / *dem_load) * (*dem_mean / *fe_mean);
  r.scalars.push_back({"flexural_modulus", "Pa", dem_modulus, fe_modulus, {}, "thesis eq. 69"});
}

void add_layer_rows(Report& r, const SpecimenTest& p, const json& dem, const json& fe,
                    const SpecimenLayers& layers)
{
  const std::string a(1, axis_name[p.axis]);
  // Layers: the normal stress along the test axis; FE integrals over the DEM slab volumes.
  r.layer_axis = std::string(1, axis_name[layers.axis]);
  r.layer_component = "sigma_" + a + a;
  r.layer_edges = layers.edges;
  double section = 1;
  for (int d = 0; d < 3; ++d)
    if (d != layers.axis)
      section *= p.hi[d] - p.lo[d];
  const json* dem_sigma = dem.contains("stress_layers") ? &dem["stress_layers"]["sigma"] : nullptr;
  const auto& fe_layers = fe.at("stress_layers");
  for (std::size_t k = 0; k + 1 < layers.edges.size(); ++k)
  {
    const double thickness = layers.edges[k + 1] - layers.edges[k];
    Row row{"layer_" + std::to_string(k) + "_" + r.layer_component, "Pa", {}, {},
            0.5 * (layers.edges[k] + layers.edges[k + 1]),          ""};
    if (dem_sigma && k < dem_sigma->size())
      row.dem = (*dem_sigma)[k][p.axis][p.axis].get<double>();
    row.fem = fe_layers["sigma"][k][p.axis][p.axis].get<double>() *
              fe_layers["volume"][k].get<double>() / (thickness * section);
    r.layers.push_back(row);
  }
}
} // namespace

std::optional<double> dem_youngs_modulus(const SpecimenTest& p, const json& dem)
{
  if (p.displacement_control)
    return number_at(dem, {"youngs_modulus"});
  const int a = p.axis;
  const auto r = component(dem, {"groups", p.fixed_group.c_str(), "force"}, a);
  const auto ul = component(dem, {"groups", p.loaded_group.c_str(), "mean_displacement"}, a);
  const auto uf = component(dem, {"groups", p.fixed_group.c_str(), "mean_displacement"}, a);
  const auto area = number_at(dem, {"cross_section_area"});
  const auto length = number_at(dem, {"gauge_length"});
  if (!r || !ul || !uf || !area || !length || *ul == *uf || *area <= 0)
    return std::nullopt;
  return -*r / *area * *length / (*ul - *uf);
}

Report compare_results(const SpecimenTest& t, const json& dem, const json& fe,
                       const SpecimenLayers& layers)
{
  Report r;
  if (t.test == "uniaxial")
    add_uniaxial_rows(r, t, dem, fe);
  else
    add_bending_rows(r, t, dem, fe);
  r.scalars.push_back(
      {"strain_energy", "J", dem_strain_energy(dem), number_at(fe, {"strain_energy"}), {}, ""});
  add_layer_rows(r, t, dem, fe, layers);
  return r;
}
} // namespace dembridge::app::verify_detail
