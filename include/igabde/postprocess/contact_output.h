#ifndef igabde_postprocess_contact_output_h
#define igabde_postprocess_contact_output_h

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_stage.h>

#include <deal.II/lac/vector.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace postprocess
  {
    /**
     * @brief The contact pressure recovered from Body 1's stress field at
     * each pair: -n . sigma(u_h) . n with the pair's normal n (compression
     * positive, Pa), beside the pair pressure p_n / area that the contact
     * solution gives. It is evaluated at the point of Body 1's contact
     * face (the patch faces @p faces) closest to the pair's point: a
     * weighted-gap pair's point is a weighted mean over its support, off a
     * curved face or, with quadratic Lagrange weights, just past a face's
     * side. Where the stress cannot be evaluated at that point (a Lagrange
     * face's projection, which is approximate), the face's sample point
     * nearest to the pair is used.
     */
    template <int dim>
    std::vector<double>
    recovered_pressures(const discretization::Body<dim>               &body1,
                        const std::vector<dealii::types::boundary_id> &faces,
                        const dealii::Vector<double>                  &u1,
                        const std::vector<contact::PairState<dim>>    &pairs);

    /**
     * @brief Writes the pairs of a load step as a CSV table (full
     * precision): pair, x, y[, z], area, gap, p_n[, p_t1[, p_t2]],
     * pressure, recovered_pressure (@p recovered), [slip_t1[, slip_t2]],
     * status.
     */
    template <int dim>
    void
    write_pair_csv(const std::vector<contact::PairState<dim>> &pairs,
                   const std::vector<double>                  &recovered,
                   const std::string                          &filename);

    /**
     * @brief Writes the pairs of a load step as a VTU point cloud (deal.II's
     * DataOutBase, binary): pressure, recovered_pressure (@p recovered),
     * gap, status (0 open, 1 stick, 2 slip, 3 closed), the contact force on
     * Body 1 and, with friction, the slip.
     */
    template <int dim>
    void
    write_pair_vtu(const std::vector<contact::PairState<dim>> &pairs,
                   const std::vector<double>                  &recovered,
                   const std::string                          &filename);
  } // namespace postprocess
} // namespace igabde

#endif
