#include "app/output/particle_vtu.h"
#include "app/checkpoint/checkpoint.h"
#include "app/output/particle_vtu_file.h"
#include "dem/bonds/bond_stress.h"
#include "dem/measurements/particle_stress.h"
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <type_traits>

namespace dembridge::app
{
namespace
{
/// Points in the user's numbering (the stores are in spatial order, renumbering.h): point j is
/// the particle with the j-th smallest id (on one rank the particle with id j), so the files do
/// not depend on the internal order. A piece of a run on several ranks: its first @p n particles
/// (the rank's own).
class UserOrder
{
public:
  UserOrder(const dem::ParticleStore& p, std::size_t n) : at_(n)
  {
    for (std::size_t i = 0; i < n; ++i)
      at_[i] = i;
    std::sort(at_.begin(), at_.end(),
              [&](std::size_t x, std::size_t y) { return p.id[x] < p.id[y]; });
  }
  /// The store index of point j.
  std::size_t operator[](std::size_t j) const { return at_[j]; }
  std::size_t size() const { return at_.size(); }

  /// @p field (a function of the store index) at the points, 3 values each.
  template <class Field> std::vector<double> vectors(Field field) const
  {
    std::vector<double> v(3 * size());
    for (std::size_t j = 0; j < size(); ++j)
    {
      const dem::Vec3 x = field(at_[j]);
      v[3 * j] = x.x(), v[3 * j + 1] = x.y(), v[3 * j + 2] = x.z();
    }
    return v;
  }
  /// @p field (a per-particle array) at the points.
  template <class Field> auto scalars(const Field& field) const
  {
    std::vector<std::remove_cv_t<std::remove_reference_t<decltype(field[0])>>> v(size());
    for (std::size_t j = 0; j < size(); ++j)
      v[j] = field[at_[j]];
    return v;
  }

private:
  std::vector<std::size_t> at_;
};

/// The particles' point data: radius, motion, forces, groups, coordination, ids, grains and
/// the particle stress tensors.
void add_particle_data(VtuFile& file, const dem::ParticleStore& p, const dem::BondStore& b,
                       const UserOrder& at)
{
  const std::size_t n = at.size();
  file.point_data("radius", at.scalars(p.radius));
  file.point_data(
      "displacement",
      at.vectors([&](std::size_t i) { return p.position[i] - p.reference_position[i]; }), 3);
  file.point_data("velocity", at.vectors([&](std::size_t i) { return p.velocity[i]; }), 3);
  file.point_data("angular_velocity",
                  at.vectors([&](std::size_t i) { return p.angular_velocity[i]; }), 3);
  file.point_data("force", at.vectors([&](std::size_t i) { return p.force[i]; }), 3);
  file.point_data("moment", at.vectors([&](std::size_t i) { return p.torque[i]; }), 3);
  file.point_data("group_mask", at.scalars(p.group_mask));
  const std::vector<int> coordination = at.scalars(p.coordination);
  file.point_data("coordination",
                  std::vector<std::int32_t>(coordination.begin(), coordination.end()));
  std::vector<std::int64_t> id(n); // the user's numbering (one rank: point j is particle j)
  for (std::size_t j = 0; j < n; ++j)
    id[j] = std::int64_t(p.id[at[j]]);
  file.point_data("id", id);
  if (!p.grain.empty()) // the microstructure's grain of each particle
    file.point_data("grain_id", at.scalars(p.grain));
  // Particle stress tensors (thesis eq. 62), Pa, tension positive; row-major 3 x 3.
  const dem::ParticleStresses stress = dem::particle_stresses(p, b);
  std::vector<double> sigma(9 * n);
  for (std::size_t j = 0; j < n; ++j)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        sigma[9 * j + std::size_t(3 * r + c)] = stress.sigma[at[j]](r, c);
  file.point_data("stress", sigma, 9);
}

/// How a bond file numbers its points and bonds: the whole model's (point j the particle with
/// id j, a bond's id its index) or a piece's (its store holds the bonds' ends in id order).
struct BondNumbering
{
  bool points_by_index = false;                   ///< else by the particles' ids
  const std::vector<std::int64_t>* ids = nullptr; ///< the bonds' ids; null: their index
  bool classes = false;                           ///< the class array
};

/// The bonds' cell data: the particle pairs, the forces and moments the bonds carry, their
/// section stresses, states, damage, ids and classes.
void add_bond_data(VtuFile& file, const dem::ParticleStore& p, const dem::BondStore& b,
                   const BondNumbering& numbering)
{
  auto point = [&](std::int32_t i) -> std::int64_t
  { return numbering.points_by_index ? i : p.id[std::size_t(i)]; };
  const std::size_t nb = b.size();
  std::vector<std::int64_t> pairs(2 * nb), id(nb);
  std::vector<double> normal(nb), shear(nb), twist(nb), bending(nb), force(3 * nb);
  std::vector<double> tensile(nb), shear_stress(nb), damage(nb);
  std::vector<std::uint8_t> state(nb);
  for (std::size_t k = 0; k < nb; ++k)
  {
    pairs[2 * k] = point(b.a[k]), pairs[2 * k + 1] = point(b.b[k]);
    id[k] = numbering.ids ? (*numbering.ids)[k] : std::int64_t(k);
    const dem::Vec3 xa = p.position[b.a[k]], xb = p.position[b.b[k]];
    dem::Vec3 e = (xb - xa).normalized();
    if (const dem::Vec3* N = b.joint_normal(k)) // a smooth joint's split (smooth_joint.h)
      e = N->dot(e) < 0 ? dem::Vec3(-*N) : *N;
    // evaluated here from the written configuration (no per-bond records kept by the run);
    // a broken bond carries nothing
    const dem::BondContactForce contact = dem::bond_contact_force(p, b, k);
    const dem::Vec3& F = contact.force;
    const dem::Vec3& M = contact.moment;
    normal[k] = -F.dot(e); // F is the force on b: pulling b back is tension
    shear[k] = (F - F.dot(e) * e).norm();
    twist[k] = M.dot(e);
    bending[k] = (M - twist[k] * e).norm();
    for (int d = 0; d < 3; ++d)
      force[3 * k + std::size_t(d)] = F[d];
    // beam theory on the section (bond_stress.h) from the forces the bond carries
    const dem::BondStress st = dem::bond_stress(F.data(), M.data(), e.data(), b.radius[k],
                                                b.failure_constants(k).moment_factor);
    state[k] = std::uint8_t(b.state[k]); // 0 intact, 1 softening, 2 broken
    tensile[k] = st.tensile;
    shear_stress[k] = st.shear;
    damage[k] = b.damage.empty() ? 0.0 : b.damage[k];
  }
  file.lines(pairs);
  file.cell_data("normal_force", normal);
  file.cell_data("shear_force", shear);
  file.cell_data("twisting_moment", twist);
  file.cell_data("bending_moment", bending);
  file.cell_data("force", force, 3);
  file.cell_data("state", state);
  file.cell_data("tensile_stress", tensile);
  file.cell_data("shear_stress", shear_stress);
  file.cell_data("damage", damage);
  file.cell_data("id", id);
  if (numbering.classes) // the class that chose each bond's constants (bond_class.h)
  {
    std::vector<std::uint8_t> bond_class(nb);
    for (std::size_t k = 0; k < nb; ++k)
      bond_class[k] = std::uint8_t(b.bond_class[k]);
    file.cell_data("class", bond_class);
    file.field_strings("class_names", std::vector<std::string>(dem::bond_class_names.begin(),
                                                               dem::bond_class_names.end()));
  }
}

/// The files' points: the particles' positions in the user's order.
std::vector<dem::Vec3> user_points(const dem::ParticleStore& p, const UserOrder& at)
{
  std::vector<dem::Vec3> points(at.size());
  for (std::size_t j = 0; j < at.size(); ++j)
    points[j] = p.position[at[j]];
  return points;
}

/// The particles' file: the particles of @p at as vertices with point data.
VtuFile particle_file(const dem::ParticleStore& p, const UserOrder& at, const dem::BondStore& b,
                      const std::vector<std::string>& group_names)
{
  VtuFile file(user_points(p, at), VtuFile::Cells::vertices);
  add_particle_data(file, p, b, at);
  file.field_strings("group_names", group_names);
  return file;
}

/// The bonds' file: line cells between @p points (their particle_id @p particle_id) with the
/// bonds' cell data.
VtuFile bond_file(const std::vector<dem::Vec3>& points,
                  const std::vector<std::int64_t>& particle_id, const dem::ParticleStore& p,
                  const dem::BondStore& b, const BondNumbering& numbering,
                  const std::vector<std::string>& group_names)
{
  VtuFile file(points, VtuFile::Cells::lines);
  add_bond_data(file, p, b, numbering);
  file.point_data("particle_id", particle_id);
  file.field_strings("group_names", group_names);
  return file;
}

/// KIND_NNNNNN (particles, bonds): a snapshot's name without extension.
std::string snapshot_stem(const char* kind, std::size_t index)
{
  char tag[48];
  std::snprintf(tag, sizeof tag, "%s_%06zu", kind, index);
  return tag;
}
} // namespace

void ParticleVtuSeries::write(const dem::ParticleStore& p, const dem::BondStore& b, double time,
                              long step)
{
  const std::size_t index = particle_files_.size(), n = p.size();
  if (pieces_) // on several ranks: the ranks' pieces and their records (ParticlePieces)
  {
    particle_files_.emplace_back(time, snapshot_stem("particles", index) + ".pvtu");
    bond_files_.emplace_back(time, snapshot_stem("bonds", index) + ".pvtu");
    return;
  }
  const UserOrder at(p, n);
  // Particles: vertices with point data
  const std::string particles = snapshot_stem("particles", index) + ".vtu";
  particle_file(p, at, b, group_names_).write(dir_ / particles, time, step);
  particle_files_.emplace_back(time, particles);
  // Bonds: line cells between the particle centres, the bond's quantities as cell data
  std::vector<std::int64_t> particle_id(n);
  for (std::size_t j = 0; j < n; ++j)
    particle_id[j] = std::int64_t(j);
  const std::string bonds = snapshot_stem("bonds", index) + ".vtu";
  bond_file(user_points(p, at), particle_id, p, b, {false, nullptr, !b.bond_class.empty()},
            group_names_)
      .write(dir_ / bonds, time, step);
  bond_files_.emplace_back(time, bonds);
}

ParticlePieces::ParticlePieces(std::filesystem::path dir, std::vector<std::string> group_names,
                               MPI_Comm comm, ParticleVtuSeries* series)
    : dir_(std::move(dir)), group_names_(std::move(group_names)), comm_(comm), series_(series)
{
  if (series_)
    series_->in_pieces();
}

void ParticlePieces::write(const dem::ParticleStore& p, std::size_t n_owned,
                           const dem::BondStore& b, double time, long step)
{
  write_piece(particle_file(p, UserOrder(p, n_owned), b, group_names_), "particles", time, step);
}

void ParticlePieces::write_bonds(const dem::ParticleStore& ends, const dem::BondStore& bonds,
                                 const std::vector<std::int64_t>& ids, bool classes, double time,
                                 long step)
{
  const std::vector<std::int64_t> particle_id(ends.id.begin(), ends.id.end());
  write_piece(
      bond_file(ends.position, particle_id, ends, bonds, {true, &ids, classes}, group_names_),
      "bonds", time, step);
}

void ParticlePieces::write_piece(const VtuFile& file, const char* kind, double time, long step)
{
  const unsigned rank = dealii::Utilities::MPI::this_mpi_process(comm_);
  const unsigned n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm_);
  // rank 0's series numbers the snapshots (a resumed run continues its checkpoint's list)
  unsigned long index = series_ ? series_->particle_files().size() : 0;
  MPI_Bcast(&index, 1, MPI_UNSIGNED_LONG, 0, comm_);
  const std::string stem = snapshot_stem(kind, index);
  auto piece = [&](unsigned r) { return stem + "_r" + std::to_string(r) + ".vtu"; };
  // every rank learns whether one could not write (then all throw the first such error)
  std::string failed;
  try
  {
    file.write(dir_ / piece(rank), time, step);
    if (rank == 0)
    {
      std::vector<std::string> pieces;
      for (unsigned r = 0; r < n_ranks; ++r)
        pieces.push_back(piece(r));
      file.write_pvtu(dir_ / (stem + ".pvtu"), pieces);
    }
  }
  catch (const std::exception& e)
  {
    failed = *e.what() ? e.what() : "ParaView piece: unknown error";
  }
  const unsigned first = dealii::Utilities::MPI::min(failed.empty() ? n_ranks : rank, comm_);
  if (first < n_ranks)
    throw std::runtime_error(dealii::Utilities::MPI::broadcast(comm_, failed, first));
}

void ParticleVtuSeries::visit_state(dem::StateArchive& a)
{
  dem::StateGroup group(a, "snapshots");
  visit_file_list(a, "particles", particle_files_);
  visit_file_list(a, "bonds", bond_files_);
}

void ParticleVtuSeries::finish() const
{
  for (const auto& [name, files] :
       {std::pair{"particles.pvd", &particle_files_}, std::pair{"bonds.pvd", &bond_files_}})
  {
    write_pvd(dir_ / name, *files);
  }
}

void remove_later_dem_snapshots(const std::filesystem::path& dir, const ParticleVtuSeries& vtu,
                                const std::vector<std::pair<double, std::string>>& crack_files)
{
  std::set<std::string> listed;
  for (const auto* files : {&vtu.particle_files(), &vtu.bond_files(), &crack_files})
    for (const auto& f : *files)
      listed.insert(f.second);
  for (const auto& entry : std::filesystem::directory_iterator(dir))
  {
    std::string name = entry.path().filename().string();
    const bool particles_or_bonds =
        name.rfind("particles_", 0) == 0 || name.rfind("bonds_", 0) == 0;
    // a piece of a run on several ranks (particles_NNNNNN_rR.vtu, bonds_...) goes with its record
    if (const auto r = name.rfind("_r");
        particles_or_bonds && r != name.npos && entry.path().extension() == ".vtu")
      name = name.substr(0, r) + ".pvtu";
    const bool record = entry.path().extension() == ".pvtu" && particles_or_bonds;
    const bool snapshot =
        record || (entry.path().extension() == ".vtu" &&
                   (name.rfind("particles_", 0) == 0 || name.rfind("bonds_", 0) == 0 ||
                    name.rfind("cracks_", 0) == 0));
    if (snapshot && !listed.count(name))
      std::filesystem::remove(entry.path());
  }
  for (const auto& name : listed)
    if (!std::filesystem::exists(dir / name))
      std::printf("dembridge: warning: snapshot %s of the interrupted run is missing (its "
                  "staging folder was cleared); the ParaView series lacks it\n",
                  name.c_str());
}
} // namespace dembridge::app
