#pragma once
// A bonded-particle model spread over MPI ranks on deal.II's distributed particle handler
// (docs/parallel.md). The handler, on a background p4est mesh (background_grid.h), decides which
// rank owns a particle, migrates particles between ranks and hands each rank its ghosts; this
// class turns that into what dem/'s explicit solver reads: on each rank one ParticleStore that
// holds the rank's own particles first, its ghosts after them, and one BondStore with every
// bond that has an owned end (a bond with a ghost end lives on both ranks, LAMMPS's
// `newton_bond off`, computed alike on both).
//
// Per step only the kinematics of the ghosts change (update_ghosts: positions, velocities,
// angular velocities and orientations from their owners, through a Utilities::MPI::Partitioner
// over the particles' slots; nothing else is exchanged). The stores are rebuilt from the
// handler only when particles may have left their ranks (needs_rebuild: one particle moved half
// a cell since the last rebuild): the rank writes its particles' state back into the handler's
// properties, the handler sorts them into their new cells and ranks (and, when one rank owns
// too many, the mesh is repartitioned by its particles and the handler's particles go with their
// cells) and exchanges the ghost layer, the state and each bond of a particle that changed
// ranks, for either reason, are sent to the particle's new owner, and the stores and the
// partitioner are made anew. Between rebuilds the ghost set is fixed, so a bond
// computed at one rebuild can be computed until the next whatever its particles do. With
// contacts the ghosts also carry their radius and mass, and a rebuild comes before two particles
// that are not in a rank's store could touch one of its own: the ghost layer (one cell) less
// twice the travel allowed between rebuilds is at least the contact cut-off, twice the largest
// radius.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/model/model.h"
#include "distributed/background_grid.h"
#include <array>
#include <cstdint>
#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/particles/particle_handler.h>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dembridge::distributed
{
/// A particle's support reaction (force, moment) of the last step: state of the explicit
/// solver that travels with the particle.
using Reaction = std::array<double, 6>;
/// The non-zero reactions of a rank's owned particles, by local index (ascending).
using Reactions = std::vector<std::pair<std::uint32_t, Reaction>>;

/// Why @p bonds cannot be spread over ranks (empty: they can): smooth joints, whose bond
/// classes the bond records do not carry; the message names the parameter that set them.
std::string smooth_joints_on_ranks(const dem::BondStore& bonds);

class DistributedParticles
{
public:
  /// Every rank passes the same model (its particles' indices are their global ids): the rank
  /// keeps the particles in its cells and the bonds with an owned end. The mesh is partitioned
  /// so that the ranks hold about as many particles each (deal.II's cell weights).
  DistributedParticles(const dem::Model& model, const BackgroundGrid& grid, MPI_Comm comm);

  /// The rank's particles: owned ones in [0, n_owned()), ghosts after them.
  dem::ParticleStore& particles() { return particles_; }
  const dem::ParticleStore& particles() const { return particles_; }
  /// Every bond with an owned end, between local particle indices, in the model's orientation.
  dem::BondStore& bonds() { return bonds_; }
  const dem::BondStore& bonds() const { return bonds_; }
  std::size_t n_owned() const { return n_owned_; }
  /// Global id (index in the model) of each local particle.
  const std::vector<std::int64_t>& global_ids() const { return global_id_; }
  /// The model's index of bond k of bonds() at the setup (its global id: it travels in the
  /// bond's record through migrations; the ParaView bond files show it).
  std::int64_t bond_id(std::size_t k) const;
  /// Whether the model's bonds have classes (bonds() holds them then).
  bool bond_classes() const { return bond_classes_; }
  /// The records (bond_records.h) of the broken bonds of owned particles whose end b drifted
  /// out of this rank's store, in the order of their ids: kept by the owner of end a (they
  /// travel with it) so that the bond files list every bond; a bond is in bonds() or here.
  const std::vector<double>& detached_bonds() const { return detached_; }
  /// The support reactions of the owned particles as the last rebuild brought them.
  const Reactions& reactions() const { return reactions_; }

  /// Ghosts take their owners' x, v, w and q (collective; no allocation).
  void update_ghosts();
  struct MotionCheck
  {
    bool rebuild = false;  ///< some particle moved more than half a cell since the last rebuild
    bool unstable = false; ///< some rank holds a non-finite position or said it was unstable
  };
  /// Collective (one reduction of two numbers): how far the particles moved.
  MotionCheck check_motion(bool local_unstable = false);
  /// Collective: migrates particles and their bonds to their new ranks and rebuilds the stores
  /// (see above). @p reactions: the owned particles' support reactions (the solver's state).
  /// @p contacts: records of @p contact_record_size doubles whose first two name the global ids
  /// of their particles (a negative first: only the second), each with an owned particle
  /// (dem::ContactForces::export_history); on return the records kept here and those sent here
  /// by the ranks the particles left.
  void rebuild(const Reactions& reactions, std::vector<double>& contacts,
               std::size_t contact_record_size);
  /// Whether ghosts carry their radius and mass (the contact law reads them): a model with
  /// contacts.
  bool with_contacts() const { return n_properties_ > 2; }

  long n_rebuilds() const { return n_rebuilds_; }
  /// A rebuild repartitions the mesh (cell weights: 1 + 1000 per particle, as at the setup) when
  /// the rank owning the most particles holds more than this times their mean: particles that
  /// flew into one rank's cells leave it its neighbours' work as well.
  static constexpr double max_imbalance = 1.1;
  /// Rebuilds that repartitioned the mesh (the same on every rank).
  long n_repartitions() const { return n_repartitions_; }
  /// Over the repartitions: the largest imbalance (most owned particles / their mean) that
  /// started one, and the largest one left (0, 0 without any).
  std::pair<double, double> repartition_imbalance() const { return largest_imbalance_; }
  /// Particles that arrived from other ranks over all rebuilds (this rank).
  long n_arrived() const { return n_arrived_; }
  const BackgroundGrid& grid() const { return grid_; }
  MPI_Comm communicator() const { return comm_; }
  /// Doubles sent per update_ghosts from this rank, and the ranks it sends to.
  std::size_t halo_doubles() const;
  std::size_t halo_targets() const;
  /// Bytes this rank holds for its particles: the stores (capacity), the exchange's buffers and
  /// partitioner, the background mesh (p4est and deal.II's cells), and the handler's particles
  /// at 72 bytes each (location, reference location, id and the 2 property doubles; the
  /// handler's own lists aside).
  std::size_t memory_bytes() const;
  /// Its parts: the background mesh, and the handler's particles (owned and ghosts).
  std::size_t mesh_bytes() const { return tria_.memory_consumption(); }
  std::size_t handler_bytes() const;

private:
  /// Fills the owned particle with global id `id` at local index i (all but its position: the
  /// handler's location); returns its support reaction.
  using FillOwned = std::function<Reaction(std::int64_t id, std::size_t i)>;
  /// Collective: when the owned particles are imbalanced beyond max_imbalance, the mesh
  /// repartitioned by the particles' weights with the handler's particles in it (step-68).
  void repartition_if_imbalanced();
  /// Slots, ghost exchange, stores and partitioner from the handler's owned particles and the
  /// bond records held; the ghosts' kinematics at the end (collective).
  void build_local(std::vector<double>& records, const FillOwned& fill);

  MPI_Comm comm_;
  BackgroundGrid grid_;
  dealii::parallel::distributed::Triangulation<3> tria_;
  dealii::MappingCartesian<3> mapping_;
  dealii::Particles::ParticleHandler<3> handler_;
  dem::ParticleStore particles_;
  dem::BondStore bonds_;
  std::size_t n_owned_ = 0;
  std::vector<std::int64_t> global_id_;
  /// (local a, local b) -> the bond's id, sorted: the solver may reorder bonds_ (threads)
  std::vector<std::pair<std::uint64_t, std::int64_t>> bond_ids_;
  std::vector<double> detached_;
  bool bond_classes_ = false;
  Reactions reactions_;
  std::int64_t n_global_ = 0;
  std::int64_t first_slot_ = 0;       ///< slot of the first owned particle
  std::vector<dem::Vec3> rebuilt_at_; ///< owned positions at the last rebuild
  double skin_ = 0;                   ///< displacement that triggers a rebuild, m
  unsigned n_properties_ = 2;         ///< handler properties a particle carries
  long n_rebuilds_ = 0, n_repartitions_ = 0, n_arrived_ = 0, n_lost_ = 0;
  std::pair<double, double> largest_imbalance_{0, 0};
  // the per-step exchange: 13 doubles a particle at index 13 slot + c
  std::shared_ptr<const dealii::Utilities::MPI::Partitioner> partitioner_;
  std::vector<double> ghost_buffer_, send_buffer_;
  std::vector<MPI_Request> requests_;
};
} // namespace dembridge::distributed
