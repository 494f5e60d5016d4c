#ifndef igabde_scene_step_results_h
#define igabde_scene_step_results_h

#include <igabde/base/files.h>

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

    /**
     * @brief The contact resultant and support reaction of every body (and
     * the obstacle's contact force) at the end of a step with displacements
     * @p u and load factors @p factors, into @p record; @p stage is nullptr
     * without contact. With contact, the step's resultant on Body 1 goes to
     * @p log, its components below 1e-10 of its length (round-off) as 0.
     */
    template <int dim>
    void
    record_forces(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const contact::ContactStage<dim>                              *stage,
      const std::vector<Vector<double>>                             &u,
      const std::vector<double>                                     &factors,
      StepRecord                                                    &record,
      std::ostream                                                  &log);

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

    /**
     * @brief The model's range at the end of a load step: the largest
     * strain of the bodies and, with @p stage, the largest tangential
     * displacement between paired points in pair spacings go to @p record;
     * the first step past a strain of 0.1 (small-strain, linear elastic)
     * or past one pair spacing (pairs formed once in the reference
     * configuration, small sliding) adds a warning to @p warnings and a
     * line to @p log.
     */
    template <int dim>
    void
    check_model_range(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const contact::ContactStage<dim>                              *stage,
      const std::vector<Vector<double>>                             &u,
      StepRecord                                                    &record,
      std::vector<std::string>                                      &warnings,
      std::ostream                                                  &log);

    /**
     * @brief The files of load step @p step in @p directory: the pair table
     * contact-NNNN.csv of @p pairs (nullptr without contact; recovered
     * pressures on Body 1's patch faces @p slave_faces) and, with
     * @p write_vtu, the pairs' and the bodies' VTU files, whose names
     * @p pvd_records gains (one series per body, then one for the pairs);
     * write_pvd_series() writes the series. The files are written by
     * @p writer's threads while the run goes on, after the previous step's
     * (this call waits for them first).
     *
     * Collective in spirit on @p n_ranks ranks: every rank calls it, rank
     * @p rank writes piece @p rank of each body's VTU (with more than one
     * rank and cell: solution-NAME-NNNN.R.vtu, and rank 0 the record
     * solution-NAME-NNNN.pvtu that names them); rank 0 alone writes the
     * pairs' files. No rank waits for another.
     */
    template <int dim>
    void
    write_step_output(
      const std::string                                             &directory,
      const bool                                                     write_vtu,
      const unsigned int                                             step,
      const unsigned int                                             rank,
      const unsigned int                                             n_ranks,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::vector<Vector<double>>                             &u,
      const std::vector<contact::PairState<dim>>                    *pairs,
      const std::vector<types::boundary_id>                    &slave_faces,
      std::vector<std::vector<std::pair<double, std::string>>> &pvd_records,
      base::BackgroundWriter                                   &writer);

    /**
     * @brief Output/FCLIB export: the condensed contact problem @p stage
     * solved last (the step's W, q, mu; the tangential rows are the
     * step's increments) with its solution p, u = W p + q, written as the
     * FCLIB local problem fclib-NNNN.hdf5 of @p step in @p directory. A
     * problem that is not an FCLIB local problem (no W: the full path;
     * floating bodies) is left out with a line in @p log.
     */
    template <int dim>
    void
    write_fclib_step(const std::string                &directory,
                     const unsigned int                step,
                     const contact::ContactStage<dim> &stage,
                     std::ostream                     &log);

    /**
     * @brief Each body's PVD series solution-<name>.pvd and, when it has
     * entries, the pairs' contact.pvd, from @p pvd_records (see
     * write_step_output()).
     */
    template <int dim>
    void
    write_pvd_series(
      const std::string                                             &directory,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::vector<std::vector<std::pair<double, std::string>>>
        &pvd_records);

    /**
     * @brief The results of the last load step: error norms against the
     * exact solution, the contact checks the scene asks for (uniform
     * pressure, Hertz) on @p pairs (nullptr without contact), then the
     * displacement and stress at every probe point. Each goes to @p summary
     * (checks, warnings, points, point_stresses) and a line to @p log.
     */
    template <int dim>
    void
    evaluate_final_results(
      const AllParameters                                           &parameters,
      const std::string                                             &scene_file,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::optional<discretization::ExactSolution<dim>>       &exact,
      const std::vector<contact::PairState<dim>>                    *pairs,
      const std::vector<Vector<double>>                             &u,
      const std::vector<double>                                     &factors,
      ConditionalOStream                                            &log,
      RunSummary                                                    &summary);
  } // namespace scene
} // namespace igabde

#endif
