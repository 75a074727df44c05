// dembridge::fem — what is measured on a solution: point values, reactions, boundary means,
// strain energy, and the ParaView fields (displacement, strain, stress, von Mises stress).
#include "dem/core/output_file.h"
#include "elastic_problem.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace dembridge::fem
{
using namespace dealii;

namespace
{
/// Strain eps = sym(grad u), stress sigma = C : eps and the von Mises stress
/// sigma_vM = sqrt(3/2 s : s), s = sigma - tr(sigma)/3 I, as named cell-wise point data.
class StrainStressPostprocessor : public DataPostprocessor<3>
{
public:
  explicit StrainStressPostprocessor(const SymmetricTensor<4, 3>& C) : stiffness(C) {}

  std::vector<std::string> get_names() const override
  {
    std::vector<std::string> names;
    for (const std::string quantity : {"strain", "stress"})
      for (const std::string c : {"xx", "yy", "zz", "yz", "xz", "xy"})
        names.push_back(quantity + "_" + c);
    names.emplace_back("von_mises_stress");
    return names;
  }
  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  get_data_component_interpretation() const override
  {
    return std::vector<DataComponentInterpretation::DataComponentInterpretation>(
        13, DataComponentInterpretation::component_is_scalar);
  }
  UpdateFlags get_needed_update_flags() const override { return update_gradients; }

  void evaluate_vector_field(const DataPostprocessorInputs::Vector<3>& input,
                             std::vector<Vector<double>>& computed) const override
  {
    static constexpr unsigned int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
    for (unsigned int p = 0; p < input.solution_gradients.size(); ++p)
    {
      Tensor<2, 3> grad;
      for (unsigned int d = 0; d < 3; ++d)
        grad[d] = input.solution_gradients[p][d];
      const SymmetricTensor<2, 3> eps = symmetrize(grad);
      const SymmetricTensor<2, 3> sigma = stiffness * eps;
      for (unsigned int k = 0; k < 6; ++k)
      {
        computed[p](k) = eps[pairs[k][0]][pairs[k][1]];
        computed[p](6 + k) = sigma[pairs[k][0]][pairs[k][1]];
      }
      const SymmetricTensor<2, 3> s = deviator(sigma);
      computed[p](12) = std::sqrt(1.5 * (s * s));
    }
  }

private:
  const SymmetricTensor<4, 3> stiffness;
};
} // namespace

// ------------------------------------------------------------------------------------------
// Probes: the first rank (lowest number) that owns a cell containing the point evaluates it.
PointProbe ElasticProblem::make_probe(const Point<3>& point, const std::string& where) const
{
  PointProbe probe;
  probe.point = point;
  typename DoFHandler<3>::active_cell_iterator found;
  bool have_cell = false;
  Point<3> unit;
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      BoundingBox<3> box = cell->bounding_box();
      box.extend(geometric_tolerance);
      if (!box.point_inside(point))
        continue;
      try
      {
        unit = mapping.transform_real_to_unit_cell(cell, point);
      }
      catch (const Mapping<3>::ExcTransformationFailed&)
      {
        continue;
      }
      if (GeometryInfo<3>::is_inside_unit_cell(unit, 1e-8))
      {
        found = cell;
        have_cell = true;
        break;
      }
    }
  const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
  const unsigned int none = std::numeric_limits<unsigned int>::max();
  const unsigned int owner = Utilities::MPI::min(have_cell ? rank : none, mpi_communicator);
  if (owner == none)
    throw std::runtime_error(where + ": point lies outside the mesh");
  if (owner != rank)
    return probe;
  for (unsigned int d = 0; d < 3; ++d)
    unit[d] = std::clamp(unit[d], 0.0, 1.0);
  FEValues<3> fe_values(mapping, fe, Quadrature<3>(std::vector<Point<3>>{unit}), update_values);
  fe_values.reinit(found);
  probe.owned = true;
  probe.dofs.resize(fe.n_dofs_per_cell());
  found->get_dof_indices(probe.dofs);
  for (unsigned int i = 0; i < probe.dofs.size(); ++i)
  {
    Tensor<1, 3> shape;
    shape[fe.system_to_component_index(i).first] = fe_values.shape_value(i, 0);
    probe.shape_vectors.push_back(shape);
  }
  return probe;
}

Tensor<1, 3> ElasticProblem::probe_vector(const PointProbe& probe) const
{
  Tensor<1, 3> u;
  for (unsigned int i = 0; i < probe.dofs.size(); ++i)
    u += solution(probe.dofs[i]) * probe.shape_vectors[i];
  return Utilities::MPI::sum(u, mpi_communicator);
}

double ElasticProblem::probe_value(const PointProbe& probe, const Tensor<1, 3>& direction) const
{
  return probe_vector(probe) * direction;
}

// ------------------------------------------------------------------------------------------
// f_int,i = int eps(phi_i) : sigma(u) dx, element by element, without constraints.
void ElasticProblem::compute_internal_forces(const LA::MPI::Vector& u, LA::MPI::Vector& f_int) const
{
  f_int = 0;
  const QGauss<3> quadrature(fe.degree + 1);
  FEValues<3> fe_values(mapping, fe, quadrature, update_gradients | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  Vector<double> cell_force(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      cell->get_dof_indices(dofs);
      cell_force = 0;
      for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        Tensor<2, 3> grad;
        for (unsigned int i = 0; i < n; ++i)
          grad[fe.system_to_component_index(i).first] += u(dofs[i]) * fe_values.shape_grad(i, q);
        const Tensor<2, 3> sigma = stiffness * symmetrize(grad);
        for (unsigned int i = 0; i < n; ++i)
          cell_force(i) +=
              (sigma[fe.system_to_component_index(i).first] * fe_values.shape_grad(i, q)) *
              fe_values.JxW(q);
      }
      f_int.add(dofs, cell_force);
    }
  f_int.compress(VectorOperation::add);
}

Tensor<1, 3> ElasticProblem::reaction(const types::boundary_id id) const
{
  LA::MPI::Vector f_int(locally_owned_dofs, mpi_communicator);
  compute_internal_forces(solution, f_int);
  Tensor<1, 3> r;
  for (unsigned int c = 0; c < 3; ++c)
  {
    std::vector<bool> mask(3, false);
    mask[c] = true;
    const IndexSet boundary_dofs =
        DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(mask), {id});
    for (const auto dof : boundary_dofs)
      if (locally_owned_dofs.is_element(dof))
        r[c] += f_int(dof) - external_force(dof);
  }
  return Utilities::MPI::sum(r, mpi_communicator);
}

ElasticProblem::BoundaryMeans ElasticProblem::boundary_means(const types::boundary_id id) const
{
  const QGauss<2> face_quadrature(fe.degree + 1);
  FEFaceValues<3> fe_face_values(mapping, fe, face_quadrature,
                                 update_values | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<1, 3>> u(face_quadrature.size());
  double area = 0;
  Tensor<1, 3> moment, integral;
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const auto& face : cell->face_iterators())
        if (face->at_boundary() && face->boundary_id() == id)
        {
          fe_face_values.reinit(cell, face);
          fe_face_values[displacement].get_function_values(solution, u);
          for (const unsigned int q : fe_face_values.quadrature_point_indices())
          {
            area += fe_face_values.JxW(q);
            moment += fe_face_values.quadrature_point(q) * fe_face_values.JxW(q);
            integral += u[q] * fe_face_values.JxW(q);
          }
        }
  BoundaryMeans means;
  means.area = Utilities::MPI::sum(area, mpi_communicator);
  if (means.area > 0)
  {
    means.centroid = Point<3>(Utilities::MPI::sum(moment, mpi_communicator) / means.area);
    means.mean_displacement = Utilities::MPI::sum(integral, mpi_communicator) / means.area;
  }
  return means;
}

double ElasticProblem::strain_energy() const
{
  const QGauss<3> quadrature(fe.degree + 1);
  FEValues<3> fe_values(mapping, fe, quadrature, update_gradients | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<SymmetricTensor<2, 3>> eps(quadrature.size());
  double energy = 0;
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values[displacement].get_function_symmetric_gradients(solution, eps);
      for (const unsigned int q : fe_values.quadrature_point_indices())
        energy += 0.5 * (eps[q] * (stiffness * eps[q])) * fe_values.JxW(q);
    }
  return Utilities::MPI::sum(energy, mpi_communicator);
}

ElasticProblem::LayerStresses ElasticProblem::layer_stresses(const unsigned int axis,
                                                             const std::vector<double>& edges) const
{
  const unsigned int n_layers = edges.size() < 2 ? 0 : edges.size() - 1;
  const QIterated<3> quadrature(QGauss<1>(fe.degree + 1), 2);
  FEValues<3> fe_values(mapping, fe, quadrature,
                        update_gradients | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<SymmetricTensor<2, 3>> eps(quadrature.size());
  std::vector<double> volume(n_layers, 0.0);
  std::vector<SymmetricTensor<2, 3>> integral(n_layers);
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned() && n_layers > 0)
    {
      fe_values.reinit(cell);
      fe_values[displacement].get_function_symmetric_gradients(solution, eps);
      for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        const double x = fe_values.quadrature_point(q)[axis];
        if (x < edges.front() || x > edges.back())
          continue;
        const auto k = std::min<std::size_t>(
            std::upper_bound(edges.begin(), edges.end(), x) - edges.begin() - 1, n_layers - 1);
        volume[k] += fe_values.JxW(q);
        integral[k] += (stiffness * eps[q]) * fe_values.JxW(q);
      }
    }
  LayerStresses layers;
  for (unsigned int k = 0; k < n_layers; ++k)
  {
    layers.volume.push_back(Utilities::MPI::sum(volume[k], mpi_communicator));
    const SymmetricTensor<2, 3> total = Utilities::MPI::sum(integral[k], mpi_communicator);
    layers.sigma.push_back(layers.volume.back() > 0 ? total / layers.volume.back()
                                                    : SymmetricTensor<2, 3>());
  }
  return layers;
}

// ------------------------------------------------------------------------------------------
// Output (step-40): one .vtu per rank, a .pvtu per cycle and a .pvd over cycles whose times are
// physical seconds, as in the DEM output, so that both open together in ParaView.
void ElasticProblem::output_results(const std::filesystem::path& output_dir,
                                    const unsigned int cycle, const double time)
{
  TimerOutput::Scope t(computing_timer, "output results");
  DataOut<3> data_out;
  data_out.attach_dof_handler(dof_handler);
  const std::vector<std::string> names(3, "displacement");
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> interpretation(
      3, DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(solution, names, DataOut<3>::type_dof_data, interpretation);
  const StrainStressPostprocessor postprocessor(stiffness);
  data_out.add_data_vector(solution, postprocessor);
  Vector<float> subdomain(triangulation.n_active_cells());
  for (unsigned int i = 0; i < subdomain.size(); ++i)
    subdomain(i) = triangulation.locally_owned_subdomain();
  data_out.add_data_vector(subdomain, "subdomain");
  std::vector<Vector<float>> fields(cell_outputs.size(), Vector<float>(subdomain.size()));
  for (std::size_t k = 0; k < cell_outputs.size(); ++k)
  {
    for (const auto& cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        fields[k](cell->active_cell_index()) = float(cell_outputs[k].second(cell->center()));
    data_out.add_data_vector(fields[k], cell_outputs[k].first);
  }
  data_out.build_patches(mapping, fe.degree);

  const std::string pvtu = data_out.write_vtu_with_pvtu_record(
      output_dir.string() + "/", prm.base_name, cycle, mpi_communicator, 4);
  pvtu_records.emplace_back(time, pvtu);
  if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
  {
    dem::OutputFile pvd(output_dir / (prm.base_name + ".pvd")); // failures name file, reason
    DataOutBase::write_pvd_record(pvd, pvtu_records);
    pvd.close();
  }
}

} // namespace dembridge::fem
