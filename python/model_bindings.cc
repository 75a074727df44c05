#include "python/model_bindings.h"
#include "app/cli/case_folder.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "app/output/contact_output.h"
#include "app/output/dem_figures.h"
#include "app/output/dem_history.h"
#include "app/output/result_warnings.h"
#include "app/runs/dem_static_run.h"
#include "dem/measurements/particle_stress.h"
#include "dem/model/model.h"
#include "dem/solvers/run_explicit.h"
#include <filesystem>
#include <iomanip>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <sstream>

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
/// A run's observer that keeps history.csv's rows (the command line's columns and format) in
/// memory and writes no file.
class HistoryObserver : public dem::RunObserver
{
public:
  HistoryObserver(std::ostream& history, const dem::Model& model)
      : history_(history), model_(model), contacts_(model)
  {
  }
  void on_record(const dem::ExplicitSolver& s) override
  {
    app::history_row(history_,
                     {s.steps(), s.time(), s.energy(), s.max_speed(), s.unbalanced_force_ratio(),
                      s.n_broken_bonds()},
                     model_.particles, s.groups(), contacts_);
  }

private:
  std::ostream& history_;
  const dem::Model& model_;
  const app::ContactOutput contacts_;
};

/// JSON text (what the library's summary functions write) as a Python object.
py::object from_json(const std::string& text)
{
  return py::module_::import("json").attr("loads")(text);
}

/// A DEM case built as `dembridge run` builds it, then stepped in the explicit solver, solved by
/// the static solver, or run to its end as the command line runs it.
class Model
{
public:
  Model(const std::string& case_file, const std::vector<std::string>& overrides)
      : case_file_(fs::absolute(case_file).string())
  {
    // reading names the file or the override itself, as `dembridge run` does
    auto prm = rethrow_as_case_error([&] { return app::read_case(case_file, overrides); });
    in_the_case_folder(
        [&]
        {
          if (prm->get("Mode") != "dem")
            throw dem::InputError("Mode: " + prm->get("Mode") +
                                  ": dembridge.Model builds DEM cases (Mode = dem); "
                                  "dembridge.run() runs every mode");
          config_ = app::parse_dem_case(*prm);
          output_ = app::parse_output_settings(*prm);
          static_settings_ = app::static_solver_settings(*prm);
          bond_model_ = prm->get({"Bonds"}, "model");
          model_ = dem::build_model(config_);
        });
  }

  /// Advances @p n time steps (the last one a record step: energies and bond forces fresh).
  void step(long n)
  {
    if (ran_ || static_run_)
      throw CaseError("Model.step: the model was run or solved already (build a new Model)");
    if (!solver_)
      solver_ = dem::make_explicit_solver(model_, config_);
    for (long k = 0; k < n; ++k)
      solver_->step(k + 1 == n);
  }

  /// One static solve (the command line's static solver and linear solver settings) of the
  /// loads at @p time (none: the final state); its solver figures as JSON.
  std::string solve_static(std::optional<double> time)
  {
    if (solver_ || ran_)
      throw CaseError("Model.solve_static: the model was stepped or run already (build a new "
                      "Model)");
    dem::StaticSettings settings = static_settings_;
    if (time)
      settings.time = *time;
    in_the_case_folder(
        [&]
        {
          const dem::StaticResult st = dem::solve_static(model_, settings);
          dem::record_bond_forces(model_.particles, model_.bonds);
          static_run_ = app::StaticRun{st, st.assembly_seconds + st.solve_seconds, 1};
        });
    nlohmann::json j;
    app::add_static_run_figures(j, model_, config_, *static_run_);
    return j["solver"].dump();
  }

  /// Runs the case to its end as `dembridge run` does (the same solver, load steps, schedule and
  /// stop criteria; no files); its figures as JSON (figures()).
  std::string run()
  {
    if (solver_ || ran_ || static_run_)
      throw CaseError("Model.run: the model was stepped, solved or run already (build a new "
                      "Model)");
    ran_ = true;
    std::ostringstream history;
    const app::ContactOutput contacts(model_);
    history << app::history_header(model_, contacts) << std::setprecision(10);
    in_the_case_folder(
        [&]
        {
          if (config_.run.static_solver)
          {
            const auto record = [&](int k, double t, const dem::StaticResult&)
            {
              app::history_row(history, app::static_step_record(model_, k, t), model_.particles,
                               model_.groups, contacts);
            };
            static_run_ = app::solve_static_load_steps(model_, config_, output_.load_steps,
                                                       static_settings_, record);
            return;
          }
          app::check_explicit_end_time(config_.run.end_time, config_.particles.save_file);
          dem::RunSchedule schedule;
          schedule.record_interval = output_.history_interval;
          schedule.snapshot_interval = output_.snapshot_interval;
          HistoryObserver observer(history, model_);
          explicit_run_ = dem::run_explicit(model_, config_, observer, schedule);
        });
    history_ = history.str();
    return figures();
  }

  /// summary.json's figures of the model's current state (app/runs/dem_static_run.h), computed
  /// by the command line's own code: after run() those of `dembridge run` (an explicit run's
  /// moduli fitted to its load history aside: the Model keeps none).
  std::string figures() const
  {
    nlohmann::json j;
    j["warnings"] = nlohmann::json::array();
    app::check_bond_coverage(model_.particles, model_.bonds.size(), config_, j);
    dem::RunResult r;
    if (static_run_)
      r = app::add_static_run_figures(j, model_, config_, *static_run_);
    else if (explicit_run_)
      r = add_explicit_figures(j, *explicit_run_);
    else
    {
      r.stop_reason = solver_ ? "stepped" : "not run";
      r.time = time();
      r.steps = steps();
      if (!config_.measure.deflection_group.empty())
      {
        const auto& g = model_.groups[model_.group_index(config_.measure.deflection_group,
                                                         "Measurements/deflection group")];
        r.deflection_vector = dem::mean_displacement(model_.particles, g);
        r.deflection = r.deflection_vector.dot(config_.measure.deflection_direction.normalized());
      }
    }
    const dem::ParticleStresses stresses = dem::particle_stresses(model_.particles, model_.bonds);
    app::add_final_state_figures(j, model_, config_, bond_model_, r, stresses, {},
                                 broken_bonds() > 0);
    return j.dump();
  }

  double time() const
  {
    return solver_ ? solver_->time() : explicit_run_ ? explicit_run_->time : 0;
  }
  long steps() const
  {
    return solver_ ? solver_->steps() : explicit_run_ ? explicit_run_->steps : 0;
  }
  const dem::Model& model() const { return model_; }
  const std::string& history() const { return history_; }
  double time_step() const { return model_.time_step; }
  bool static_case() const { return config_.run.static_solver; }

private:
  /// @p work in the case file's folder, its errors naming the file as the command line's do.
  template <typename Work> void in_the_case_folder(Work&& work) const
  {
    rethrow_as_case_error([&] { app::in_case_folder(case_file_, work); });
  }

  long broken_bonds() const
  {
    long n = 0;
    for (const auto state : model_.bonds.state)
      n += state == dem::BondState::broken;
    return n;
  }

  /// The explicit run's own figures, under summary.json's keys.
  dem::RunResult add_explicit_figures(nlohmann::json& j, const dem::RunResult& r) const
  {
    j["solver"] = {{"type", "explicit"}};
    j["time_step"] = model_.time_step;
    j["steps"] = r.steps;
    j["simulated_time"] = r.time;
    app::add_energy_figures(j, r);
    return r;
  }

  std::string case_file_;
  dem::CaseConfig config_;
  app::OutputSettings output_;
  dem::StaticSettings static_settings_;
  std::string bond_model_;
  dem::Model model_;
  std::unique_ptr<dem::ExplicitSolver> solver_;
  std::optional<app::StaticRun> static_run_;
  std::optional<dem::RunResult> explicit_run_;
  std::string history_; ///< history.csv's text of run()
  bool ran_ = false;
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
                      "A DEM case built as `dembridge run` builds it, stepped or solved "
                      "from Python; its state as NumPy arrays");
  c.def(py::init<const std::string&, const std::vector<std::string>&>(), py::arg("case_file"),
        py::arg("overrides"), py::call_guard<py::gil_scoped_release>())
      .def("step", &Model::step, py::arg("n") = 1, py::call_guard<py::gil_scoped_release>(),
           "Advances n explicit time steps")
      .def(
          "solve_static",
          [](Model& model, std::optional<double> time)
          {
            std::string text;
            {
              py::gil_scoped_release unlocked;
              text = model.solve_static(time);
            }
            return from_json(text);
          },
          py::arg("time") = py::none(),
          "One static solve, as the command line's static solver does it, of the loads at "
          "`time` (s; None: the final state); the solver's figures as a dict")
      .def(
          "run",
          [](Model& model)
          {
            std::string text;
            {
              py::gil_scoped_release unlocked;
              text = model.run();
            }
            return from_json(text);
          },
          "Runs the case to its end as `dembridge run` does (no files); summary.json's figures "
          "as a dict")
      .def(
          "figures", [](const Model& model) { return from_json(model.figures()); },
          "summary.json's figures of the model's current state, as a dict")
      .def_property_readonly("history_text", &Model::history,
                             "history.csv's text of run() (the command line's file); empty "
                             "before run()")
      .def_property_readonly("time", &Model::time, "s, the simulated time")
      .def_property_readonly("steps", &Model::steps)
      .def_property_readonly("time_step", &Model::time_step, "s")
      .def_property_readonly("static_case", &Model::static_case,
                             "whether the case asks for the static solver (Simulation/solver)")
      .def_property_readonly("n_particles",
                             [](const Model& s) { return s.model().particles.size(); })
      .def_property_readonly("n_bonds", [](const Model& s) { return s.model().bonds.size(); });
  bind_particle_views(c);
  bind_bond_views(c);
}
} // namespace dembridge::python
