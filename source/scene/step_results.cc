#include <igabde/base/utilities.h>

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/body_description.h>

#include <igabde/elasticity/stress_measures.h>

#include <igabde/postprocess/contact_checks.h>
#include <igabde/postprocess/contact_output.h>
#include <igabde/postprocess/fclib_writer.h>
#include <igabde/scene/step_results.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <tuple>

namespace igabde
{
  namespace scene
  {
    template <int dim>
    void
    record_contact_outcome(const typename LoadController<dim>::Outcome &outcome,
                           const contact::Algorithm algorithm,
                           StepRecord              &record)
    {
      const auto &last         = outcome.last;
      record.contact           = true;
      record.newton_iterations = outcome.iterations;
      record.contact_solves    = outcome.contact_solves;
      record.step_cuts         = outcome.cuts;
      record.residual          = last.residual;
      record.n_open            = last.n_open;
      record.n_stick           = last.n_stick;
      record.n_slip            = last.n_slip;
      record.n_closed          = last.n_closed;
      if (algorithm != contact::Algorithm::bde)
        record.max_penetration = last.max_penetration;
      if (algorithm == contact::Algorithm::augmented_lagrange)
        record.multiplier_updates = last.updates;
      record.residual_history  = last.residual_history;
      record.krylov_iterations = last.linear_iterations;
      if (outcome.success)
        record.condition_check_max_violation =
          last.condition_check_max_violation;
      else
        {
          // The failed step's figures stay next to the finished steps.
          record.failed    = true;
          record.diagnosis = last.diagnosis;
          record.advice =
            last.advice.empty() ?
              "Try more load steps (Load path/Number of steps) or step cuts "
              "(Contact/Max step cuts), a larger Contact/Max iterations, or "
              "check that the bodies are supported." :
              last.advice + ".";
        }
    }



    template <int dim>
    void
    check_finite_displacements(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::vector<Vector<double>>                             &u,
      const unsigned int                                             step)
    {
      for (unsigned int b = 0; b < bodies.size(); ++b)
        AssertThrow(std::all_of(u[b].begin(),
                                u[b].end(),
                                [](const double v) {
                                  return std::isfinite(v);
                                }),
                    ExcMessage("load step " + std::to_string(step) +
                               ": the displacement of " + bodies[b]->name() +
                               " is not finite (overflow: check the load and "
                               "displacement factors, the loads and Young's "
                               "modulus of the scene)."));
    }



    template <int dim>
    unsigned int
    body_holding(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const Point<dim>                                              &x)
    {
      for (unsigned int k = 0; k < bodies.size(); ++k)
        if (bodies[k]->contains(x))
          return k;
      return bodies.size();
    }



    template <int dim>
    Point<dim>
    point_of(const std::vector<double> &x)
    {
      AssertDimension(x.size(), dim);
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = x[d];
      return p;
    }



    template <int dim>
    void
    check_probe_points(
      const AllParameters                                           &parameters,
      const std::string                                             &scene_file,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies)
    {
      for (const ProbePoint &probe : parameters.probes)
        {
          std::ostringstream item;
          item << probe.name << ":";
          for (unsigned int d = 0; d < dim; ++d)
            item << (d > 0 ? ", " : " ") << probe.location[d];
          AssertThrow(body_holding<dim>(bodies, point_of<dim>(probe.location)) <
                        bodies.size(),
                      base::ExcInput(
                        scene_file + ": Probe points: '" + item.str() +
                        "' lies in no body; give a point inside one of "
                        "the deformable bodies."));
        }
    }



    template void
    record_contact_outcome<2>(const LoadController<2>::Outcome &,
                              const contact::Algorithm,
                              StepRecord &);
    template void
    record_contact_outcome<3>(const LoadController<3>::Outcome &,
                              const contact::Algorithm,
                              StepRecord &);
    template void
    check_finite_displacements<2>(
      const std::vector<std::unique_ptr<discretization::Body<2>>> &,
      const std::vector<Vector<double>> &,
      const unsigned int);
    template void
    check_finite_displacements<3>(
      const std::vector<std::unique_ptr<discretization::Body<3>>> &,
      const std::vector<Vector<double>> &,
      const unsigned int);
    template unsigned int
    body_holding<2>(
      const std::vector<std::unique_ptr<discretization::Body<2>>> &,
      const Point<2> &);
    template unsigned int
    body_holding<3>(
      const std::vector<std::unique_ptr<discretization::Body<3>>> &,
      const Point<3> &);
    template Point<2>
    point_of<2>(const std::vector<double> &);
    template Point<3>
    point_of<3>(const std::vector<double> &);
    template void
    check_probe_points<2>(
      const AllParameters &,
      const std::string &,
      const std::vector<std::unique_ptr<discretization::Body<2>>> &);
    template void
    check_probe_points<3>(
      const AllParameters &,
      const std::string &,
      const std::vector<std::unique_ptr<discretization::Body<3>>> &);
  } // namespace scene
} // namespace igabde
