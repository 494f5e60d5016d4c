#ifndef igabde_scene_step_results_h
#define igabde_scene_step_results_h

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_stage.h>

#include <igabde/scene/load_controller.h>
#include <igabde/scene/parameters.h>
#include <igabde/scene/run_record.h>

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief The contact solver's figures of a load step (@p outcome of the
     * LoadController; @p algorithm is Contact/Algorithm) into @p record.
     */
    template <int dim>
    void
    record_contact_outcome(const typename LoadController<dim>::Outcome &outcome,
                           const contact::Algorithm algorithm,
                           StepRecord              &record);

    /**
     * @brief Refuses a displacement of load step @p step that is not finite:
     * overflow or underflow (a load factor of 1e308, E = 1e-308) gives
     * inf/NaN without any solver noticing, and is never reported.
     */
    template <int dim>
    void
    check_finite_displacements(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::vector<Vector<double>>                             &u,
      const unsigned int                                             step);

    /// The first body that holds @p x (bodies.size() if none).
    template <int dim>
    unsigned int
    body_holding(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const Point<dim>                                              &x);

    /// The @p dim values @p x (a point as the parameters read it) as a
    /// point.
    template <int dim>
    Point<dim>
    point_of(const std::vector<double> &x);

    /**
     * @brief Refuses (input error) a probe point of the scene that lies in
     * no body, before anything is solved.
     */
    template <int dim>
    void
    check_probe_points(
      const AllParameters                                           &parameters,
      const std::string                                             &scene_file,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies);

  } // namespace scene
} // namespace igabde

#endif
