#include "particle_vtu.h"
#include "dem/bonds/bond_stress.h"
#include "dem/measurements/particle_stress.h"
#include <cstdio>
#include <deal.II/base/data_out_base.h>
#include <fstream>

namespace dembridge::app
{
namespace
{
using dealii::DataComponentInterpretation::component_is_part_of_tensor;
using dealii::DataComponentInterpretation::component_is_part_of_vector;
using dealii::DataComponentInterpretation::DataComponentInterpretation;
using Ranges =
    std::vector<std::tuple<unsigned int, unsigned int, std::string, DataComponentInterpretation>>;

dealii::Point<3> point(const dem::Vec3& x)
{
  return {x.x(), x.y(), x.z()};
}

void put(dealii::Table<2, float>& data, unsigned& row, unsigned col, const dem::Vec3& v)
{
  for (int d = 0; d < 3; ++d)
    data(row + d, col) = float(v[d]);
  row += 3;
}

template <int dim>
void write_file(const std::filesystem::path& file,
                const std::vector<dealii::DataOutBase::Patch<dim, 3>>& patches,
                const std::vector<std::string>& names, const Ranges& ranges, double time, long step)
{
  std::ofstream out(file);
  if (!out)
    throw std::runtime_error(file.string() + ": cannot write");
  dealii::DataOutBase::VtkFlags flags(time, unsigned(step), false);
  dealii::DataOutBase::write_vtu(patches, names, ranges, flags, out);
}
} // namespace

void ParticleVtuSeries::write(const dem::ParticleStore& p, const dem::BondStore& b, double time,
                              long step)
{
  char tag[32];
  std::snprintf(tag, sizeof tag, "%06zu", particle_files_.size());
  // Particles
  {
    const std::vector<std::string> names = {"radius",
                                            "displacement",
                                            "displacement",
                                            "displacement",
                                            "velocity",
                                            "velocity",
                                            "velocity",
                                            "angular_velocity",
                                            "angular_velocity",
                                            "angular_velocity",
                                            "force",
                                            "force",
                                            "force",
                                            "moment",
                                            "moment",
                                            "moment",
                                            "group_mask",
                                            "coordination",
                                            "id",
                                            "stress",
                                            "stress",
                                            "stress",
                                            "stress",
                                            "stress",
                                            "stress",
                                            "stress",
                                            "stress",
                                            "stress"};
    Ranges ranges;
    for (unsigned first : {1u, 4u, 7u, 10u, 13u})
      ranges.emplace_back(first, first + 2, names[first], component_is_part_of_vector);
    ranges.emplace_back(19u, 27u, "stress", component_is_part_of_tensor);
    // Particle stress tensors (thesis eq. 62), Pa, tension positive.
    const dem::ParticleStresses stress = dem::particle_stresses(p, b);
    std::vector<dealii::DataOutBase::Patch<0, 3>> patches(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      auto& patch = patches[i];
      patch.vertices[0] = point(p.position[i]);
      patch.patch_index = unsigned(i);
      patch.data.reinit(unsigned(names.size()), 1);
      unsigned row = 0;
      patch.data(row++, 0) = float(p.radius[i]);
      put(patch.data, row, 0, p.position[i] - p.reference_position[i]);
      put(patch.data, row, 0, p.velocity[i]);
      put(patch.data, row, 0, p.angular_velocity[i]);
      put(patch.data, row, 0, p.force[i]);
      put(patch.data, row, 0, p.torque[i]);
      patch.data(row++, 0) = float(p.group_mask[i]);
      patch.data(row++, 0) = float(p.coordination[i]);
      patch.data(row++, 0) = float(i);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          patch.data(row++, 0) = float(stress.sigma[i](r, c));
    }
    const std::string file = std::string("particles_") + tag + ".vtu";
    write_file(dir_ / file, patches, names, ranges, time, step);
    particle_files_.emplace_back(time, file);
  }
  // Bonds
  {
    const std::vector<std::string> names = {
        "normal_force", "shear_force", "twisting_moment", "bending_moment", "force", "force",
        "force",        "state",       "tensile_stress",  "shear_stress",   "damage"};
    Ranges ranges = {{4, 6, "force", component_is_part_of_vector}};
    std::vector<dealii::DataOutBase::Patch<1, 3>> patches(b.size());
    for (std::size_t k = 0; k < b.size(); ++k)
    {
      auto& patch = patches[k];
      const dem::Vec3 xa = p.position[b.a[k]], xb = p.position[b.b[k]];
      patch.vertices[0] = point(xa);
      patch.vertices[1] = point(xb);
      patch.patch_index = unsigned(k);
      patch.reference_cell = dealii::ReferenceCells::Line;
      patch.data.reinit(unsigned(names.size()), 2);
      const dem::Vec3 e = (xb - xa).normalized();
      // a broken bond carries nothing (its last recorded forces are those before the break)
      const bool bonded = dem::is_bonded(b.state[k]);
      const dem::Vec3 F = bonded ? b.force[k] : dem::Vec3::Zero();
      const dem::Vec3 M = bonded ? b.moment[k] : dem::Vec3::Zero();
      const double normal = -F.dot(e); // F is the force on b: pulling b back is tension
      const double twist = M.dot(e);
      // beam theory on the section (bond_stress.h) from the forces the bond carries
      const dem::BondStress st =
          dem::bond_stress(F.data(), M.data(), e.data(), b.radius[k], b.failure.moment_factor);
      for (unsigned v = 0; v < 2; ++v)
      {
        unsigned row = 0;
        patch.data(row++, v) = float(normal);
        patch.data(row++, v) = float((F - F.dot(e) * e).norm());
        patch.data(row++, v) = float(twist);
        patch.data(row++, v) = float((M - twist * e).norm());
        put(patch.data, row, v, F);
        patch.data(row++, v) = float(int(b.state[k])); // 0 intact, 1 softening, 2 broken
        patch.data(row++, v) = float(st.tensile);
        patch.data(row++, v) = float(st.shear);
        patch.data(row++, v) = float(b.damage.empty() ? 0.0 : b.damage[k]);
      }
    }
    const std::string file = std::string("bonds_") + tag + ".vtu";
    write_file(dir_ / file, patches, names, ranges, time, step);
    bond_files_.emplace_back(time, file);
  }
}

void ParticleVtuSeries::finish() const
{
  for (const auto& [name, files] :
       {std::pair{"particles.pvd", &particle_files_}, std::pair{"bonds.pvd", &bond_files_}})
  {
    std::ofstream out(dir_ / name);
    dealii::DataOutBase::write_pvd_record(out, *files);
  }
}
} // namespace dembridge::app
