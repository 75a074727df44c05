#include "python/model_bindings.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/run_explicit.h"
#include <filesystem>
#include <memory>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;
namespace fs = std::filesystem;

namespace dembridge::python
{
std::string one_line_message(const std::exception& e)
{
  return app::one_line(e.what());
}

void register_case_error(py::module_& m)
{
  py::register_exception<CaseError>(m, "CaseError", PyExc_ValueError);
}

namespace
{
/// The working directory at a case file's folder while it lives (paths inside a case, such as
/// particle files and meshes, are relative to it), as `dembridge run` does.
class InCaseFolder
{
public:
  explicit InCaseFolder(const std::string& case_file) : previous_(fs::current_path())
  {
    fs::current_path(fs::absolute(case_file).parent_path());
  }
  ~InCaseFolder() { fs::current_path(previous_); }

private:
  fs::path previous_;
};

/// A run's observer that writes nothing: Model.run() gives the state, not files.
class SilentObserver : public dem::RunObserver
{
};

/// A DEM case built and stepped in the explicit solver.
class Model
{
public:
  Model(const std::string& case_file, const std::vector<std::string>& overrides)
      : case_name_(fs::path(case_file).filename().string())
  {
    // reading names the file or the override itself, as `dembridge run` does
    auto prm = rethrow_as_case_error([&] { return app::read_case(case_file, overrides); });
    with_case_name(
        [&]
        {
          if (prm->get("Mode") != "dem")
            throw dem::InputError("Mode: " + prm->get("Mode") +
                                  ": dembridge.Model builds DEM cases (Mode = dem); "
                                  "dembridge.run() runs every mode");
          InCaseFolder folder(case_file);
          config_ = app::parse_dem_case(*prm);
          if (config_.run.static_solver)
            throw dem::InputError("Simulation/solver: static: dembridge.Model steps the "
                                  "explicit solver; dembridge.run() runs static cases");
          output_ = app::parse_output_settings(*prm);
          model_ = dem::build_model(config_);
        });
  }

  /// Advances @p n time steps (the last one a record step: energies and bond forces fresh).
  void step(long n)
  {
    if (ran_)
      throw CaseError("Model.step: the model was run to its end by Model.run()");
    if (!solver_)
    {
      solver_ = std::make_unique<dem::ExplicitSolver>(
          model_.particles, model_.bonds, model_.groups, model_.constraints, model_.loads,
          dem::SolverSettings{model_.time_step, config_.run.particle_damping, config_.run.threads,
                              config_.run.mass_damping});
      for (const auto& contribution : model_.contributions)
        solver_->add_contribution(contribution.get());
    }
    for (long k = 0; k < n; ++k)
      solver_->step(k + 1 == n);
  }

  /// Runs the case to its end as `dembridge run` does (the same solver, schedule and stop
  /// criteria; no files): its figures as a dict.
  py::dict run()
  {
    if (solver_ || ran_)
      throw CaseError("Model.run: the model was stepped or run already (build a new Model)");
    ran_ = true;
    dem::RunSchedule schedule;
    schedule.record_interval = output_.history_interval;
    schedule.snapshot_interval = output_.snapshot_interval;
    SilentObserver observer;
    const dem::RunResult r = dem::run_explicit(model_, config_, observer, schedule);
    steps_ = r.steps;
    time_ = r.time;
    py::dict d;
    d["steps"] = r.steps;
    d["simulated_time"] = r.time;
    d["stop_reason"] = r.stop_reason;
    d["energy_balance_error"] = r.energy_balance_error;
    d["unbalanced_force_ratio"] = r.unbalanced_force_ratio;
    if (r.deflection)
      d[py::str(config_.measure.deflection_name)] = *r.deflection;
    if (r.natural_frequency)
      d["natural_frequency"] = *r.natural_frequency;
    d["energy"] = py::dict(
        py::arg("kinetic") = r.energy.kinetic, py::arg("strain") = r.energy.strain,
        py::arg("damping") = r.energy.damping, py::arg("external_work") = r.energy.external,
        py::arg("fracture") = r.energy.fracture);
    return d;
  }

  double time() const { return solver_ ? solver_->time() : time_; }
  long steps() const { return solver_ ? solver_->steps() : steps_; }
  const dem::Model& model() const { return model_; }
  double time_step() const { return model_.time_step; }

private:
  template <typename Work> void with_case_name(Work&& work)
  {
    try
    {
      work();
    }
    catch (const std::exception& e)
    {
      // name the file as the CLI does: the message names the key and the reason
      const std::string what = one_line_message(e);
      throw CaseError(what.rfind(case_name_, 0) == 0 ? what : case_name_ + ": " + what);
    }
  }

  std::string case_name_;
  dem::CaseConfig config_;
  app::OutputSettings output_;
  dem::Model model_;
  std::unique_ptr<dem::ExplicitSolver> solver_;
  bool ran_ = false;
  long steps_ = 0;
  double time_ = 0;
};

/// A read-only NumPy view of @p data (rows of @p columns values) kept alive by @p owner.
template <typename T>
py::array view(const T* data, std::size_t rows, std::size_t columns, const py::object& owner)
{
  std::vector<py::ssize_t> shape{py::ssize_t(rows)}, strides{py::ssize_t(columns * sizeof(T))};
  if (columns > 1)
  {
    shape.push_back(py::ssize_t(columns));
    strides.push_back(sizeof(T));
  }
  py::array a(py::dtype::of<T>(), shape, strides, data, owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

py::array vec3_view(const std::vector<dem::Vec3>& v, const py::object& owner)
{
  static_assert(sizeof(dem::Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
  return view(v.empty() ? nullptr : v.front().data(), v.size(), 3, owner);
}

template <typename T> py::array scalar_view(const std::vector<T>& v, const py::object& owner)
{
  return view(v.data(), v.size(), 1, owner);
}

const dem::Model& of(const py::object& self)
{
  return self.cast<const Model&>().model();
}

void bind_particle_views(py::class_<Model>& c)
{
  c.def_property_readonly(
       "positions", [](py::object s) { return vec3_view(of(s).particles.position, s); },
       "(N, 3) m, a view of the model's positions")
      .def_property_readonly(
          "reference_positions",
          [](py::object s) { return vec3_view(of(s).particles.reference_position, s); },
          "(N, 3) m, where the particles were when their bonds formed")
      .def_property_readonly(
          "velocities", [](py::object s) { return vec3_view(of(s).particles.velocity, s); },
          "(N, 3) m/s (at the half step)")
      .def_property_readonly(
          "angular_velocities",
          [](py::object s) { return vec3_view(of(s).particles.angular_velocity, s); },
          "(N, 3) rad/s (at the half step)")
      .def_property_readonly(
          "forces", [](py::object s) { return vec3_view(of(s).particles.force, s); },
          "(N, 3) N, each particle's resultant at the last step")
      .def_property_readonly(
          "torques", [](py::object s) { return vec3_view(of(s).particles.torque, s); },
          "(N, 3) N m")
      .def_property_readonly(
          "radii", [](py::object s) { return scalar_view(of(s).particles.radius, s); }, "(N,) m")
      .def_property_readonly(
          "masses", [](py::object s) { return scalar_view(of(s).particles.mass, s); }, "(N,) kg")
      .def_property_readonly(
          "ids", [](py::object s) { return scalar_view(of(s).particles.id, s); },
          "(N,) the particles' ids as the output files show them (the store is in spatial "
          "order)")
      .def_property_readonly(
          "displacements",
          [](py::object s)
          {
            const auto& p = of(s).particles;
            py::array_t<double> u({py::ssize_t(p.size()), py::ssize_t(3)});
            auto w = u.mutable_unchecked<2>();
            for (std::size_t i = 0; i < p.size(); ++i)
              for (int k = 0; k < 3; ++k)
                w(py::ssize_t(i), k) = p.position[i][k] - p.reference_position[i][k];
            return u;
          },
          "(N, 3) m, positions - reference_positions (a new array)")
      .def(
          "stresses",
          [](const Model& m)
          {
            const auto sigma = dem::particle_stresses(m.model().particles, m.model().bonds).sigma;
            py::array_t<double> out({py::ssize_t(sigma.size()), py::ssize_t(3), py::ssize_t(3)});
            auto w = out.mutable_unchecked<3>();
            for (std::size_t i = 0; i < sigma.size(); ++i)
              for (int r = 0; r < 3; ++r)
                for (int k = 0; k < 3; ++k)
                  w(py::ssize_t(i), r, k) = sigma[i](r, k);
            return out;
          },
          "(N, 3, 3) Pa: each particle's stress from its bonds (thesis eq. 62), a new array");
}

void bind_bond_views(py::class_<Model>& c)
{
  c.def_property_readonly(
       "bond_ends",
       [](const Model& m)
       {
         const auto& b = m.model().bonds;
         py::array_t<std::int32_t> ends({py::ssize_t(b.size()), py::ssize_t(2)});
         auto w = ends.mutable_unchecked<2>();
         for (std::size_t k = 0; k < b.size(); ++k)
         {
           w(py::ssize_t(k), 0) = b.a[k];
           w(py::ssize_t(k), 1) = b.b[k];
         }
         return ends;
       },
       "(M, 2) the bonds' particles, as row indices into the particle arrays (a new array)")
      .def_property_readonly(
          "bond_states",
          [](py::object s)
          {
            static_assert(sizeof(dem::BondState) == 1);
            const auto& st = of(s).bonds.state;
            return view(reinterpret_cast<const std::uint8_t*>(st.data()), st.size(), 1, s);
          },
          "(M,) uint8: 0 intact, 1 softening, 2 broken (a view)")
      .def_property_readonly(
          "bond_damage", [](py::object s) { return scalar_view(of(s).bonds.damage, s); },
          "(M,) the damage D in [0, 1] (a view)")
      .def_property_readonly(
          "bond_forces", [](py::object s) { return vec3_view(of(s).bonds.force, s); },
          "(M, 3) N, each bond's contact force on its second particle, fresh after a record "
          "step (the last of each step() call)");
}
} // namespace

void bind_model(py::module_& m)
{
  py::class_<Model> c(m, "Model",
                      "A DEM case built as `dembridge run` builds it, stepped "
                      "from Python; its state as NumPy arrays");
  c.def(py::init<const std::string&, const std::vector<std::string>&>(), py::arg("case_file"),
        py::arg("overrides"))
      .def("step", &Model::step, py::arg("n") = 1, "Advances n explicit time steps")
      .def("run", &Model::run, "Runs the case to its end as `dembridge run` does (no files)")
      .def_property_readonly("time", &Model::time, "s, the simulated time")
      .def_property_readonly("steps", &Model::steps)
      .def_property_readonly("time_step", &Model::time_step, "s")
      .def_property_readonly("n_particles",
                             [](const Model& s) { return s.model().particles.size(); })
      .def_property_readonly("n_bonds", [](const Model& s) { return s.model().bonds.size(); });
  bind_particle_views(c);
  bind_bond_views(c);
}
} // namespace dembridge::python
